// Ray casting's fast paths (algorithms/ray_casting/fast_path.hpp) against the textbook
// traversal: the same ids and the same depth bits on every shipped scene (hard cases
// included), at a size that is no multiple of the vector widths, and on the property
// generator's random scenes (orthographic views, eyes inside objects, rays along faces);
// and the rays set up four at a time are the rays set up one at a time, bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "algorithms/ray_casting/cast.hpp"
#include "algorithms/ray_casting/ray_casting.hpp"
#include "property/random_scene.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

using ray_casting::Path;

Frame visibilityBy(const PreparedScene& scene, Path path, int threads) {
  ray_casting::Knobs knobs;
  knobs.path = path;
  Stats stats;
  return test::visibilityOf(scene, knobs, threads, stats);
}

// Empty when the path agrees with the textbook traversal bit for bit, else what differs.
std::string differences(const PreparedScene& scene, Path path, int threads) {
  const Frame textbook = visibilityBy(scene, Path::scalar, threads);
  const Frame fast = visibilityBy(scene, path, threads);
  std::string found;
  if (fast.ids != textbook.ids) found += " ids";
  if (std::memcmp(fast.depth.data(), textbook.depth.data(), fast.depth.size() * sizeof(float)) != 0) found += " depth";
  return found;
}

constexpr Path kFastPaths[] = {Path::simd, Path::packet};
const char* nameOf(Path path) { return path == Path::simd ? "simd" : path == Path::packet ? "packet" : "scalar"; }

TEST(RayCastingFastPath, SameIdsAndDepthsAsTheTextbookTraversalOnEveryShippedScene) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: the fast paths are the textbook traversal here";
  for (const auto& file : test::shippedScenes()) {
    const Scene scene = loadScene(file);
    PreparedScene prepared(scene);
    prepared.setSize(317, 203);  // no multiple of 4 or 8: the last rays of a row run alone
    for (const Path path : kFastPaths) EXPECT_EQ(differences(prepared, path, 2), "") << file.filename() << " " << nameOf(path);
  }
}

TEST(RayCastingFastPath, SameIdsAndDepthsAsTheTextbookTraversalOnRandomScenes) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: the fast paths are the textbook traversal here";
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const test::RandomScene random = test::randomScene(seed);
    PreparedScene prepared(random.scene);
    prepared.setSize(150, 101);
    for (const Path path : kFastPaths)
      ASSERT_EQ(differences(prepared, path, 1), "") << "seed " << seed << " (" << random.camera << ") " << nameOf(path);
  }
}

// A packet visits a node once for its eight rays. When their directions spread (a small
// image), the interval bounds over the packet let it visit nodes none of its rays
// meets, unless each ray is tested at inner nodes too: then it visits no more nodes than
// its rays visit one at a time (without those tests, eight times more on the bunny).
TEST(RayCastingFastPath, PacketsOfSpreadRaysVisitNoMoreNodesThanSingleRays) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: the fast paths are the textbook traversal here";
  for (const char* name : {"scenes/bunny.toml", "scenes/dragons.toml", "scenes/counters.toml"}) {
    const test::LoadedScene loaded(test::sourcePath(name), 64);
    std::int64_t visited[2];
    for (const Path path : {Path::packet, Path::simd}) {
      ray_casting::Knobs knobs;
      knobs.path = path;
      Stats stats;
      test::visibilityOf(loaded.prepared, knobs, 1, stats);
      visited[path == Path::packet ? 0 : 1] = stats.counter("bvh nodes visited");
    }
    EXPECT_LE(visited[0], visited[1]) << name << ": packets " << visited[0] << " against single rays " << visited[1];
  }
}

// Every field of two set-ups, bit for bit.
std::string fieldsThatDiffer(const ray_casting::PixelRay& a, const ray_casting::PixelRay& b) {
  const auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  std::string found;
  for (int axis = 0; axis < 3; ++axis) {
    if (!same(a.ray.origin[axis], b.ray.origin[axis])) found += " origin";
    if (!same(a.ray.direction[axis], b.ray.direction[axis])) found += " direction";
    if (!same(a.inverseDirection[axis], b.inverseDirection[axis])) found += " inverse";
  }
  if (!same(a.startDistance, b.startDistance)) found += " startDistance";
  if (!same(a.slope, b.slope)) found += " slope";
  if (!same(a.tNear, b.tNear) || !same(a.tFar, b.tFar)) found += " near/far";
  return found;
}

TEST(RayCastingFastPath, RaysSetUpFourAtATimeAreTheRaysSetUpOneAtATime) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: rays are set up one at a time here";
  std::mt19937 random(11);
  std::uniform_real_distribution<double> position(-1e5, 1e5), unit(-1, 1);
  for (int trial = 0; trial < 60; ++trial) {
    Camera camera;
    camera.projection = trial % 3 == 0 ? Projection::orthographic : Projection::perspective;
    camera.orthoHeight = 7.5;
    camera.eye = dvec3(position(random), position(random), position(random));
    // Every third camera looks straight down an axis: the rays through the middle
    // column and row then have zero components (infinite inverses).
    camera.target = camera.eye + (trial % 3 == 1 ? dvec3(0, 0, -1) : dvec3(unit(random), unit(random), unit(random)));
    camera.up = trial % 3 == 1 ? dvec3(0, 1, 0) : glm::normalize(dvec3(unit(random), 1, unit(random)));
    const int width = 37 + trial % 5, height = 21;
    const CameraTransform transform(camera, width, height);
    for (int y = 0; y < height; ++y) {
      std::vector<ray_casting::PixelRay> together(static_cast<std::size_t>(width));
      ray_casting::setUpPixelRays(transform, y, 0, width, together.data());
      for (int x = 0; x < width; ++x) {
        const ray_casting::PixelRay alone(transform, transform.rayThroughPixel(conventions::pixelCenter(x), conventions::pixelCenter(y)));
        ASSERT_EQ(fieldsThatDiffer(together[std::size_t(x)], alone), "") << "trial " << trial << ", pixel (" << x << ", " << y << ")";
      }
    }
  }
}

}  // namespace
}  // namespace hsr
