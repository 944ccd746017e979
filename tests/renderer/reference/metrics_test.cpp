// The error definitions of README.md ("Metrics"), on inputs small enough to check by hand.
#include <gtest/gtest.h>

#include "renderer/reference/metrics.hpp"

namespace hsr {
namespace {

TEST(Metrics, PixelErrorSkipsAmbiguousPixelsAndDepthErrorUsesAgreeingOnes) {
  ReferenceImage truth;
  truth.frame = Frame(4, 1);
  truth.frame.ids = {1, 2, 3, 0};
  truth.frame.depth = {1.0f, 2.0f, 3.0f, INFINITY};
  truth.ambiguous = {0, 0, 1, 0};
  Frame frame(4, 1);
  frame.ids = {1, 5, 4, 0};  // pixel 1 wrong, pixel 2 differs but is ambiguous
  frame.depth = {1.5f, 2.0f, 3.0f, INFINITY};
  const SurfaceError error = surfaceError(frame, truth);
  EXPECT_EQ(error.comparedPixels, 3);
  EXPECT_EQ(error.ambiguousPixels, 1);
  EXPECT_EQ(error.wrongPixels, 1);
  EXPECT_DOUBLE_EQ(error.pixelError, 1.0 / 3);
  EXPECT_EQ(error.depthPixels, 1);  // only pixel 0 shows the same triangle; the background has no depth
  EXPECT_DOUBLE_EQ(error.depthErrorMean, 0.5);
  EXPECT_DOUBLE_EQ(error.depthErrorMax, 0.5);
}

TEST(Metrics, CullingErrorCountsFalseCullsAndWastedWork) {
  const std::vector<std::uint8_t> kept = {1, 1, 0, 0, 1}, visible = {1, 0, 1, 0, 1};
  const CullingError error = cullingError(kept, visible);
  EXPECT_EQ(error.items, 5);
  EXPECT_EQ(error.visible, 3);
  EXPECT_EQ(error.kept, 3);
  EXPECT_EQ(error.falseCulls, 1);  // item 2
  EXPECT_EQ(error.wastedWork, 1);  // item 1
}

TEST(Metrics, VisibleTrianglesAreTheIdsTheReferenceShows) {
  ReferenceImage truth;
  truth.frame = Frame(3, 1);
  truth.frame.ids = {0, 2, 2};
  EXPECT_EQ(visibleTriangles(truth, 3), (std::vector<std::uint8_t>{0, 1, 0}));
}

TEST(Metrics, LineErrorWeighsWrongLengthInPixels) {
  // Edge 0, 100 px: drawn on [0, 0.5], visible on [0.25, 1]: 25 px drawn wrongly, 50 hidden wrongly.
  // Edge 1, 10 px: drawn and visible on [0, 1].
  const std::vector<EdgeVisibility> drawn = {{100, {{0, 0.5}}}, {10, {{0, 1}}}};
  const std::vector<EdgeVisibility> truth = {{100, {{0.25, 1}}}, {10, {{0, 0.4}, {0.4, 1}}}};
  const LineError error = lineError(drawn, truth);
  EXPECT_DOUBLE_EQ(error.visibleLength, 85);
  EXPECT_DOUBLE_EQ(error.wronglyDrawn, 25);
  EXPECT_DOUBLE_EQ(error.wronglyHidden, 50);
  EXPECT_DOUBLE_EQ(error.error, 75.0 / 85);
}

}  // namespace
}  // namespace hsr
