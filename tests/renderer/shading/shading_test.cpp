// The shading pass in single precision (what every rasterizing algorithm runs) against
// the same pass in double precision (what the exact reference runs), on every shipped
// scene, hard cases far from the origin included, under flat, lambert and phong
// shading and with the scene's shadows: the float shader may move a channel by at most
// one level of 255, and only rarely (README "Speed" quotes the figures this measures).
#include <gtest/gtest.h>

#include <optional>

#include "algorithms/registry.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/shadow_maps.hpp"
#include "renderer/shading/shading.hpp"
#include "renderer/util/parallel.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

struct PrecisionError {
  int largestLevels = 0;             // the largest difference in any channel, in levels of 255
  std::int64_t channels = 0, differing = 0;
};

// Shades the z-buffer's ids of `scene` with both precisions and compares the bytes.
PrecisionError floatAgainstDouble(const Scene& scene, int width) {
  PreparedScene prepared(scene);
  prepared.setSize(width, std::max(1, width * scene.height / scene.width));
  Stats stats;
  Visibility visibility;
  pipeline::renderVisibility(prepared, pipeline::configurationOf(findAlgorithm("zbuffer"), {}), 2, stats, visibility);
  std::optional<pipeline::ShadowMaps> maps;
  if (scene.effects.shadows) maps.emplace(prepared, scene.effects.shadow, 2, stats);
  Frame single = visibility.frame, twice = visibility.frame;
  PixelShader<float> singleShader(prepared, prepared.camera(), maps ? &*maps : nullptr);
  PixelShader<double> doubleShader(prepared, prepared.camera(), maps ? &*maps : nullptr);
  shadeFrame(prepared, single, singleShader, 2, stats);
  shadeFrame(prepared, twice, doubleShader, 2, stats);
  PrecisionError error;
  for (std::size_t i = 0; i < single.color.size(); ++i) {
    if (i % 4 == 3 || single.ids[i / 4] == 0) continue;
    const int levels = std::abs(int(single.color[i]) - int(twice.color[i]));
    error.largestLevels = std::max(error.largestLevels, levels);
    ++error.channels;
    error.differing += levels > 0;
  }
  return error;
}

TEST(Shading, SinglePrecisionMovesAChannelByAtMostOneLevelOnEveryShippedScene) {
  PrecisionError total;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(test::sourcePath("scenes"))) {
    if (entry.path().extension() != ".toml" || test::isStudyLevel(entry.path())) continue;
    const Scene original = loadScene(entry.path());
    for (const Shading shading : {Shading::flat, Shading::lambert, Shading::phong}) {
      Scene scene = original;
      scene.effects.shading = shading;
      const PrecisionError error = floatAgainstDouble(scene, 320);
      EXPECT_LE(error.largestLevels, 1) << entry.path() << " " << shadingName(shading);
      total.largestLevels = std::max(total.largestLevels, error.largestLevels);
      total.channels += error.channels;
      total.differing += error.differing;
    }
  }
  ASSERT_GT(total.channels, 0);
  const double fraction = double(total.differing) / double(total.channels);
  EXPECT_LT(fraction, 1e-4) << total.differing << " of " << total.channels << " channels differ";
  std::printf("float against double shading: %lld of %lld channels differ (%.5f%%), by at most %d level\n",
              static_cast<long long>(total.differing), static_cast<long long>(total.channels), 100 * fraction, total.largestLevels);
}

// Corner normals keep each neighbouring face's normal and corner angles once computed
// (PreparedScene::faceGeometry), filled in by whichever shading thread asks first: the
// normals must have the same bits cold or warm, asked in any order, from any number of
// threads racing to fill the same entries.
TEST(Shading, CornerNormalsAreTheSameColdOrWarmInAnyOrderFromAnyThread) {
  const test::LoadedScene racing(test::sourcePath("scenes/bunny.toml")), backwards(test::sourcePath("scenes/bunny.toml"));
  Stats stats;
  const std::size_t count = racing.prepared.triangleCount();
  std::vector<std::array<dvec3, 3>> cold(count), warm(count), reversed(count);
  const VertexTriangles& around = racing.prepared.trianglesAroundVertices(stats, 2);
  // Two threads, each over every triangle from its own end, so both ask for the same
  // faces at about the same time.
  parallelFor(2, 2, [&](std::size_t thread, int) {
    for (std::size_t k = 0; k < count; ++k) {
      const auto t = static_cast<std::uint32_t>(thread == 0 ? k : count - 1 - k);
      std::array<dvec3, 3> normals;
      racing.prepared.cornerNormals(t, around, normals);
      if ((thread == 0) == (t < count / 2)) cold[t] = normals;
    }
  });
  for (std::uint32_t t = 0; t < count; ++t) racing.prepared.cornerNormals(t, around, warm[t]);
  const VertexTriangles& aroundBackwards = backwards.prepared.trianglesAroundVertices(stats, 1);
  for (std::uint32_t t = static_cast<std::uint32_t>(count); t-- > 0;) backwards.prepared.cornerNormals(t, aroundBackwards, reversed[t]);
  for (std::size_t t = 0; t < count; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      ASSERT_EQ(cold[t][k], warm[t][k]) << "triangle " << t << " corner " << k;
      ASSERT_EQ(cold[t][k], reversed[t][k]) << "triangle " << t << " corner " << k;
      ASSERT_NEAR(glm::length(cold[t][k]), 1, 1e-12);
    }
}

}  // namespace
}  // namespace hsr
