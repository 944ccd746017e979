// One test per statement of renderer/util/conventions.hpp, each rendering a known triangle.
#include <gtest/gtest.h>

#include <random>

#include "renderer/raster/screen_triangles.hpp"
#include "renderer/shading/shading.hpp"
#include "renderer/util/conventions.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

using test::pixelCamera;
using test::renderZBuffer;
using test::sceneOf;
using test::triangleMesh;

std::uint32_t idAt(const Frame& frame, int x, int y) { return frame.ids[std::size_t(y) * std::size_t(frame.width) + std::size_t(x)]; }

long coveredPixels(const Frame& frame) {
  return static_cast<long>(std::count_if(frame.ids.begin(), frame.ids.end(), [](std::uint32_t id) { return id != 0; }));
}

TEST(Conventions, CameraLooksDownMinusZ) {
  Camera camera;  // eye (0, 0, 5) looking at the origin: down -z
  const Mesh inFront = triangleMesh({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}});
  const Mesh behind = triangleMesh({{-1, -1, 10}, {1, -1, 10}, {0, 1, 10}});
  const Scene front = sceneOf(camera, 64, 64, {inFront}), back = sceneOf(camera, 64, 64, {behind});
  EXPECT_GT(coveredPixels(renderZBuffer(PreparedScene(front))), 100);
  EXPECT_EQ(coveredPixels(renderZBuffer(PreparedScene(back))), 0);
}

TEST(Conventions, XRightYUpRowZeroAtTheTop) {
  // A small triangle in the upper right quadrant of the view (x > 0, y > 0 in world).
  const Scene scene = sceneOf(pixelCamera(64), 64, 64, {triangleMesh({{10, 10, 0}, {20, 10, 0}, {10, 20, 0}})});
  const Frame frame = renderZBuffer(PreparedScene(scene));
  // World (x, y) -> pixel (x + 32, 32 - y): covered pixels lie in columns 42..52, rows 12..22.
  EXPECT_EQ(idAt(frame, 43, 21), 1u);
  EXPECT_EQ(idAt(frame, 21, 43), 0u);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (idAt(frame, x, y)) {
        EXPECT_GE(x, 42);
        EXPECT_LE(y, 22);
      }
}

TEST(Conventions, CounterClockwiseIsFrontFacing) {
  const Scene scene = sceneOf(pixelCamera(64), 64, 64,
                              {triangleMesh({{0, 0, 0}, {10, 0, 0}, {0, 10, 0},     // counter-clockwise seen from +z
                                             {0, 0, 0}, {0, 10, 0}, {10, 0, 0}})}); // clockwise
  Stats stats;
  const ScreenGeometry geometry = buildScreenTriangles(PreparedScene(scene), {}, 1, stats);
  ASSERT_EQ(geometry.triangles.size(), 2u);
  EXPECT_TRUE(geometry.triangles[0].frontFacing);
  EXPECT_FALSE(geometry.triangles[1].frontFacing);
}

TEST(Conventions, PixelCentersAtHalf) {
  // A triangle with a corner at pixel coordinates (0, 0) whose legs are 3 pixels long
  // covers the centers (i + 0.5, j + 0.5) with i + j + 1 < 3 strictly inside: 3 pixels.
  // (Centers on the hypotenuse, i + j + 1 = 3, lie on a right edge: excluded.)
  const Scene scene = sceneOf(pixelCamera(8), 8, 8, {triangleMesh({{-4, 4, 0}, {-4, 1, 0}, {-1, 4, 0}})});
  const Frame frame = renderZBuffer(PreparedScene(scene));
  EXPECT_EQ(coveredPixels(frame), 3);
  EXPECT_EQ(idAt(frame, 0, 0), 1u);
  EXPECT_EQ(idAt(frame, 1, 0), 1u);
  EXPECT_EQ(idAt(frame, 0, 1), 1u);
}

