// The z-buffer against the exact reference on every shipped scene. The rasterizer is
// exact for its snapped vertices and float32 depths, so a non-ambiguous pixel may show
// another triangle than the reference only for one of two documented reasons
// (algorithms/zbuffer/README.md, "Agreement with the reference"):
//   snapping: the pixel center lies within 1/256 pixel of the projected boundary of
//     either triangle (vertices snap to 1/256 pixel, which moves an edge by at most
//     sqrt(2)/512 pixel);
//   depth resolution: both triangles cover the center, and their depths there, in the
//     float32 encoding the buffer stores, are within two float32 steps of each other.
// This test classifies every such pixel and fails on any other.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/metrics.hpp"
#include "renderer/reference.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

struct Explained {
  long snapping = 0, depthResolution = 0, unexplained = 0;
};

Explained classify(const PreparedScene& scene, const Frame& frame, const ReferenceImage& truth) {
  const CameraTransform camera(scene.scene().camera, scene.width(), scene.height());
  const DepthEncoding encoding = depthEncoding(DepthFormat::float32, camera);
  Explained result;
  for (std::size_t p = 0; p < frame.pixelCount(); ++p) {
    if (truth.ambiguous[p] || frame.ids[p] == truth.frame.ids[p]) continue;
    const dvec2 center(double(p % std::size_t(frame.width)) + 0.5, double(p / std::size_t(frame.width)) + 0.5);
    const double nearestEdge = test::nearestProjectedEdge(scene, camera, {frame.ids[p], truth.frame.ids[p]}, center);
    if (nearestEdge < test::kSnapDistance) {
      ++result.snapping;
      continue;
    }
    if (frame.ids[p] != 0 && truth.frame.ids[p] != 0) {
      const Ray ray = camera.rayThroughPixel(center.x, center.y);
      const double shown = test::hitDistance(scene, camera, frame.ids[p] - 1, ray);
      const double exact = test::hitDistance(scene, camera, truth.frame.ids[p] - 1, ray);
      const auto stored = [&](double d) { return float(encoding.z(camera.screenAffineDepth(d))); };
      const float larger = std::max(stored(shown), stored(exact));
      const float step = std::nextafter(larger, 2.0f) - larger;  // one float32 step at that depth
      if (std::isfinite(shown) && std::isfinite(exact) && std::abs(stored(shown) - stored(exact)) <= 2 * step) {
        ++result.depthResolution;
        continue;
      }
    }
    ++result.unexplained;
    ADD_FAILURE() << "pixel " << center.x << "," << center.y << " z-buffer id "
                  << frame.ids[p] << " reference id " << truth.frame.ids[p] << " edge distance " << nearestEdge;
  }
  return result;
}

TEST(ZBufferAgainstReference, EveryWrongPixelIsExplainedBySnappingOrDepthResolution) {
  for (const auto& entry : std::filesystem::recursive_directory_iterator(test::sourcePath("scenes"))) {
    if (entry.path().extension() != ".toml" || test::isStudyLevel(entry.path())) continue;
    const Scene scene = loadScene(entry.path());
    PreparedScene prepared(scene);
    prepared.setSize(320, std::max(1, 320 * scene.height / scene.width));
    Stats stats;
    const ReferenceImage truth = renderReference(prepared, 0, stats);
    const Frame frame = test::renderZBuffer(prepared, zbuffer::Variant::full, DepthFormat::float32, 0);
    const SurfaceError error = surfaceError(frame, truth);
    const Explained explained = classify(prepared, frame, truth);
    EXPECT_EQ(explained.unexplained, 0) << entry.path();
    EXPECT_EQ(explained.snapping + explained.depthResolution, error.wrongPixels);
    EXPECT_LT(error.pixelError, 0.001) << entry.path();
    std::printf("%-24s wrong %4ld of %6ld: snapping %4ld, depth resolution %3ld; ambiguous %ld\n",
                entry.path().filename().c_str(), long(error.wrongPixels), long(error.comparedPixels), explained.snapping,
                explained.depthResolution, long(error.ambiguousPixels));
  }
}

}  // namespace
}  // namespace hsr
