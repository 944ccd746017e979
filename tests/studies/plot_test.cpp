// The plots' shared rules (studies/plot.hpp).
#include <gtest/gtest.h>

#include "studies/plot.hpp"

namespace hsr::studies {
namespace {

TEST(Plot, ATimeAxisGoesLogarithmicOnlyPastTwentyTimesAndBarsOtherwiseStartAtZero) {
  EXPECT_EQ(timeAxis('y', {1.0, 19.9}, true), "set yrange [0:*]\n");
  EXPECT_EQ(timeAxis('y', {1.0, 19.9}, false), "");
  EXPECT_EQ(timeAxis('x', {0.5, 10.5}, false), "set logscale x\n");
  EXPECT_EQ(timeAxis('y', {2.0, 41.0, 7.0}, true), "set logscale y\n");
  // Zero and non-finite values (a mode that did no work, a missing frame) do not count.
  EXPECT_EQ(timeAxis('y', {0.0, 1.0, 3.0, INFINITY}, true), "set yrange [0:*]\n");
  EXPECT_EQ(timeAxis('y', {}, true), "set yrange [0:*]\n");
}

}  // namespace
}  // namespace hsr::studies
