// Ray casting's hard cases (scenes/hard/watertight, grazing, thin_sheet,
// large_coordinates), each asserting numbers.
#include <gtest/gtest.h>

#include <cmath>

#include "algorithms/ray_casting/ray_casting.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

using ray_casting::Variant;
using test::renderRayCasting;
using test::rayCastingKnobs;

// The convex hull of points, counter-clockwise in a y-up sense (Andrew's monotone chain).
std::vector<dvec2> convexHull(std::vector<dvec2> points) {
  std::sort(points.begin(), points.end(), [](const dvec2& a, const dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  const auto cross = [](const dvec2& o, const dvec2& a, const dvec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<dvec2> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// How far inside a convex polygon a point lies (negative outside).
double depthInside(const std::vector<dvec2>& hull, const dvec2& p) {
  double depth = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const dvec2 a = hull[i], b = hull[(i + 1) % hull.size()];
    const dvec2 edge = b - a;
    depth = std::min(depth, ((edge.x * (p.y - a.y) - edge.y * (p.x - a.x))) / glm::length(edge));
  }
  return depth;
}

// 7. Watertightness: every pixel center inside a closed convex mesh's silhouette shows
// a front face of that mesh, including the centers exactly on its shared edges.
TEST(RayCastingHardCase, NoRayPassesBetweenTrianglesThatShareAnEdge) {
  const Scene scene = loadScene(test::sourcePath("scenes/hard/watertight.toml"));
  const PreparedScene prepared(scene);
  const CameraTransform& camera = prepared.camera();
  for (const Variant which : {Variant::bvh, Variant::naive}) {
    const Frame frame = renderRayCasting(prepared, rayCastingKnobs(which));
    for (const Instance& instance : prepared.instances()) {
      std::vector<dvec2> projected;
      for (std::uint32_t t = instance.firstTriangle; t < instance.firstTriangle + instance.triangleCount; ++t)
        for (const std::uint32_t v : prepared.triangles()[t]) {
          const dvec2 pixel = camera.pixelFromClip(camera.clipFromWorld(prepared.positions()[v]));
          projected.push_back({pixel.x, -pixel.y});  // y up, for the hull's orientation
        }
      const std::vector<dvec2> hull = convexHull(projected);
      long inside = 0, onSharedEdges = 0, wrong = 0;
      for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
          const dvec2 center(x + 0.5, y + 0.5);
          if (depthInside(hull, {center.x, -center.y}) < 1e-6) continue;
          ++inside;
          // Centers on a projected edge of a front face (shared with its neighbour).
          const std::uint32_t id = frame.ids[std::size_t(y) * std::size_t(frame.width) + std::size_t(x)];
          const bool ours = id != 0 && id - 1 >= instance.firstTriangle && id - 1 < instance.firstTriangle + instance.triangleCount;
          if (!ours || glm::dot(prepared.faceNormal(id - 1), camera.forward()) >= 0) {
            ++wrong;
            continue;
          }
          if (test::distanceToProjectedEdges(prepared, camera, id - 1, center) < 1e-9) ++onSharedEdges;
        }
      EXPECT_GT(inside, 3000) << scene.objects[instance.object].name;
      EXPECT_EQ(wrong, 0) << scene.objects[instance.object].name << " variant " << int(which);
      // The case is exercised: centers lie on shared edges (to rounding): 63 on the
      // edge-on cube's front edge, 261 on the sphere's meridians, and the corner-on
      // cube's corner, where three faces meet.
      EXPECT_GE(onSharedEdges, instance.object == 1 ? 1 : 50) << scene.objects[instance.object].name;
    }
  }
}

// 8. Grazing rays: rays with zero direction components (infinite inverses in the slab
// test) and rays inside faces' planes. No NaN, and no pixel differs from the reference.
TEST(RayCastingHardCase, GrazingRaysAndAxisParallelRaysAgreeWithTheReference) {
  const Scene scene = loadScene(test::sourcePath("scenes/hard/grazing.toml"));
  const PreparedScene prepared(scene);
  Stats stats;
  const ReferenceImage truth = traceReference(prepared, 2, stats);
  for (const Variant which : {Variant::bvh, Variant::naive}) {
    const Frame frame = renderRayCasting(prepared, rayCastingKnobs(which));
    EXPECT_EQ(std::count_if(frame.depth.begin(), frame.depth.end(), [](float d) { return std::isnan(d); }), 0);
    const SurfaceError error = surfaceError(frame, truth);
    EXPECT_EQ(error.wrongPixels, 0) << int(which);
    EXPECT_GT(error.comparedPixels, std::int64_t(frame.pixelCount()) * 99 / 100);  // the ties: the boxes' diagonals
  }
  // The row of rays in the floor's plane (pixel row 64, y = 0) sees the floor edge-on,
  // so it shows what lies beyond: the backdrop, or the boxes' faces that cross y = 0.
  const Frame frame = renderRayCasting(prepared, rayCastingKnobs(Variant::bvh));
  const Instance& floor = prepared.instances()[0];
  for (int x = 0; x < frame.width; ++x) {
    const std::uint32_t id = frame.ids[64 * std::size_t(frame.width) + std::size_t(x)];
    EXPECT_FALSE(id != 0 && id - 1 < floor.firstTriangle + floor.triangleCount) << "floor seen edge-on at x " << x;
  }
}

// 9. A sheet thinner than the step: the march skips it at a long step and never at a
// short one; refinement improves the depth of what was found but finds nothing more.
TEST(RayCastingHardCase, MarchSkipsASheetThinnerThanTheStep) {
  const Scene scene = loadScene(test::sourcePath("scenes/hard/thin_sheet.toml"));
  const PreparedScene prepared(scene);
  Stats stats;
  const ReferenceImage truth = traceReference(prepared, 2, stats);
  const Instance& sheet = prepared.instances()[0];
  const auto isSheet = [&](std::uint32_t id) { return id != 0 && id - 1 < sheet.firstTriangle + sheet.triangleCount; };
  const long sheetPixels = std::count_if(truth.frame.ids.begin(), truth.frame.ids.end(), isSheet);
  ASSERT_GT(sheetPixels, 5000);
  const auto march = [&](double step, bool percent, int refine) {
    ray_casting::Knobs knobs = rayCastingKnobs(Variant::march);
    knobs.step = {step, percent};
    knobs.refine = refine;
    return renderRayCasting(prepared, knobs);
  };
  const auto sheetFound = [&](const Frame& frame) {
    long found = 0;
    for (std::size_t p = 0; p < frame.pixelCount(); ++p) found += isSheet(truth.frame.ids[p]) && isSheet(frame.ids[p]);
    return found;
  };

  const Frame longStep = march(5, true, 0);  // 5% of the diagonal: about 0.26, 130 times the sheet
  EXPECT_LT(sheetFound(longStep), sheetPixels / 10);
  const Frame shortStep = march(0.001, false, 0);  // half the sheet's thickness
  EXPECT_GT(sheetFound(shortStep), sheetPixels * 99 / 100);

  const Frame refined = march(5, true, 8);
  EXPECT_EQ(sheetFound(refined), sheetFound(longStep));
  EXPECT_EQ(refined.ids == longStep.ids, false);  // the depths moved, and with them the nearest triangles
  const SurfaceError coarse = surfaceError(longStep, truth), fine = surfaceError(refined, truth);
  EXPECT_LT(fine.depthErrorMean, coarse.depthErrorMean / 10);
}

// 4 (for ray casting). Moving the scene by 1e5 or scaling it by 1e-3 .. 1e3 (the camera
// with it) changes no id.
TEST(RayCastingHardCase, LargeCoordinatesGiveTheSameIdImage) {
  const Scene scene = loadScene(test::sourcePath("scenes/hard/large_coordinates.toml"));
  const Frame original = renderRayCasting(PreparedScene(scene), rayCastingKnobs(Variant::bvh));
  ASSERT_GT(std::count_if(original.ids.begin(), original.ids.end(), [](std::uint32_t id) { return id != 0; }), 20000);
  const struct {
    double scale;
    dvec3 offset;
  } variants[] = {{1, dvec3(1e5)}, {1e-3, dvec3(0)}, {1e-1, dvec3(0)}, {1e1, dvec3(0)}, {1e3, dvec3(0)}, {1e3, dvec3(-1e5, 1e5, 3e5)}};
  for (const auto& v : variants) {
    const Frame frame = renderRayCasting(PreparedScene(test::movedAndScaled(scene, v.scale, v.offset)), rayCastingKnobs(Variant::bvh));
    long differing = 0;
    for (std::size_t p = 0; p < frame.ids.size(); ++p) differing += frame.ids[p] != original.ids[p];
    EXPECT_EQ(differing, 0) << "scale " << v.scale << " offset " << v.offset.x;
  }
}

}  // namespace
}  // namespace hsr
