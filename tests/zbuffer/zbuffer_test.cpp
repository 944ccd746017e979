// The z-buffer's two variants agree bit for bit, and the output does not depend on
// the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "algorithms/zbuffer/zbuffer.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

bool sameBits(const Frame& a, const Frame& b) {
  return a.ids == b.ids && a.color == b.color &&
         std::memcmp(a.distances().data(), b.distances().data(), a.distances().size() * sizeof(float)) == 0;
}

TEST(ZBuffer, SameBitsForAnyThreadCount) {
  for (const char* name : {"scenes/counters.toml", "scenes/trees.toml", "scenes/hard/coplanar.toml"}) {
    const Scene scene = loadScene(test::sourcePath(name));
    PreparedScene prepared(scene);
    prepared.setSize(400, 300);
    for (const auto variant : {zbuffer::Variant::full, zbuffer::Variant::scanline}) {
      const Frame one = test::renderZBuffer(prepared, variant, DepthFormat::float32, 1);
      EXPECT_GT(std::count(one.ids.begin(), one.ids.end(), 0u), 0) << name;
      for (int threads : {2, 3, 8}) EXPECT_TRUE(sameBits(one, test::renderZBuffer(prepared, variant, DepthFormat::float32, threads))) << name << " with " << threads << " threads";
    }
  }
}

TEST(ZBuffer, ScanlineAgreesWithFullFrameInEveryFormat) {
  for (const char* name : {"scenes/counters.toml", "scenes/hard/coplanar.toml", "scenes/hard/near_plane.toml"}) {
    const Scene scene = loadScene(test::sourcePath(name));
    PreparedScene prepared(scene);
    prepared.setSize(320, 240);
    for (std::size_t f = 0; f < depthFormatNames().size(); ++f) {
      const auto format = static_cast<DepthFormat>(f);
      EXPECT_TRUE(sameBits(test::renderZBuffer(prepared, zbuffer::Variant::full, format, 2),
                           test::renderZBuffer(prepared, zbuffer::Variant::scanline, format, 2)))
          << name << " " << depthFormatName(format);
    }
  }
}

TEST(ZBuffer, CountersShowWhatEachVariantDid) {
  const Scene scene = loadScene(test::sourcePath("scenes/counters.toml"));
  PreparedScene prepared(scene);
  prepared.setSize(640, 360);
  Stats full, scanline;
  test::render(prepared, zbuffer::Knobs{zbuffer::Variant::full, DepthFormat::unorm16}, 2, full);
  test::render(prepared, zbuffer::Knobs{zbuffer::Variant::scanline, DepthFormat::unorm16}, 2, scanline);
  // The same fragments are tested and written; only the memory differs.
  EXPECT_EQ(full.counter("fragments tested"), scanline.counter("fragments tested"));
  EXPECT_EQ(full.counter("fragments written"), scanline.counter("fragments written"));
  EXPECT_GT(full.counter("fragments tested"), full.counter("fragments written"));  // some fragments lose
  EXPECT_EQ(full.counter("depth buffer bytes"), 640 * 360 * 2);
  EXPECT_EQ(scanline.counter("depth buffer bytes"), 2 * 640 * 2);  // one row per worker
  EXPECT_GT(scanline.counter("active triangles summed over rows"), 0);
  // The scanline variant decodes each row before its buffer is reused; the full frame
  // keeps its buffer, and counters has no pass that asks for distances.
  EXPECT_EQ(scanline.counter(kDistancesDecodedCounter), 640 * 360);
  EXPECT_EQ(full.counter(kDistancesDecodedCounter), 0);
  // Most of the 31 counters are beside or behind the camera and never reach the rasterizer.
  EXPECT_GT(full.counter("triangles outside view"), full.counter("triangles in") / 2);
}

