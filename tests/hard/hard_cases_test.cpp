// The foundation's hard cases (scenes/hard/), each asserting numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "coverage.hpp"
#include "floating_point_traps.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

struct Range {
  std::uint32_t first, end;  // global triangle indices [first, end)
  bool holds(std::uint32_t id) const { return id != 0 && id - 1 >= first && id - 1 < end; }
};

Range rangeOf(const PreparedScene& scene, std::size_t instance) {
  const Instance& i = scene.instances()[instance];
  return {i.firstTriangle, i.firstTriangle + i.triangleCount};
}

// Every clear pixel (test_support.hpp) shows what the rays see, and at least
// `clearFraction` of the image is clear, so the agreement covers most of it.
void expectAgreementWithRays(const PreparedScene& scene, const Frame& frame, double clearFraction) {
  const test::Agreement agreement = test::agreementWithRays(scene, frame);
  EXPECT_GT(agreement.clearPixels, long(clearFraction * double(scene.width() * scene.height())));
  EXPECT_EQ(agreement.mismatches, 0);
}

// 1. Shared edges: no cracks, no double hits.
TEST(HardCase, SharedEdgesCoverEveryPixelExactlyOnce) {
  const Scene scene = loadScene(test::sourcePath("scenes/hard/shared_edges.toml"));
  const PreparedScene prepared(scene);
  const Range fan = rangeOf(prepared, 0), sphere = rangeOf(prepared, 1), bunny = rangeOf(prepared, 2);

  const test::Coverage fanCoverage = test::rasterCoverage(prepared, fan.first, fan.end);
  long fanWrites = 0;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      ASSERT_EQ(fanCoverage.at(fanCoverage.front, x, y) + fanCoverage.at(fanCoverage.back, x, y), 1) << x << "," << y;
      ++fanWrites;
    }
  EXPECT_EQ(fanWrites, long(scene.width) * scene.height);

  // A ray through a closed mesh enters it as often as it leaves: per pixel, as many
  // front-facing as back-facing triangles. A crack or a double hit on any shared edge
  // breaks the balance. The sphere is convex: at most one of each.
  for (const Range& solid : {sphere, bunny}) {
    const test::Coverage coverage = test::rasterCoverage(prepared, solid.first, solid.end);
    long covered = 0;
    for (int y = 0; y < scene.height; ++y)
      for (int x = 0; x < scene.width; ++x) {
        ASSERT_EQ(coverage.at(coverage.front, x, y), coverage.at(coverage.back, x, y)) << x << "," << y;
        if (solid.first == sphere.first) {
          ASSERT_LE(coverage.at(coverage.front, x, y), 1);
        }
        covered += coverage.at(coverage.front, x, y) > 0;
      }
    EXPECT_GT(covered, 2000);
  }
}

// 2. The near plane: triangles reaching behind the eye are clipped, not wrapped around.
TEST(HardCase, NearPlaneCrossingsMatchExactRays) {
  const Scene scene = loadScene(test::sourcePath("scenes/hard/near_plane.toml"));
  const PreparedScene prepared(scene);
  Stats stats;
  const Frame frame = test::render(prepared, zbuffer::Knobs{}, 1, stats);
  EXPECT_EQ(stats.counter("triangles clipped"), 3);  // the two ground triangles and the wall
  const Range behind = rangeOf(prepared, 2);
  test::CaseFailures drawn("a triangle wholly behind the eye was drawn");
  for (std::size_t p = 0; p < frame.ids.size(); ++p)
    drawn.expect(!behind.holds(frame.ids[p]), [&] { return test::describePixel(frame, p) + ": " + test::describeTriangle(prepared, frame.ids[p] - 1); });
  EXPECT_NO_FAILED_CASES(drawn);
  expectAgreementWithRays(prepared, frame, 0.98);
}

