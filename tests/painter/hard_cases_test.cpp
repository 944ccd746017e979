// The painter's hard cases (scenes/hard/), each with the numbers it must keep.
#include <gtest/gtest.h>

#include <cmath>

#include "algorithms/painter/painter.hpp"
#include "renderer/reference/metrics.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

using painter::Variant;

struct PaintedRun {
  Frame frame;
  Stats stats;
  SurfaceError error;
  test::WrongPixels wrong;
};

PaintedRun paintAgainstReference(const PreparedScene& prepared, Variant variant) {
  PaintedRun run;
  run.frame = test::render(prepared, test::painterKnobs(variant), 2, run.stats);
  Stats referenceStats;
  const ReferenceImage truth = traceReference(prepared, 2, referenceStats);
  run.error = surfaceError(run.frame, truth);
  run.wrong = test::classifyWrongPixels(prepared, run.frame, truth);
  return run;
}

std::filesystem::path hardScene(const std::string& name) { return test::sourcePath("scenes/hard/" + name + ".toml"); }

// Three rectangles each partly over the next: no order of whole rectangles is right.
TEST(PainterHardCases, CyclicOverlapDefeatsTheSortAndNotNewellOrBsp) {
  const test::LoadedScene loaded(hardScene("cyclic_overlap"));
  const PreparedScene& prepared = loaded.prepared;
  const PaintedRun sort = paintAgainstReference(prepared, Variant::sort);
  EXPECT_GT(sort.error.wrongPixels, 100) << "the sort must be wrong at a crossing";
  const PaintedRun newell = paintAgainstReference(prepared, Variant::newell);
  EXPECT_EQ(newell.error.wrongPixels, 0);
  EXPECT_GT(newell.stats.counter("newell splits"), 0) << "a cycle is broken only by splitting";
  const PaintedRun bsp = paintAgainstReference(prepared, Variant::bsp);
  EXPECT_EQ(bsp.error.wrongPixels, 0);
  EXPECT_GT(bsp.stats.counter("bsp splits"), 0);
  std::printf("cyclic overlap: sort %ld wrong; newell %ld splits, %ld reorders; bsp %ld splits\n", long(sort.error.wrongPixels),
              long(newell.stats.counter("newell splits")), long(newell.stats.counter("newell reorders")),
              long(bsp.stats.counter("bsp splits")));
}

// Two triangles through each other: each must be split along the other's plane.
TEST(PainterHardCases, InterpenetratingTrianglesAreSplitAlongTheirIntersection) {
  const test::LoadedScene loaded(hardScene("interpenetrating"));
  const PreparedScene& prepared = loaded.prepared;
  EXPECT_GT(paintAgainstReference(prepared, Variant::sort).error.wrongPixels, 100);
  for (const Variant variant : {Variant::newell, Variant::bsp}) {
    const PaintedRun run = paintAgainstReference(prepared, variant);
    EXPECT_EQ(run.error.wrongPixels, 0) << int(variant);
    EXPECT_EQ(run.stats.counter(variant == Variant::newell ? "newell splits" : "bsp splits"), 1) << int(variant);
    EXPECT_EQ(run.stats.counter("pieces painted"), 3) << "two halves of one triangle, and the other whole";
  }
}

// Sixty squares in one plane (coplanar only up to rounding once projected): no
// splitting against each other, no cap.
TEST(PainterHardCases, ManyCoplanarFacesNeitherLoopNorSplit) {
  const test::LoadedScene loaded(hardScene("many_coplanar"));
  const PreparedScene& prepared = loaded.prepared;
  const PaintedRun newell = paintAgainstReference(prepared, Variant::newell);
  EXPECT_EQ(newell.frame.partial, "");
  EXPECT_EQ(newell.stats.counter("newell unresolved conflicts"), 0);
  EXPECT_EQ(newell.stats.counter("newell splits"), 0);
  EXPECT_EQ(newell.stats.counter("newell reorders"), 0);
  EXPECT_EQ(newell.wrong.unexplained, 0);
  const PaintedRun bsp = paintAgainstReference(prepared, Variant::bsp);
  EXPECT_EQ(bsp.stats.counter("bsp splits"), 0);
  EXPECT_EQ(bsp.stats.counter("bsp nodes"), 1) << "one plane holds them all";
  EXPECT_EQ(bsp.wrong.unexplained, 0);
  // Where squares overlap the reference finds an exact tie and leaves the pixel out;
  // everywhere else both are exact.
  EXPECT_GT(newell.error.ambiguousPixels, 1000);
  EXPECT_EQ(newell.error.wrongPixels, 0);
  EXPECT_EQ(bsp.error.wrongPixels, 0);
}

// Planes within 1e-7 of a corner: the pieces of the big triangle cover its pixels
// exactly once, and no sliver makes a NaN.
TEST(PainterHardCases, NearDegenerateSplitsLeaveNoCracksAndNoNaN) {
  const test::LoadedScene loaded(hardScene("near_degenerate_splits"));
  const PreparedScene& prepared = loaded.prepared;
  // Each screen triangle's pixels, counted with the rasterizer alone.
  Stats geometryStats;
  const ScreenGeometry geometry = buildScreenTriangles(prepared, {}, 1, geometryStats);
  long covered = 0;
  for (const ScreenTriangle& tri : geometry.triangles)
    for (int y = tri.minY; y <= tri.maxY; ++y) rasterizeSpan(tri, y, tri.minX, tri.maxX + 1, [&](int) { ++covered; });
  for (const Variant variant : {Variant::newell, Variant::bsp}) {
    const PaintedRun run = paintAgainstReference(prepared, variant);
    EXPECT_GT(run.stats.counter(variant == Variant::newell ? "newell splits" : "bsp splits"), 0) << int(variant);
    EXPECT_GT(run.stats.counter("pieces painted"), 4);
    EXPECT_EQ(run.stats.counter("fragments written"), covered) << "each triangle's pixels written exactly once";
    EXPECT_EQ(run.wrong.unexplained, 0) << int(variant);
    for (const float depth : run.frame.depth) EXPECT_FALSE(std::isnan(depth));
  }
}

}  // namespace
}  // namespace hsr
