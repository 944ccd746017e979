// Timing and measuring one algorithm run the way hsr compare and hsr sweep report it:
// one warm-up run (which also builds what the scene caches, such as the BVH), then
// `repeats` timed runs; the median and the range of their wall times, and the peak of
// heap bytes any one run allocated beyond what was in use before it.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <utility>
#include <vector>

#include "studies/allocation_meter.hpp"
#include "renderer/stats.hpp"

namespace hsr::studies {

struct Timing {
  double median = 0, min = 0, max = 0;  // seconds
};

inline Timing summarize(std::vector<double> seconds) {
  std::sort(seconds.begin(), seconds.end());
  const std::size_t n = seconds.size();
  const double median = n % 2 ? seconds[n / 2] : (seconds[n / 2 - 1] + seconds[n / 2]) / 2;
  return {median, seconds.front(), seconds.back()};
}

template <typename Result>
struct Measured {
  Result result;  // of the last timed run
  Stats stats;    // of the last timed run
  Timing time;
  std::int64_t peakBytes = 0;
  int repeats = 0;
};

// run(Stats&) -> Result. repeats >= 1.
template <typename Run>
auto measure(int repeats, Run&& run) {
  using Result = decltype(run(std::declval<Stats&>()));
  Measured<Result> measured;
  {
    Stats warmUp;
    measured.result = run(warmUp);
  }
  std::vector<double> seconds;
  for (int repetition = 0; repetition < repeats; ++repetition) {
    measured.result = Result();  // freed before the next run, so its peak is its own
    Stats stats;
    resetHeapPeak();
    const std::int64_t before = heapBytesInUse();
    const auto start = std::chrono::steady_clock::now();
    measured.result = run(stats);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    measured.peakBytes = std::max(measured.peakBytes, heapPeakBytes() - before);
    measured.stats = std::move(stats);
  }
  measured.time = summarize(std::move(seconds));
  measured.repeats = repeats;
  return measured;
}

}  // namespace hsr::studies
