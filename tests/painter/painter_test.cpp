// The painter's algorithm against the exact reference, and its contracts: the same bits
// on any thread count, one BSP tree for every eye, transparency blended back to front,
// the split cap reported, the budgets refusing before any work.
#include <gtest/gtest.h>

#include <cstring>

#include "algorithms/painter/bsp.hpp"
#include "algorithms/registry.hpp"
#include "renderer/reference/metrics.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

using painter::Variant;

TEST(PainterAgainstReference, NewellAndBspWrongPixelsAreOnlySnappingOrCoplanarity) {
  for (const auto& entry : std::filesystem::recursive_directory_iterator(test::sourcePath("scenes"))) {
    if (entry.path().extension() != ".toml" || test::isStudyLevel(entry.path())) continue;
    const test::LoadedScene loaded(entry.path(), 320);
    const PreparedScene& prepared = loaded.prepared;
    Stats stats;
    const ReferenceImage truth = traceReference(prepared, 0, stats);
    for (const Variant variant : {Variant::newell, Variant::bsp, Variant::sort}) {
      const painter::Knobs knobs = test::painterKnobs(variant);
      if (const std::string refusal = painter::refusal(prepared, knobs); !refusal.empty()) {
        std::printf("%-28s variant %d refused: %s\n", entry.path().filename().c_str(), int(variant), refusal.c_str());
        continue;
      }
      const Frame frame = test::renderPainter(prepared, knobs, 0);
      const SurfaceError error = surfaceError(frame, truth);
      const test::WrongPixels wrong = test::classifyWrongPixels(prepared, frame, truth);
      EXPECT_EQ(wrong.total(), error.wrongPixels);
      if (variant != Variant::sort) {  // the sort's error is the lesson, reported, not asserted
        EXPECT_EQ(wrong.unexplained, 0) << entry.path() << " variant " << int(variant);
        EXPECT_TRUE(frame.partial.empty()) << frame.partial;
      }
      std::printf("%-28s %-6s wrong %5ld of %6ld: snapping %4ld, coplanar %4ld, unexplained %5ld\n",
                  entry.path().filename().c_str(), variant == Variant::sort ? "sort" : variant == Variant::bsp ? "bsp" : "newell",
                  long(error.wrongPixels), long(error.comparedPixels), wrong.snapping, wrong.depthTie, wrong.unexplained);
    }
  }
}

TEST(Painter, SameBitsOnAnyThreadCount) {
  const test::LoadedScene loaded(test::sourcePath("scenes/counters.toml"), 320);
  const PreparedScene& prepared = loaded.prepared;
  for (const Variant variant : {Variant::sort, Variant::newell, Variant::bsp}) {
    const Frame one = test::renderPainter(prepared, test::painterKnobs(variant), 1);
    for (const int threads : {2, 3}) {
      const Frame many = test::renderPainter(prepared, test::painterKnobs(variant), threads);
      EXPECT_EQ(one.ids, many.ids) << int(variant) << " on " << threads << " threads";
      EXPECT_EQ(one.color, many.color);
      EXPECT_EQ(0, std::memcmp(one.depth.data(), many.depth.data(), one.depth.size() * sizeof(float)));
    }
  }
}

// The tree is built once, in world space; each eye only walks it. Six eyes all around
// the cyclic overlap (from above, the sides and below) all see it right.
TEST(PainterBsp, OneTreeServesEveryEye) {
  Scene scene = loadScene(test::sourcePath("scenes/hard/cyclic_overlap.toml"));
  const PreparedScene built(scene);
  Stats buildStats;
  const painter::BspTree tree(built, test::painterKnobs(Variant::bsp), buildStats);
  EXPECT_GT(buildStats.counter("bsp splits"), 0);
  const dvec3 eyes[] = {{0.3, -0.37, 8}, {6, 1, 4}, {-5, -4, 3}, {1, 6, -3}, {0.2, 0.1, -8}, {-7, 2, 0.5}};
  for (const dvec3& eye : eyes) {
    scene.camera.eye = eye;
    const PreparedScene prepared(scene);
    Stats stats;
    PaintedPieces painted{buildScreenTriangles(prepared, {}, 2, stats), {}};
    painted.order = tree.backToFront(prepared, painted.geometry, stats);
    Frame frame(prepared.width(), prepared.height());
    painter::paint(prepared, painted, 2, frame, stats);
    EXPECT_EQ(stats.counter("bsp splits"), 0) << "walking the tree builds nothing";
    const ReferenceImage truth = traceReference(prepared, 2, stats);
    const test::WrongPixels wrong = test::classifyWrongPixels(prepared, frame, truth);
    EXPECT_EQ(wrong.unexplained, 0) << "eye " << eye.x << "," << eye.y << "," << eye.z;
    EXPECT_LE(wrong.total(), 3);
  }
}

