// The z-buffer against the exact reference on every shipped scene. The rasterizer is
// exact for its snapped vertices and float32 depths, so a non-ambiguous pixel may show
// another triangle than the reference only for one of two documented reasons
// (algorithms/zbuffer/README.md, "Agreement with the reference"):
//   snapping: the pixel center lies within 1/256 pixel of the projected boundary of
//     either triangle (vertices snap to 1/256 pixel, which moves an edge by at most
//     sqrt(2)/512 pixel);
//   depth resolution: both triangles cover the center, and their depths there, in the
//     float32 encoding the buffer stores, are within two float32 steps of each other.
// This test classifies every such pixel (test::classifyWrongPixels) and fails on any other.
#include <gtest/gtest.h>

#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

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
    const CameraTransform& camera = prepared.camera();
    const test::WrongPixels explained = test::classifyWrongPixels(prepared, frame, truth, test::float32DepthTie(camera));
    EXPECT_EQ(explained.unexplained, 0) << entry.path();
    EXPECT_EQ(explained.total(), error.wrongPixels);
    EXPECT_LT(error.pixelError, 0.001) << entry.path();
    std::printf("%-24s wrong %4ld of %6ld: snapping %4ld, depth resolution %3ld; ambiguous %ld\n",
                entry.path().filename().c_str(), long(error.wrongPixels), long(error.comparedPixels), explained.snapping,
                explained.depthTie, long(error.ambiguousPixels));
  }
}

}  // namespace
}  // namespace hsr
