// parallelFor and the threads it keeps between loops (renderer/util/parallel.hpp): every item
// once, loops inside loops, an exception from the caller's share, and the caller's
// floating-point traps in every worker.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cfenv>
#include <chrono>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

#include "floating_point_traps.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr {
namespace {

TEST(Parallel, EveryItemOnceInLoopAfterLoop) {
  for (int loop = 0; loop < 2000; ++loop) {
    const std::size_t count = 1 + std::size_t(loop % 97);
    const int threads = 1 + loop % 3;
    std::vector<int> seen(count, 0), workerOf(count, -1);
    parallelFor(count, threads, [&](std::size_t item, int worker) {
      ++seen[item];
      workerOf[item] = worker;
    });
    ASSERT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(count)) << "loop " << loop;
    for (const int worker : workerOf) ASSERT_TRUE(worker >= 0 && worker < threads) << "loop " << loop;
  }
}

TEST(Parallel, LoopsInsideALoopsBodyRunWhileThePoolIsBusy) {
  std::vector<std::int64_t> sums(8, 0);
  parallelFor(sums.size(), 2, [&](std::size_t outer, int) {
    std::vector<std::int64_t> parts(100, 0);
    parallelFor(parts.size(), 2, [&](std::size_t inner, int) { parts[inner] = std::int64_t(outer * 1000 + inner); });
    sums[outer] = std::accumulate(parts.begin(), parts.end(), std::int64_t{0});
  });
  for (std::size_t outer = 0; outer < sums.size(); ++outer) EXPECT_EQ(sums[outer], std::int64_t(outer * 100000 + 4950));
}

TEST(Parallel, AnExceptionFromTheCallersShareWaitsForTheHelpers) {
  // The helper waits in its items until the caller has taken one, so the caller's
  // share is never empty.
  std::atomic<bool> callerStarted = false;
  EXPECT_THROW(parallelFor(64, 2,
                           [&](std::size_t, int worker) {
                             if (worker == 0) {
                               callerStarted = true;
                               throw std::runtime_error("the caller's item failed");
                             }
                             const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(10);
                             while (!callerStarted && std::chrono::steady_clock::now() < giveUp) std::this_thread::yield();
                           }),
               std::runtime_error);
  // The pool is free again, and runs the next loop whole.
  std::atomic<int> items = 0;
  parallelFor(64, 2, [&](std::size_t, int) { ++items; });
  EXPECT_EQ(items, 64);
}

TEST(Parallel, WorkersRunWithTheCallersFloatingPointTraps) {
  // Threads kept from a loop run untrapped must take up traps enabled after they started,
  // and drop them again: as threads started by the caller would. Each of the two items
  // waits for the other, so both workers run one.
  const auto trapsSeen = [] {
    std::vector<int> traps(2, -1);
    std::atomic<int> arrived = 0;
    parallelFor(2, 2, [&](std::size_t, int worker) {
      traps[std::size_t(worker)] = fegetexcept();
      ++arrived;
      const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (arrived < 2 && std::chrono::steady_clock::now() < giveUp) std::this_thread::yield();
    });
    return traps;
  };
  {
    const test::TrappedFloatingPoint none(0);
    EXPECT_EQ(trapsSeen(), std::vector<int>({0, 0}));
  }
  {
    const test::TrappedFloatingPoint trapped;
    EXPECT_EQ(trapsSeen(), std::vector<int>({test::kTrappedExceptions, test::kTrappedExceptions}));
  }
  {
    const test::TrappedFloatingPoint none(0);
    EXPECT_EQ(trapsSeen(), std::vector<int>({0, 0}));
  }
}

TEST(FloatingPointTraps, OnInEveryTestExactlyWhereTheBuildAsks) {
  // CI checks the traps in the sanitizer build only (scripts/test.sh): were the build's
  // HSR_TRAP_FLOATING_POINT lost on the way to test_main.cpp, every trapping test there
  // would pass untrapped, and nothing else would say so.
#ifdef HSR_TRAP_FLOATING_POINT
  EXPECT_EQ(fegetexcept() & test::kTrappedExceptions, test::kTrappedExceptions);
#else
  EXPECT_EQ(fegetexcept(), 0);  // the release build runs as it is timed, untrapped
#endif
}

}  // namespace
}  // namespace hsr