// 3. Z-fighting: which quad wins, per depth format, and whether a small camera move flips it.
TEST(HardCase, CoplanarFacesPerDepthFormat) {
  const Scene scene = loadScene(test::sourcePath("scenes/hard/coplanar.toml"));
  const PreparedScene prepared(scene);
  Scene moved = scene;
  moved.camera.eye += dvec3(0.01, 0.01, 0);  // a centimetre, if units are metres
  const PreparedScene movedPrepared(moved);

  // The rays (double precision) resolve both offsets: they say where each upper quad is visible.
  const auto raysAnswer = [](const PreparedScene& view) {
    const Scene& description = view.scene();
    Frame frame(description.width, description.height);
    const CameraTransform camera(description.camera, description.width, description.height);
    for (int y = 0; y < description.height; ++y)
      for (int x = 0; x < description.width; ++x)
        frame.ids[std::size_t(y * description.width + x)] = test::nearestHit(view, camera, camera.rayThroughPixel(x + 0.5, y + 0.5));
    return frame;
  };
  const Frame truthBefore = raysAnswer(prepared), truthAfter = raysAnswer(movedPrepared);
  const int width = scene.width;
  // Interior: the exact answer is the upper quad here and at the four neighbours, so
  // snapping at the quad's edges cannot change the winner.
  const auto interiorOf = [&](const Range& over, std::size_t p) {
    const std::size_t x = p % std::size_t(width);
    return x > 0 && x + 1 < std::size_t(width) && p >= std::size_t(width) && p + std::size_t(width) < truthBefore.ids.size() &&
           over.holds(truthBefore.ids[p]) && over.holds(truthBefore.ids[p - 1]) && over.holds(truthBefore.ids[p + 1]) &&
           over.holds(truthBefore.ids[p - std::size_t(width)]) && over.holds(truthBefore.ids[p + std::size_t(width)]);
  };

  struct Pair {
    const char* name;
    Range under, over;
    bool exactTie;
    long wrong[5] = {}, flips[5] = {};
  };
  Pair pairs[3] = {{"left (tie)", rangeOf(prepared, 0), rangeOf(prepared, 1), true},
                   {"middle (0.02)", rangeOf(prepared, 2), rangeOf(prepared, 3), false},
                   {"right (0.001)", rangeOf(prepared, 4), rangeOf(prepared, 5), false}};
  for (std::size_t f = 0; f < depthFormatNames().size(); ++f) {
    const auto format = static_cast<DepthFormat>(f);
    const Frame before = test::renderZBuffer(prepared, zbuffer::Variant::full, format);
    const Frame after = test::renderZBuffer(movedPrepared, zbuffer::Variant::full, format);
    for (Pair& pair : pairs)
      for (std::size_t p = 0; p < before.ids.size(); ++p) {
        const bool inPair = (pair.under.holds(before.ids[p]) || pair.over.holds(before.ids[p])) &&
                            (pair.under.holds(after.ids[p]) || pair.over.holds(after.ids[p]));
        const bool winnerChanged = pair.over.holds(before.ids[p]) != pair.over.holds(after.ids[p]);
        // A z-fighting flip: the winner changed while the exact answer did not (edges that
        // truly moved are not flips). An exact tie has no exact winner: any change counts.
        const bool truthChanged = pair.over.holds(truthBefore.ids[p]) != pair.over.holds(truthAfter.ids[p]);
        pair.flips[f] += inPair && winnerChanged && (pair.exactTie || !truthChanged);
        if (!pair.exactTie && interiorOf(pair.over, p) && !pair.over.holds(before.ids[p])) ++pair.wrong[f];
      }
  }
  std::printf("%-22s", "format");
  for (const Pair& pair : pairs) std::printf("  %s: wrong, flips", pair.name);
  std::printf("\n");
  for (std::size_t f = 0; f < depthFormatNames().size(); ++f) {
    std::printf("%-22s", depthFormatNames()[f].c_str());
    for (const Pair& pair : pairs) std::printf("  %12ld %6ld", pair.wrong[f], pair.flips[f]);
    std::printf("\n");
  }

  const auto index = [](DepthFormat format) { return static_cast<std::size_t>(format); };
  const Pair &tie = pairs[0], &middle = pairs[1], &right = pairs[2];
  for (std::size_t f = 0; f < depthFormatNames().size(); ++f) {
    // An exact tie is decided by submission order in every format: the first quad wins, always.
    EXPECT_EQ(tie.flips[f], 0) << depthFormatNames()[f];
    // Every format but unorm16 resolves 0.02 at this range.
    if (f != index(DepthFormat::unorm16)) {
      EXPECT_EQ(middle.wrong[f] + middle.flips[f], 0) << depthFormatNames()[f];
    }
  }
  // Reversed-Z float32 resolves even 0.001 everywhere and is stable under the move ...
  for (const DepthFormat reversed : {DepthFormat::reversedFloat32, DepthFormat::reversedFloat32Infinite}) {
    EXPECT_EQ(right.wrong[index(reversed)], 0);
    EXPECT_EQ(right.flips[index(reversed)], 0);
  }
  // ... where unorm16 flickers at 0.02 and loses 0.001 nearly everywhere,
  EXPECT_GT(middle.flips[index(DepthFormat::unorm16)], 50);
  EXPECT_GT(right.wrong[index(DepthFormat::unorm16)], 500);
  // and float32 and unorm24 (the same 2^24 steps near z = 1) lose 0.001 far away only.
  for (const DepthFormat middling : {DepthFormat::float32, DepthFormat::unorm24}) {
    EXPECT_GT(right.wrong[index(middling)], 0);
    EXPECT_LT(right.wrong[index(middling)], right.wrong[index(DepthFormat::unorm16)] / 10);
  }
}

