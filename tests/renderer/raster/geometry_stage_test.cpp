// The geometry stage's vertex step: screenVertices, which runs four vertices to a vector
// where the CPU has AVX2, must give screenVertex's bits for every vertex, wherever the
// camera and the vertex are. And its triangle step's output: the same list for any
// thread count and storage (one worker with room kept from an earlier frame appends in
// order; otherwise chunks are concatenated), and the same built into reused storage as
// built fresh.
#include <gtest/gtest.h>

#include <bit>
#include <random>
#include <vector>

#include "floating_point_traps.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "renderer/scene/visible_set.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

// A vertex's fields as bits: the pixel and depth only where screenVertex sets them (in
// front of the near plane).
std::vector<std::uint64_t> bitsOf(const ScreenVertex& vertex) {
  if (vertex.outside & kNearPlane) return {vertex.outside};
  return {vertex.outside, std::bit_cast<std::uint64_t>(vertex.pixel.x), std::bit_cast<std::uint64_t>(vertex.pixel.y),
          std::bit_cast<std::uint64_t>(vertex.depth)};
}

TEST(Geometry, VerticesFourAtATimeAreTheTextbookVertexBitForBit) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "no AVX2 here: screenVertices is screenVertex itself";
  // A division by zero or an invalid operation in a lane behind the eye would stop here.
  const test::TrappedFloatingPoint traps;
  std::mt19937 random(2027);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-2, 24);  // cameras and points up to 2^24 from the origin
  int compared = 0, behind = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Camera camera;
    camera.projection = trial % 3 == 0 ? Projection::orthographic : Projection::perspective;
    const double far = std::ldexp(1.0, exponent(random));
    camera.eye = dvec3(unit(random), unit(random), unit(random)) * far;
    camera.target = camera.eye + dvec3(unit(random), unit(random), unit(random) - 1.5);
    camera.fovYDegrees = 20 + 100 * (unit(random) + 1) / 2;
    camera.orthoHeight = std::ldexp(1.0, exponent(random));
    camera.near = std::ldexp(1.0, exponent(random) - 10);
    camera.far = camera.near * 1e4;
    const CameraTransform transform(camera, 64 + trial, 48 + 2 * trial);
    const ClipVolume volume(transform, trial % 2 == 0);
    // Points around the eye at every scale, the eye itself (w = d = 0 under perspective)
    // and points on the near plane; 4k + 3 of them, so the scalar tail runs too.
    std::vector<dvec3> points;
    for (int i = 0; i < 63; ++i) {
      const double scale = std::ldexp(1.0, exponent(random));
      points.push_back(camera.eye + dvec3(unit(random), unit(random), unit(random)) * scale);
    }
    points[5] = camera.eye;
    points[17] = camera.eye + transform.forward() * camera.near;
    std::vector<ScreenVertex> fast(points.size());
    screenVertices(transform, volume, points, fast.data());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const ScreenVertex textbook = screenVertex(transform, volume, points[i]);
      ASSERT_EQ(bitsOf(fast[i]), bitsOf(textbook)) << "trial " << trial << " point " << i;
      ++compared;
      behind += (textbook.outside & kNearPlane) != 0;
    }
  }
  // Both kinds of vertex were compared, many times.
  EXPECT_GT(behind, 1000);
  EXPECT_GT(compared - behind, 1000);
}

// Every field of every screen triangle and kept corner, as bits (padding left out).
std::vector<std::uint64_t> bitsOf(const ScreenGeometry& geometry) {
  std::vector<std::uint64_t> bits;
  const auto real = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  for (const ScreenTriangle& t : geometry.triangles) {
    for (int k = 0; k < 3; ++k) bits.insert(bits.end(), {std::uint64_t(t.edgeA[k]), std::uint64_t(t.edgeB[k]), std::uint64_t(t.edgeC[k])});
    bits.insert(bits.end(), {std::uint64_t(t.minX), std::uint64_t(t.maxX), std::uint64_t(t.minY), std::uint64_t(t.maxY), real(t.x0),
                             real(t.y0), real(t.t0), real(t.tdx), real(t.tdy), t.triangle, t.frontFacing});
  }
  bits.push_back(geometry.corners.size());
  for (const auto& corners : geometry.corners)
    for (const dvec3& corner : corners) bits.insert(bits.end(), {real(corner.x), real(corner.y), real(corner.z)});
  return bits;
}

