// Timing and measuring one algorithm run the way hsr compare and hsr sweep report it:
// one warm-up run (which also builds what the scene caches, such as the BVH), then
// `repeats` timed runs; the spread of their wall times, and the peak of heap bytes any
// one run allocated beyond what was in use before it.
//
// Repeated timings on a shared machine disagree, so every figure the studies print or
// plot carries its spread, and two figures are ordered only when their ranges do not
// overlap: otherwise they are "within noise" of each other.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "renderer/util/stats.hpp"
#include "studies/allocation_meter.hpp"

namespace hsr::studies {

// The spread of repeated timings of one thing, in whatever unit they were given.
struct Timing {
  double median = 0, min = 0, max = 0;
  // Slowest over fastest; above kBusySpread the runs disagree more than a quiet machine makes them.
  double spread() const { return min > 0 ? max / min : 1; }
};
constexpr double kBusySpread = 1.5;

Timing summarize(std::vector<double> values);

// Which of two timings is faster, judged on their [min, max] ranges: only when one's
// slowest run beats the other's fastest. Overlapping ranges are within noise.
enum class Order { faster, slower, withinNoise };
Order compareTimings(const Timing& a, const Timing& b);

// A median and a 95% confidence interval for it, from samples that vary for reasons
// other than noise too (one frame time per pose of a turning scene): the order
// statistics a sign test puts around the median, so no distribution is assumed. Under
// eight samples the interval is the whole range.
struct Interval {
  double median = 0, low = 0, high = 0;
};
Interval medianWithConfidence(std::vector<double> values);

// A published claim checked on measurements: "held", "did not hold", or "within noise"
// when the measurements cannot tell.
enum class Verdict { held, didNotHold, withinNoise };
const char* verdictText(Verdict verdict);
// "x < bound": held when the whole interval lies below it, did not hold when the whole
// interval lies above it, within noise when it straddles the bound.
Verdict below(const Interval& interval, double bound);
// All of the claims' verdicts together: did not hold if any did not, within noise if any
// could not tell, held only if every one held.
Verdict allOf(const std::vector<Verdict>& verdicts);

// When some timings (in seconds) spread wider than kBusySpread, one line on stderr: how
// many, the widest (named), that the machine was busy, and how to measure again
// (`moreRuns`, an option with a larger value, such as "--repeat 9"). Runs less than
// kNoiseFloor apart are not counted: under half a millisecond, waking the worker threads
// or a timer tick can be the whole difference on a quiet machine. Returns whether it warned.
constexpr double kNoiseFloor = 5e-4;
bool warnIfBusy(const std::vector<std::pair<std::string, Timing>>& timings, const std::string& moreRuns);

template <typename Result>
struct Measured {
  Result result;  // of the last timed run
  std::vector<Stats> runs;      // each timed run's counters and phase times
  std::vector<double> seconds;  // each timed run's wall time
  Timing time;                  // of `seconds`
  std::int64_t peakBytes = 0;
  int repeats = 0;
  const Stats& lastStats() const { return runs.back(); }
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
  for (int repetition = 0; repetition < repeats; ++repetition) {
    measured.result = Result();  // freed before the next run, so its peak is its own
    Stats stats;
    resetHeapPeak();
    const std::int64_t before = heapBytesInUse();
    const auto start = std::chrono::steady_clock::now();
    measured.result = run(stats);
    measured.seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    measured.peakBytes = std::max(measured.peakBytes, heapPeakBytes() - before);
    measured.runs.push_back(std::move(stats));
  }
  measured.time = summarize(measured.seconds);
  measured.repeats = repeats;
  return measured;
}

}  // namespace hsr::studies