// The fill rule, edge by edge: pixel centers exactly on an edge (x or y = k + 0.5).
TEST(Conventions, TopLeftFillRule) {
  // Pixel coordinates (px, py) -> world (px - 16, 16 - py) for a 32 x 32 image.
  const auto world = [](double px, double py) { return dvec3(px - 16, 16 - py, 0); };
  const auto count = [](const Mesh& mesh) {
    return coveredPixels(renderZBuffer(PreparedScene(sceneOf(pixelCamera(32), 32, 32, {mesh}))));
  };
  // Rectangle [4.5, 8.5] x [4.5, 8.5] in pixel coordinates, two triangles: its left
  // and top edges run through centers of columns/rows 4 (included), right and bottom
  // through 8 (excluded): exactly the 4 x 4 pixels 4..7 are covered.
  const Mesh square = triangleMesh({world(4.5, 4.5), world(4.5, 8.5), world(8.5, 8.5),
                                    world(4.5, 4.5), world(8.5, 8.5), world(8.5, 4.5)});
  const Frame frame = renderZBuffer(PreparedScene(sceneOf(pixelCamera(32), 32, 32, {square})));
  EXPECT_EQ(coveredPixels(frame), 16);
  EXPECT_NE(idAt(frame, 4, 4), 0u);  // top-left corner's center: on a top and a left edge
  EXPECT_EQ(idAt(frame, 8, 4), 0u);  // on the right edge
  EXPECT_EQ(idAt(frame, 4, 8), 0u);  // on the bottom edge
  // A triangle whose only on-center edge is its bottom edge (y = 8.5): that row is excluded.
  EXPECT_EQ(count(triangleMesh({world(2, 8.5), world(12, 8.5), world(7, 2)})),
            count(triangleMesh({world(2, 8.49), world(12, 8.49), world(7, 2)})));
  // Mirrored, the same edge is a top edge (y = 8.5, triangle below): that row is included.
  EXPECT_GT(count(triangleMesh({world(2, 8.5), world(7, 15), world(12, 8.5)})),
            count(triangleMesh({world(2, 8.51), world(7, 15), world(12, 8.51)})));
}

TEST(Conventions, DepthFormatsStoreNearAndFarAsDocumented) {
  Camera camera;
  camera.near = 0.5;
  camera.far = 50;
  const CameraTransform transform(camera, 64, 64);
  const auto zAt = [&](DepthFormat format, double distance) {
    return depthEncoding(format, transform).z(transform.screenAffineDepth(distance));
  };
  EXPECT_NEAR(zAt(DepthFormat::float32, 0.5), 0.0, 1e-12);
  EXPECT_NEAR(zAt(DepthFormat::float32, 50), 1.0, 1e-12);
  EXPECT_NEAR(zAt(DepthFormat::reversedFloat32, 0.5), 1.0, 1e-12);
  EXPECT_NEAR(zAt(DepthFormat::reversedFloat32, 50), 0.0, 1e-12);
  EXPECT_NEAR(zAt(DepthFormat::reversedFloat32Infinite, 0.5), 1.0, 1e-12);
  EXPECT_NEAR(zAt(DepthFormat::reversedFloat32Infinite, 5e6), 1e-7, 1e-12);  // near / distance
  EXPECT_EQ(Unorm16Depth::store(1.0), 65535);
  EXPECT_EQ(Unorm24Depth::store(1.0), (1u << 24) - 1);
  EXPECT_TRUE(ReversedFloat32Depth::nearer(0.75f, 0.5f));
  EXPECT_TRUE(Float32Depth::nearer(0.5f, 0.75f));
  EXPECT_FALSE(Float32Depth::nearer(0.5f, 0.5f));  // ties keep what is there
}

TEST(Conventions, FrameDepthIsViewDistanceForEveryFormat) {
  // A wall facing the camera at distance 7 (eye at z = 5, wall at z = -2).
  Camera camera;
  camera.near = 0.5;
  camera.far = 50;
  const Scene scene = sceneOf(camera, 32, 32, {triangleMesh({{-50, -50, -2}, {50, -50, -2}, {0, 50, -2}})});
  for (std::size_t f = 0; f < depthFormatNames().size(); ++f) {
    const auto format = static_cast<DepthFormat>(f);
    const Frame frame = renderZBuffer(PreparedScene(scene), zbuffer::Variant::full, format);
    const double tolerance = format == DepthFormat::unorm16 ? 0.02 : 1e-4;  // one unorm16 step at d = 7 is ~0.01
    test::CaseFailures off(std::string("a depth is not the wall's distance 7 in ") + depthFormatName(format));
    for (std::size_t p = 0; p < frame.pixelCount(); ++p)
      off.expect(std::abs(frame.distances()[p] - 7.0) <= tolerance, [&] { return test::describePixel(frame, p) + ": " + std::to_string(frame.distances()[p]); });
    EXPECT_NO_FAILED_CASES(off);
  }
}

