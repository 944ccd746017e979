// The z-buffer's fast path (algorithms/zbuffer/fast_path.hpp) against the textbook loop:
// the same ids, the same depth bits and the same counters, on every shipped scene (hard
// cases included), on the property generator's random scenes, in the float formats, at
// a size whose width and height are not multiples of the 8-pixel blocks (so the masked
// lanes at the image's right edge run); and the block test does skip hidden work.
#include <gtest/gtest.h>

#include <cstring>

#include "algorithms/zbuffer/zbuffer.hpp"
#include "property/random_scene.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

struct Rendered {
  Frame frame;
  Stats stats;
};

Rendered visibilityBy(const PreparedScene& scene, zbuffer::Path path, DepthFormat format, int threads) {
  Rendered result{Frame(1, 1), Stats()};
  zbuffer::Knobs knobs;
  knobs.depthFormat = format;
  knobs.path = path;
  result.frame = test::visibilityOf(scene, knobs, threads, result.stats);
  return result;
}

// Empty when the two paths agree bit for bit, else what differs.
std::string differences(const PreparedScene& scene, DepthFormat format, int threads) {
  const Rendered textbook = visibilityBy(scene, zbuffer::Path::scalar, format, threads);
  const Rendered fast = visibilityBy(scene, zbuffer::Path::simd, format, threads);
  std::string found;
  if (fast.frame.ids != textbook.frame.ids) found += " ids";
  if (std::memcmp(fast.frame.distances().data(), textbook.frame.distances().data(), fast.frame.distances().size() * sizeof(float)) != 0) found += " depth";
  for (const char* counter : {"fragments tested", "fragments written", "depth ties"})
    if (fast.stats.counter(counter) != textbook.stats.counter(counter))
      found += std::string(" ") + counter + " (" + std::to_string(fast.stats.counter(counter)) + " against " +
               std::to_string(textbook.stats.counter(counter)) + ")";
  return found;
}

constexpr DepthFormat kFastFormats[] = {DepthFormat::float32, DepthFormat::reversedFloat32, DepthFormat::reversedFloat32Infinite};

TEST(FastPath, SameBitsAndCountersAsTheTextbookLoopOnEveryShippedScene) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: the fast path is the textbook loop here";
  for (const auto& file : test::shippedScenes()) {
    const Scene scene = loadScene(file);
    PreparedScene prepared(scene);
    prepared.setSize(317, 203);  // neither a multiple of 8: blocks cut by the image's edges
    for (const DepthFormat format : kFastFormats)
      EXPECT_EQ(differences(prepared, format, 2), "") << file.filename() << " " << depthFormatName(format);
  }
}

TEST(FastPath, SameBitsAndCountersAsTheTextbookLoopOnRandomScenes) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: the fast path is the textbook loop here";
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const test::RandomScene random = test::randomScene(seed);
    PreparedScene prepared(random.scene);
    prepared.setSize(150, 101);
    for (const DepthFormat format : kFastFormats)
      ASSERT_EQ(differences(prepared, format, 1), "") << "seed " << seed << " " << depthFormatName(format);
  }
}

// A frame is reused from render to render (an interactive viewer, the benchmarks), and
// the fast path draws depth in a buffer of its own: every id and distance of the frame
// must still come out as from a fresh one, by either path.
TEST(FastPath, AReusedFrameHoldingOtherValuesComesOutAsAFreshOne) {
  const test::LoadedScene cube(test::sourcePath("scenes/cube.toml"), 317);  // most blocks empty
  Stats setUp;
  const ScreenGeometry geometry = buildScreenTriangles(cube.prepared, {}, 2, setUp);
  for (const zbuffer::Path path : {zbuffer::Path::scalar, zbuffer::Path::simd}) {
    Frame fresh(cube.prepared.width(), cube.prepared.height()), reused(fresh.width, fresh.height);
    Stats stats;
    zbuffer::renderFullFrame(geometry, DepthFormat::float32, 2, fresh, stats, {.path = path});
    std::fill(reused.ids.begin(), reused.ids.end(), 0xDEADBEEFu);
    std::fill(reused.depth.begin(), reused.depth.end(), -1.0f);
    zbuffer::renderFullFrame(geometry, DepthFormat::float32, 2, reused, stats, {.path = path});
    EXPECT_EQ(reused.ids, fresh.ids) << (path == zbuffer::Path::simd ? "simd" : "scalar");
    EXPECT_EQ(reused.distances(), fresh.distances()) << (path == zbuffer::Path::simd ? "simd" : "scalar");
    EXPECT_GT(std::count(fresh.ids.begin(), fresh.ids.end(), conventions::kBackgroundId), fresh.ids.size() / 2);
  }
}

TEST(FastPath, SkipsMostOfTheCitysHiddenFragmentsByBlock) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: the fast path is the textbook loop here";
  const test::LoadedScene city(test::sourcePath("scenes/city.toml"), 640);
  const Rendered fast = visibilityBy(city.prepared, zbuffer::Path::simd, DepthFormat::float32, 2);
  const std::int64_t tested = fast.stats.counter("fragments tested"), written = fast.stats.counter("fragments written");
  const std::int64_t skipped = fast.stats.counter("fragments skipped by block depth");
  // The city's boxes come in random order, so most fragments lose; the block test finds
  // more than half of the losers without computing their depth, and never a winner.
  EXPECT_GT(tested, 3 * written);
  EXPECT_GT(skipped, (tested - written) / 2);
  EXPECT_LE(skipped, tested - written);
}

TEST(FastPath, IntegerFormatsAndNoDepthTestRunTheTextbookLoop) {
  const test::LoadedScene counters(test::sourcePath("scenes/counters.toml"), 320);
  for (const DepthFormat format : {DepthFormat::unorm24, DepthFormat::unorm16}) {
    const Rendered rendered = visibilityBy(counters.prepared, zbuffer::Path::simd, format, 2);
    const auto names = rendered.stats.counterNames();
    EXPECT_EQ(std::count(names.begin(), names.end(), "fragments skipped by block depth"), 0) << depthFormatName(format);
    EXPECT_GT(rendered.stats.counter("fragments tested"), 0);
  }
  Stats stats;
  zbuffer::Knobs withoutTest;
  withoutTest.depthTest = false;
  test::visibilityOf(counters.prepared, withoutTest, 2, stats);
  const auto names = stats.counterNames();
  EXPECT_EQ(std::count(names.begin(), names.end(), "fragments skipped by block depth"), 0);
}

}  // namespace
}  // namespace hsr