// 4. Large coordinates: moving and scaling the whole scene changes no pixel.
TEST(HardCase, LargeCoordinatesGiveTheSameIdImage) {
  const Scene scene = loadScene(test::sourcePath("scenes/hard/large_coordinates.toml"));
  for (const auto& object : scene.objects) ASSERT_EQ(object.instancing.kind, Instancing::Kind::single);
  const Frame original = test::renderZBuffer(PreparedScene(scene));
  ASSERT_GT(std::count_if(original.ids.begin(), original.ids.end(), [](std::uint32_t id) { return id != 0; }), 20000);
  const struct {
    double scale;
    dvec3 offset;
  } variants[] = {{1, dvec3(1e5)}, {1e-3, dvec3(0)}, {1e3, dvec3(0)}, {1e-3, dvec3(1e5)}, {1e3, dvec3(-1e5, 1e5, 3e5)}};
  for (const auto& v : variants) {
    const Frame frame = test::renderZBuffer(PreparedScene(test::movedAndScaled(scene, v.scale, v.offset)));
    long differing = 0;
    for (std::size_t p = 0; p < frame.ids.size(); ++p) differing += frame.ids[p] != original.ids[p];
    EXPECT_EQ(differing, 0) << "scale " << v.scale << " offset " << v.offset.x;
  }
}

// 5. Slivers and zero-area triangles: no NaN (trapped), no stray pixels.
TEST(HardCase, SliversAndZeroAreaTrianglesStayExact) {
  const Scene scene = loadScene(test::sourcePath("scenes/hard/slivers.toml"));
  const PreparedScene prepared(scene);
  // Trapped while rendering, in every build: a NaN born anywhere in the pipeline stops
  // the test instead of printing a grey pixel.
  Stats stats;
  Frame frame;
  {
    const test::TrappedFloatingPoint trapped;
    frame = test::render(prepared, zbuffer::Knobs{}, 2, stats);
  }
  test::CaseFailures nan("a depth is NaN"), zeroArea("a zero-area triangle drew a pixel");
  for (std::size_t p = 0; p < frame.pixelCount(); ++p) {
    nan.expect(!std::isnan(frame.distances()[p]), [&] { return test::describePixel(frame, p); });
    // Triangles 13, 15, ..., 23 repeat a vertex: exactly zero area, they may own no pixel.
    // (12, 14, ..., 22 are collinear in decimal, not quite in binary: the rays judge those.)
    const std::uint32_t id = frame.ids[p];
    zeroArea.expect(!(id >= 14 && id <= 24 && id % 2 == 0), [&] { return test::describePixel(frame, p) + ": " + test::describeTriangle(prepared, id - 1); });
  }
  EXPECT_NO_FAILED_CASES(nan);
  EXPECT_NO_FAILED_CASES(zeroArea);
  EXPECT_GE(stats.counter("triangles between pixel centers"), 6);
  expectAgreementWithRays(prepared, frame, 0.99);
}

// 6. Triangles hundreds (and tens of thousands) of times larger than the view.
TEST(HardCase, HugeTrianglesCoverExactly) {
  const Scene scene = loadScene(test::sourcePath("scenes/hard/huge_triangle.toml"));
  const PreparedScene prepared(scene);
  Stats stats;
  const Frame frame = test::render(prepared, zbuffer::Knobs{}, 1, stats);
  EXPECT_EQ(stats.counter("triangles clipped"), 1);  // only the one beyond the guard band
  expectAgreementWithRays(prepared, frame, 0.99);
  long big = 0, beyond = 0;
  for (std::uint32_t id : frame.ids) {
    big += id == 1;
    beyond += id == 2;
  }
  EXPECT_GT(big, 5000);
  EXPECT_GT(beyond, 5000);
}

}  // namespace
}  // namespace hsr