// Step 3 waits for a stage that asks: the full frame leaves its depth buffer as the format
// stored it, and the first call to distances() decodes it, once, to the distances the
// scanline variant decodes row by row. Asked for ids alone, it keeps nothing, and asking
// for distances then is a bug in the caller, stopped with a message.
TEST(ZBuffer, TheFullFrameDecodesItsDistancesOnceWhenAskedFor) {
  const test::LoadedScene counters(test::sourcePath("scenes/counters.toml"), 320);
  Stats setUp;
  const ScreenGeometry geometry = buildScreenTriangles(counters.prepared, {}, 2, setUp);
  for (const DepthFormat format : {DepthFormat::float32, DepthFormat::unorm24})
    for (const zbuffer::Path path : {zbuffer::Path::simd, zbuffer::Path::scalar}) {
      const std::string what = std::string(depthFormatName(format)) + (path == zbuffer::Path::simd ? " simd" : " scalar");
      Frame frame(counters.prepared.width(), counters.prepared.height()), eager(frame.width, frame.height);
      Stats stats, asked, scanlineStats;
      zbuffer::renderFullFrame(geometry, format, 2, frame, stats, {.path = path});
      EXPECT_FALSE(frame.decoded()) << what;
      EXPECT_EQ(stats.counter(kDistancesDecodedCounter), 0) << what;
      const std::vector<float> first(frame.distances(&asked).begin(), frame.distances(&asked).end());
      EXPECT_TRUE(frame.decoded()) << what;
      EXPECT_EQ(asked.counter(kDistancesDecodedCounter), std::int64_t(frame.pixelCount())) << what << ": decoded once";
      zbuffer::renderScanline(geometry, format, 2, eager, scanlineStats);
      EXPECT_EQ(std::memcmp(first.data(), eager.distances().data(), first.size() * sizeof(float)), 0) << what;
      EXPECT_GT(std::count_if(first.begin(), first.end(), [](float d) { return std::isfinite(d) && d > 0; }), 0) << what;
    }
  Frame idsOnly(counters.prepared.width(), counters.prepared.height());
  zbuffer::renderFullFrame(geometry, DepthFormat::float32, 2, idsOnly, setUp, {.keepDepth = false});
  EXPECT_GT(std::count_if(idsOnly.ids.begin(), idsOnly.ids.end(), [](std::uint32_t id) { return id != 0; }), 0);
  const std::string style = GTEST_FLAG_GET(death_test_style);
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(idsOnly.distances(), "asked for ids alone");
  GTEST_FLAG_SET(death_test_style, style);
}

// A frame reused by another algorithm after the full frame left its depth undecoded (a
// study's frame, an interactive viewer's): the other algorithm's distances are its own,
// not decoded again as though they were the z-buffer's stored values.
TEST(ZBuffer, AnotherAlgorithmInAReusedFrameKeepsItsOwnDistances) {
  const test::LoadedScene counters(test::sourcePath("scenes/counters.toml"), 160);
  const PreparedScene& scene = counters.prepared;
  Stats stats;
  const VisibilityRequest request{scene, scene.camera(), nullptr, 2, stats};
  Visibility reused{Frame(scene.width(), scene.height()), std::nullopt}, fresh{Frame(scene.width(), scene.height()), std::nullopt};
  test::algorithmOf(zbuffer::Knobs{}).visibility(request, test::valuesOf(zbuffer::Knobs{}), reused);
  ASSERT_FALSE(reused.frame.decoded());
  for (Visibility* answer : {&reused, &fresh}) test::algorithmOf(ray_casting::Knobs{}).visibility(request, test::valuesOf(ray_casting::Knobs{}), *answer);
  EXPECT_EQ(reused.frame.ids, fresh.frame.ids);
  EXPECT_EQ(reused.frame.distances(), fresh.frame.distances());
}

TEST(ZBuffer, ShadingWorkFollowsTheDeclaredEffects) {
  Scene scene = loadScene(test::sourcePath("scenes/cube.toml"));
  for (const Shading shading : {Shading::none, Shading::flat, Shading::lambert}) {
    scene.effects.shading = shading;
    const PreparedScene prepared(scene);
    Stats stats;
    const Frame frame = test::render(prepared, zbuffer::Knobs{}, 1, stats);
    const auto covered = std::count_if(frame.ids.begin(), frame.ids.end(), [](std::uint32_t id) { return id != 0; });
    EXPECT_EQ(stats.counter("shading invocations"), covered);  // once per covered pixel, whatever the overdraw
    // Set up once per triangle shown (the cube shows three faces: six triangles), with
    // corner normals only when lambert interpolates them.
    EXPECT_EQ(stats.counter("shading set-ups"), 6) << shadingName(shading);
    EXPECT_EQ(stats.counter("normals computed"), shading == Shading::lambert ? 18 : 0) << shadingName(shading);
  }
}

}  // namespace
}  // namespace hsr