TEST(Conventions, TiesKeepTheEarlierTriangle) {
  const Mesh twice = triangleMesh({{-10, -10, 0}, {10, -10, 0}, {0, 10, 0}, {-10, -10, 0}, {10, -10, 0}, {0, 10, 0}});
  const Frame frame = renderZBuffer(PreparedScene(sceneOf(pixelCamera(32), 32, 32, {twice})));
  EXPECT_GT(coveredPixels(frame), 0);
  test::CaseFailures later("a pixel shows the later of two identical triangles");
  for (std::size_t p = 0; p < frame.pixelCount(); ++p)
    later.expect(frame.ids[p] == 0 || frame.ids[p] == 1, [&] { return test::describePixel(frame, p); });
  EXPECT_NO_FAILED_CASES(later);
}

TEST(Conventions, IdsCountObjectsThenInstancesThenTriangles) {
  Scene scene = sceneOf(pixelCamera(64), 64, 64, {makeBox(dvec3(4)), makeBox(dvec3(4))});
  scene.objects[0].transform.translate = {-20, 0, 0};
  scene.objects[1].instancing.kind = Instancing::Kind::grid;
  scene.objects[1].instancing.gridCount = {2, 1, 1};
  scene.objects[1].instancing.gridSpacing = {20, 0, 0};  // copies at x = -10 and x = +10
  const PreparedScene prepared(scene);
  ASSERT_EQ(prepared.triangleCount(), 36u);
  EXPECT_EQ(prepared.instanceOf(11).object, 0u);
  EXPECT_EQ(prepared.instanceOf(12).object, 1u);
  EXPECT_EQ(prepared.instanceOf(12).copy, 0u);
  EXPECT_EQ(prepared.instanceOf(24).copy, 1u);
  const Frame frame = renderZBuffer(prepared);
  // Pixel columns: x = -20 -> 12, x = -10 -> 22, x = +10 -> 42. The +z faces are triangles 10 and 11 of each box.
  EXPECT_GE(idAt(frame, 12, 32), 11u);
  EXPECT_LE(idAt(frame, 12, 32), 12u);
  EXPECT_GE(idAt(frame, 22, 32), 23u);
  EXPECT_LE(idAt(frame, 22, 32), 24u);
  EXPECT_GE(idAt(frame, 42, 32), 35u);
  EXPECT_LE(idAt(frame, 42, 32), 36u);
}

}  // namespace
}  // namespace hsr

namespace hsr {
namespace {

// Attributes are interpolated perspective-correctly: the surface point shading finds at a
// pixel center lies on the ray through that center, not where screen-space (affine)
// interpolation of the corners would put it, which differs visibly under perspective.
TEST(Conventions, AttributesArePerspectiveCorrect) {
  Camera camera;
  camera.eye = {0, 0, 2};
  const Mesh slanted = test::triangleMesh({{-1, -1, 0}, {1, -1, -8}, {0, 1, -1}});
  const Scene description = test::sceneOf(camera, 256, 256, {slanted});  // a PreparedScene keeps a pointer to its Scene
  const PreparedScene scene(description);
  const CameraTransform transform(camera, 256, 256);
  PixelShader<double> shader(scene, transform);
  Stats stats;
  const std::uint32_t only[] = {0};
  shader.setUp(only, 1, stats);
  dvec2 p[3];
  for (int k = 0; k < 3; ++k) p[k] = transform.pixelFromClip(transform.clipFromWorld(slanted.positions[std::size_t(k)]));
  std::mt19937 random(5);
  std::uniform_real_distribution<double> inner(0.15, 0.7);
  double largestAffineError = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double u = inner(random), v = inner(random);
    if (u + v > 0.85) continue;  // well inside the triangle, so that the pixel's center is too
    const dvec2 inside = (1 - u - v) * p[0] + u * p[1] + v * p[2];
    const int x = int(inside.x), y = int(inside.y);
    const dvec2 center(conventions::pixelCenter(x), conventions::pixelCenter(y));
    const dvec3 surface = shader.surfacePoint(0, x, y).position;
    EXPECT_NEAR(glm::distance(transform.pixelFromClip(transform.clipFromWorld(surface)), center), 0.0, 1e-9);
    // The affine answer: the corners weighted by the center's barycentrics on screen.
    const double area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
    const double affineU = ((center.x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (center.y - p[0].y)) / area;
    const double affineV = ((p[1].x - p[0].x) * (center.y - p[0].y) - (center.x - p[0].x) * (p[1].y - p[0].y)) / area;
    const dvec3 affine = (1 - affineU - affineV) * slanted.positions[0] + affineU * slanted.positions[1] + affineV * slanted.positions[2];
    largestAffineError = std::max(largestAffineError, glm::distance(affine, surface));
  }
  EXPECT_GT(largestAffineError, 0.1);  // the difference perspective correction makes here, in world units
}

}  // namespace
}  // namespace hsr
