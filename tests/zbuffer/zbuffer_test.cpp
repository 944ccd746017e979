// The z-buffer's two variants agree bit for bit, and the output does not depend on
// the thread count.
#include <gtest/gtest.h>

#include <cstring>

#include "algorithms/zbuffer/zbuffer.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

bool sameBits(const Frame& a, const Frame& b) {
  return a.ids == b.ids && a.color == b.color &&
         std::memcmp(a.depth.data(), b.depth.data(), a.depth.size() * sizeof(float)) == 0;
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
  // Most of the 31 counters are beside or behind the camera and never reach the rasterizer.
  EXPECT_GT(full.counter("triangles outside view"), full.counter("triangles in") / 2);
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
