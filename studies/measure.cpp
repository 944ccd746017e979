#include "studies/measure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hsr::studies {

namespace {

double medianOfSorted(const std::vector<double>& sorted) {
  const std::size_t n = sorted.size();
  return n % 2 ? sorted[n / 2] : (sorted[n / 2 - 1] + sorted[n / 2]) / 2;
}

}  // namespace

Timing summarize(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return {medianOfSorted(values), values.front(), values.back()};
}

Order compareTimings(const Timing& a, const Timing& b) {
  if (a.max < b.min) return Order::faster;
  if (b.max < a.min) return Order::slower;
  return Order::withinNoise;
}

Interval medianWithConfidence(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const double n = double(values.size());
  // Ranks k and n - 1 - k hold the median between them with 95% probability (the
  // binomial's normal approximation: k = (n - 1.96 sqrt(n)) / 2, rounded down).
  const auto k = std::size_t(std::max(0.0, std::floor((n - 1.96 * std::sqrt(n)) / 2)));
  return {medianOfSorted(values), values[k], values[values.size() - 1 - k]};
}

Verdict below(const Interval& interval, double bound) {
  if (interval.high < bound) return Verdict::held;
  if (interval.low > bound) return Verdict::didNotHold;
  return Verdict::withinNoise;
}

const char* verdictText(Verdict verdict) {
  switch (verdict) {
    case Verdict::held: return "held";
    case Verdict::didNotHold: return "did not hold";
    case Verdict::withinNoise: return "within noise";
  }
  return "";
}

Verdict allOf(const std::vector<Verdict>& verdicts) {
  if (std::find(verdicts.begin(), verdicts.end(), Verdict::didNotHold) != verdicts.end()) return Verdict::didNotHold;
  if (std::find(verdicts.begin(), verdicts.end(), Verdict::withinNoise) != verdicts.end()) return Verdict::withinNoise;
  return Verdict::held;
}

bool warnIfBusy(const std::vector<std::pair<std::string, Timing>>& timings, const std::string& moreRuns) {
  const std::pair<std::string, Timing>* widest = nullptr;
  int wide = 0;
  for (const auto& named : timings) {
    if (named.second.spread() <= kBusySpread || named.second.max - named.second.min < kNoiseFloor) continue;
    ++wide;
    if (!widest || named.second.spread() > widest->second.spread()) widest = &named;
  }
  if (!widest) return false;
  std::fflush(stdout);  // after what was printed before it, also through a pipe
  std::fprintf(stderr,
               "hsr: warning: %d of %zu timings spread wider than %.1fx between their fastest and slowest run (widest: %s, "
               "%.2fx): something else took the machine's time while measuring (another program, or the machine was "
               "busy), so orders within that spread are noise; measure again on a quiet machine or with more runs (%s)\n",
               wide, timings.size(), kBusySpread, widest->first.c_str(), widest->second.spread(), moreRuns.c_str());
  return true;
}

}  // namespace hsr::studies