// Two squares in the pixel camera's world (world units are pixels): an opaque red one
// behind, and a blue one at opacity 0.25 in front of its right half.
Scene glassScene(bool transparency) {
  Scene scene = test::sceneOf(test::pixelCamera(40), 60, 40,
                              {test::triangleMesh({{-20, -10, 0}, {0, -10, 0}, {0, 10, 0}, {-20, -10, 0}, {0, 10, 0}, {-20, 10, 0}}),
                               test::triangleMesh({{-10, -10, 2}, {20, -10, 2}, {20, 10, 2}, {-10, -10, 2}, {20, 10, 2}, {-10, 10, 2}})});
  scene.background = vec3(0, 1, 0);
  scene.objects[0].color = vec3(1, 0, 0);
  scene.objects[1].color = vec3(0, 0, 1);
  scene.effects.transparency = transparency;
  scene.objects[1].opacity = transparency ? 0.25 : 1.0;
  return scene;
}

TEST(PainterTransparency, BlendsBackToFrontWithPorterDuffOver) {
  const Scene scene = glassScene(true);
  const PreparedScene prepared(scene);
  for (const Variant variant : {Variant::sort, Variant::newell, Variant::bsp}) {
    Stats stats;
    const Frame frame = test::render(prepared, test::painterKnobs(variant), 2, stats);
    const auto rgb = [&](int x, int y) {
      const std::uint8_t* p = &frame.color[4 * (std::size_t(y) * 60 + std::size_t(x))];
      return std::array<int, 3>{p[0], p[1], p[2]};
    };
    // Pixel x is world x + 30. (25, 20): blue over red. (40, 20): blue over the green
    // background. (15, 20): red alone. 0.25 and 0.75 of 255 round to 64 and 191.
    EXPECT_EQ(rgb(25, 20), (std::array<int, 3>{191, 0, 64}));
    EXPECT_EQ(rgb(40, 20), (std::array<int, 3>{0, 191, 64}));
    EXPECT_EQ(rgb(15, 20), (std::array<int, 3>{255, 0, 0}));
    EXPECT_GT(frame.ids[20 * 60 + 25], prepared.instances()[1].firstTriangle) << "the id is the nearest surface's";
    EXPECT_EQ(stats.counter("blended writes"), 30 * 20) << "every pixel of the blue square, once";
  }
}

TEST(PainterTransparency, AnOpaqueSceneBlendsNothing) {
  const Scene scene = glassScene(false);
  const PreparedScene prepared(scene);
  Stats stats;
  const Frame frame = test::render(prepared, test::painterKnobs(Variant::bsp), 2, stats);
  EXPECT_EQ(stats.counter("blended writes"), 0);
  long covered = 0;
  for (const std::uint32_t id : frame.ids) covered += id != 0;
  EXPECT_EQ(stats.counter("shading invocations"), covered) << "deferred: once per covered pixel, whatever the overdraw";
  EXPECT_GT(stats.counter("fragments written"), covered) << "the squares overlap";
}

TEST(PainterTransparency, AlgorithmsThatKeepOnlyTheNearestSurfaceRefuse) {
  const Scene transparentScene = glassScene(true), opaqueScene = glassScene(false);
  const PreparedScene transparent(transparentScene), opaque(opaqueScene);
  for (const char* name : {"ray_casting"}) {
    const pipeline::Configuration configuration = pipeline::configurationOf(findAlgorithm(name), {});
    EXPECT_NE(pipeline::refusal(transparent, configuration).find("transparency"), std::string::npos) << name;
    EXPECT_EQ(pipeline::refusal(opaque, configuration), "") << name;
  }
  for (const char* name : {"painter", "zbuffer"}) {
    const pipeline::Configuration configuration = pipeline::configurationOf(findAlgorithm(name), {});
    EXPECT_EQ(pipeline::refusal(transparent, configuration), "") << name << " blends back to front";
  }
}

TEST(PainterNewell, TheSplitCapLabelsThePartialImage) {
  const test::LoadedScene loaded(test::sourcePath("scenes/hard/cyclic_overlap.toml"));
  const PreparedScene& prepared = loaded.prepared;
  painter::Knobs knobs = test::painterKnobs(Variant::newell);
  Stats full;
  EXPECT_EQ(test::render(prepared, knobs, 2, full).partial, "");
  EXPECT_GT(full.counter("newell splits"), 0);
  knobs.splitCap = 0;
  Stats capped;
  const Frame frame = test::render(prepared, knobs, 2, capped);
  EXPECT_NE(frame.partial.find("split-cap=0"), std::string::npos) << frame.partial;
  EXPECT_EQ(capped.counter("newell splits"), 0);
  EXPECT_GT(capped.counter("newell unresolved conflicts"), 0);
}

TEST(PainterBudgets, RefuseBeforeAnyWorkAndNameTheKnob) {
  const test::LoadedScene loaded(test::sourcePath("scenes/counters.toml"));
  const PreparedScene& prepared = loaded.prepared;
  painter::Knobs newell = test::painterKnobs(Variant::newell);
  EXPECT_EQ(painter::refusal(prepared, newell), "");
  newell.budget = 1e6;
  EXPECT_NE(painter::refusal(prepared, newell).find("--knob budget=1e+06"), std::string::npos);
  painter::Knobs bsp = test::painterKnobs(Variant::bsp);
  EXPECT_EQ(painter::refusal(prepared, bsp), "");
  bsp.buildBudget = 1e5;
  EXPECT_NE(painter::refusal(prepared, bsp).find("--knob build-budget"), std::string::npos);
  EXPECT_EQ(painter::refusal(prepared, test::painterKnobs(Variant::sort)), "") << "the sort has no quadratic part";
}

}  // namespace
}  // namespace hsr