// The stage's counts of what became of the triangles.
std::vector<std::int64_t> countsOf(const Stats& stats) {
  std::vector<std::int64_t> counts;
  for (const char* name : {"triangles in", "triangles outside view", "triangles clipped", "triangles between pixel centers", "screen triangles"})
    counts.push_back(stats.counter(name));
  return counts;
}

TEST(Geometry, OneWorkerAppendingInOrderGivesTheConcatenatedChunksBitForBit) {
  // The city's 100,008 triangles make 25 chunks, and a near plane cuts its streets.
  test::LoadedScene city(test::sourcePath("scenes/city.toml"), 320);
  for (const bool keepCorners : {false, true}) {
    // One worker into storage with room (kept from a frame before): the chunks appended
    // in order, to the list itself.
    Stats inOrderStats;
    ScreenGeometry inOrder = buildScreenTriangles(city.prepared, {.keepCorners = keepCorners}, 1, inOrderStats);
    inOrderStats = Stats();
    buildScreenTriangles(city.prepared, city.prepared.camera(), {.keepCorners = keepCorners}, 1, inOrderStats, inOrder);
    ASSERT_GT(inOrder.triangles.size(), 4096u) << "too few triangles to fill more than one chunk";
    ASSERT_EQ(inOrder.corners.size(), keepCorners ? inOrder.triangles.size() : 0);
    ASSERT_GT(inOrderStats.counter("triangles outside view"), 4096) << "too few rejected triangles to count in more than one chunk";
    // Into fresh storage, by one worker and by more: chunk by chunk, concatenated.
    for (const int threads : {1, 2, 3}) {
      Stats stats;
      EXPECT_EQ(bitsOf(buildScreenTriangles(city.prepared, {.keepCorners = keepCorners}, threads, stats)), bitsOf(inOrder))
          << threads << " threads, corners " << (keepCorners ? "kept" : "not kept");
      EXPECT_EQ(countsOf(stats), countsOf(inOrderStats)) << threads << " threads";
    }
  }
  // And nothing submitted: no chunk at all.
  const VisibleSet nothing;
  for (const int threads : {1, 2}) {
    Stats stats;
    EXPECT_TRUE(buildScreenTriangles(city.prepared, {.submitted = &nothing}, threads, stats).triangles.empty());
    EXPECT_EQ(countsOf(stats), std::vector<std::int64_t>(5, 0));
  }
}

// Geometry built again into a list that held another scene's triangles and corners
// (a benchmark's frames) comes out as the fresh list, for one worker and for more.
TEST(Geometry, AReusedListHoldingAnotherScenesTrianglesComesOutAsAFreshOne) {
  test::LoadedScene city(test::sourcePath("scenes/city.toml"), 320), counters(test::sourcePath("scenes/counters.toml"), 320);
  for (const int threads : {1, 2}) {
    Stats stats;
    ScreenGeometry reused = buildScreenTriangles(city.prepared, {.keepCorners = true}, threads, stats);
    ASSERT_FALSE(reused.corners.empty());
    buildScreenTriangles(counters.prepared, counters.prepared.camera(), {}, threads, stats, reused);
    const ScreenGeometry fresh = buildScreenTriangles(counters.prepared, {}, threads, stats);
    EXPECT_EQ(bitsOf(reused), bitsOf(fresh)) << threads << " threads";
    EXPECT_EQ(reused.camera.width(), counters.prepared.width());
  }
}

}  // namespace
}  // namespace hsr
