// How the studies read repeated timings: the spread of one configuration's runs, which
// of two configurations is faster (only when their ranges do not overlap), the Pareto
// front decided on those ranges, a claim's verdict on a confidence interval, the split
// of a render's time into the algorithm's own and the shared passes, and the warning
// that the machine was busy.
#include <gtest/gtest.h>

#include "studies/measure.hpp"
#include "studies/results.hpp"

namespace hsr::studies {
namespace {

TEST(Timing, SummarizesTheMedianAndRangeWhateverTheOrder) {
  const Timing odd = summarize({5, 1, 4, 2, 3});
  EXPECT_EQ(odd.median, 3);
  EXPECT_EQ(odd.min, 1);
  EXPECT_EQ(odd.max, 5);
  EXPECT_EQ(odd.spread(), 5);
  const Timing even = summarize({4, 1, 3, 2});
  EXPECT_EQ(even.median, 2.5);
  const Timing one = summarize({7});
  EXPECT_EQ(one.median, 7);
  EXPECT_EQ(one.spread(), 1);
}

TEST(Timing, OneIsFasterOnlyWhenItsSlowestRunBeatsTheOthersFastest) {
  const Timing a = summarize({1.0, 1.1, 1.2}), b = summarize({1.3, 1.4, 1.5}), c = summarize({1.15, 1.35});
  EXPECT_EQ(compareTimings(a, b), Order::faster);
  EXPECT_EQ(compareTimings(b, a), Order::slower);
  EXPECT_EQ(compareTimings(a, c), Order::withinNoise) << "c's fastest run is inside a's range";
  EXPECT_EQ(compareTimings(c, b), Order::withinNoise);
}

TEST(Timing, TheMediansConfidenceIntervalIsASignTestsOrderStatistics) {
  std::vector<double> hundred;
  for (int i = 100; i >= 1; --i) hundred.push_back(i);
  const Interval interval = medianWithConfidence(hundred);
  EXPECT_EQ(interval.median, 50.5);
  // k = floor((100 - 1.96 * 10) / 2) = 40: the 41st and the 60th smallest.
  EXPECT_EQ(interval.low, 41);
  EXPECT_EQ(interval.high, 60);
  const Interval few = medianWithConfidence({0.9, 1.2, 0.8, 1.0, 1.1});
  EXPECT_EQ(few.low, 0.8) << "too few samples to narrow it: the whole range";
  EXPECT_EQ(few.high, 1.2);
}

TEST(Timing, AClaimHoldsFailsOrIsWithinNoiseByWhereItsIntervalLies) {
  EXPECT_EQ(below({0.8, 0.7, 0.9}, 1), Verdict::held);
  EXPECT_EQ(below({1.2, 1.1, 1.3}, 1), Verdict::didNotHold);
  EXPECT_EQ(below({0.95, 0.9, 1.05}, 1), Verdict::withinNoise);
  EXPECT_EQ(allOf({Verdict::held, Verdict::held}), Verdict::held);
  EXPECT_EQ(allOf({Verdict::held, Verdict::withinNoise}), Verdict::withinNoise);
  EXPECT_EQ(allOf({Verdict::withinNoise, Verdict::didNotHold, Verdict::held}), Verdict::didNotHold);
  EXPECT_STREQ(verdictText(Verdict::withinNoise), "within noise");
}

ResultRow row(std::vector<double> visibilitySeconds, double pixelError) {
  ResultRow result;
  result.visibility = summarize(std::move(visibilitySeconds));
  result.error.pixelError = pixelError;
  return result;
}

TEST(Timing, TheParetoFrontIsDecidedOnRangesNotMedians) {
  std::vector<ResultRow> rows = {
      row({1.00, 1.05, 1.10}, 0.10),  // the fastest median, but within noise of the next, which is more accurate
      row({1.05, 1.10, 1.20}, 0.05),
      row({2.00, 2.05, 2.10}, 0.01),  // surely slower than the second, and more accurate
      row({2.20, 2.25, 2.30}, 0.01),  // as accurate as the third and surely slower
      row({0.50, 0.55, 0.60}, 0.50),  // surely the fastest
      row({2.05, 2.10, 2.15}, 0.01),  // ties the third: same error, overlapping times
  };
  markParetoFront(rows);
  const std::vector<bool> front = {false, true, true, false, true, true};
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].pareto, front[i]) << "row " << i;
}

TEST(Timing, ARendersTimeSplitsIntoTheAlgorithmsOwnPassesAndTheSharedOnes) {
  std::vector<Stats> runs(2);
  runs[0].addSeconds("pass: culling", 0.001);
  runs[0].addSeconds("pass: visibility", 0.002);
  runs[0].addSeconds("pass: shading", 0.004);
  runs[1].addSeconds("pass: culling", 0.001);
  runs[1].addSeconds("pass: visibility", 0.004);
  runs[1].addSeconds("pass: shading", 0.004);
  ResultRow split;
  splitTimes(split, runs, {0.008, 0.010});
  EXPECT_DOUBLE_EQ(split.visibility.min, 0.003);
  EXPECT_DOUBLE_EQ(split.visibility.max, 0.005);
  EXPECT_DOUBLE_EQ(split.effects.min, 0.005) << "whatever is not the algorithm's: shading and the pipeline around it";
  EXPECT_DOUBLE_EQ(split.effects.max, 0.005);
  ASSERT_EQ(split.passes.size(), 3u);
  EXPECT_EQ(split.passes[1].first, "visibility");
  EXPECT_DOUBLE_EQ(split.passes[1].second.median, 0.003);
  // The reference runs outside the pipeline: its ray casting is its visibility.
  std::vector<Stats> reference(1);
  reference[0].addSeconds("reference", 0.010);
  reference[0].addSeconds("shading", 0.002);
  splitTimes(split, reference, {0.013});
  EXPECT_DOUBLE_EQ(split.visibility.median, 0.010);
  EXPECT_NEAR(split.effects.median, 0.003, 1e-15);
  EXPECT_TRUE(split.passes.empty());
}

TEST(Timing, WarnsOfABusyMachineOnlyForAWideSpreadAboveTheNoiseFloor) {
  EXPECT_FALSE(warnIfBusy({{"steady", summarize({0.010, 0.011, 0.012})}}, "--repeat 9"));
  EXPECT_TRUE(warnIfBusy({{"steady", summarize({0.010, 0.011})}, {"busy", summarize({0.010, 0.016})}}, "--repeat 9"));
  EXPECT_FALSE(warnIfBusy({{"short", summarize({0.2e-3, 0.6e-3})}}, "--repeat 9")) << "3x, but 0.4 ms apart: thread wake-ups";
}

}  // namespace
}  // namespace hsr::studies
