// parallelFor and the threads it keeps between loops (renderer/util/parallel.hpp): every item
// once, loops inside loops, an exception from the caller's share, and the caller's
// floating-point traps in every worker; the time phases spend outside the loops; and a
// frame's buffers, made without a fill and filled on the threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cfenv>
#include <chrono>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "floating_point_traps.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/util/parallel.hpp"
#include "renderer/util/stats.hpp"

namespace hsr {
namespace {

// A frame's buffers are left unfilled where they are allocated and filled by rows on the
// threads: every pixel must still start black, background and infinitely far, also in
// memory an earlier frame left full of other values.
TEST(Parallel, AFrameFilledOnAnyThreadsStartsBlackBackgroundAndInfinitelyFar) {
  for (const auto& [width, height] : {std::pair(1, 1), std::pair(7, 5), std::pair(33, 17), std::pair(640, 3)})
    for (int threads = 1; threads <= 3; ++threads) {
      {
        Frame earlier(width, height, threads);  // its memory is likely the next frame's
        std::fill(earlier.color.begin(), earlier.color.end(), std::uint8_t(77));
        std::fill(earlier.depth.begin(), earlier.depth.end(), 1.5f);
        std::fill(earlier.ids.begin(), earlier.ids.end(), 9u);
      }
      const Frame frame(width, height, threads);
      ASSERT_EQ(frame.pixelCount(), std::size_t(width) * std::size_t(height));
      ASSERT_EQ(frame.color.size(), frame.pixelCount() * 4);
      EXPECT_TRUE(std::all_of(frame.color.begin(), frame.color.end(), [](std::uint8_t c) { return c == 0; }))
          << width << "x" << height << " on " << threads;
      EXPECT_TRUE(std::all_of(frame.ids.begin(), frame.ids.end(), [](std::uint32_t id) { return id == 0; }))
          << width << "x" << height << " on " << threads;
      EXPECT_TRUE(std::all_of(frame.depth.begin(), frame.depth.end(), [](float d) { return d == std::numeric_limits<float>::infinity(); }))
          << width << "x" << height << " on " << threads;
    }
}

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

// A phase's serial time is its time outside parallel loops: a loop inside a loop's body
// counts once, as part of the outer one, and a phase timed inside a loop's body has no
// serial time of its own. Sleeps give lower bounds only, so the bounds below hold on any
// machine however loaded; the Amdahl time is exact arithmetic on the measured times.
TEST(Parallel, APhasesSerialTimeIsItsTimeOutsideParallelLoops) {
  using std::chrono::milliseconds;
  Stats stats;
  {
    PhaseTimer timer(stats, "phase");
    std::this_thread::sleep_for(milliseconds(10));  // serial
    parallelFor(4, 1, [&](std::size_t, int) {       // four items on one thread: 4 x 5 ms in a loop
      parallelFor(2, 2, [&](std::size_t, int) {});  // nested: already inside the outer loop's time
      PhaseTimer inner(stats, "inside a loop");
      std::this_thread::sleep_for(milliseconds(5));
    });
  }
  const double total = stats.seconds("phase"), serial = stats.serialTime("phase").serial;
  EXPECT_GE(serial, 0.010);
  EXPECT_LE(serial, total - 0.020);
  // The loop ran on one worker; on 16 cores its four items would take a quarter of it.
  EXPECT_NEAR(stats.serialTime("phase").onAmdahlCores - serial, (total - serial) / 4, 1e-6);
  EXPECT_GE(stats.seconds("inside a loop"), 0.020);
  EXPECT_EQ(stats.serialTime("inside a loop").serial, 0.0);
  EXPECT_EQ(ParallelTime::insideLoop(), false);
  // --stats prints each phase's serial time, and a pass's time on 16 cores.
  Stats pass;
  { PhaseTimer timer(pass, "pass: visibility"); }
  const std::string report = pass.report();
  EXPECT_NE(report.find("pass: visibility serial time"), std::string::npos) << report;
  EXPECT_NE(report.find("pass: visibility on 16 cores (Amdahl) time"), std::string::npos) << report;
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
