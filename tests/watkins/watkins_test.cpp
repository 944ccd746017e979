// Watkins' scanline algorithm: with its spans split where polygons cross (or in
// halves), it shows what sampling every pixel on its own shows, bit for bit (shipped
// scenes, hard cases, random scenes); spans decided at their ends need no split, and a
// crossing is found in one split; without splits it is wrong exactly where polygons pass
// through each other; its working memory does not grow with the image; any thread
// count, the same bits and counters.
#include <gtest/gtest.h>

#include "property/random_scene.hpp"
#include "studies/allocation_meter.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

using watkins::Split;

watkins::Knobs splitting(Split split) {
  watkins::Knobs knobs;
  knobs.split = split;
  return knobs;
}

TEST(Watkins, SameImageAsSamplingEveryPixelOnItsOwn) {
  for (const auto& path : test::shippedScenes()) {
    if (test::isStudyLevel(path)) continue;
    const test::LoadedScene loaded(path, 317);
    const Frame sampled = test::sampledOneByOne(loaded.prepared);
    for (const Split split : {Split::crossing, Split::halves}) {
      Stats stats;
      const Frame frame = test::visibilityOf(loaded.prepared, splitting(split), 2, stats);
      test::expectSameAsSampledOneByOne(frame, sampled, "watkins on " + path.filename().string());
    }
  }
}

TEST(Watkins, SameImageAsSamplingEveryPixelOnItsOwnOnRandomScenes) {
  for (std::uint64_t seed = 1; seed <= 1000; ++seed) {
    const test::RandomScene random = test::randomScene(seed);
    PreparedScene prepared(random.scene);
    prepared.setSize(150, 101);
    const Frame sampled = test::sampledOneByOne(prepared);
    for (const Split split : {Split::crossing, Split::halves}) {
      Stats stats;
      const Frame frame = test::visibilityOf(prepared, splitting(split), 1, stats);
      ASSERT_EQ(frame.ids, sampled.ids) << "seed " << seed << " (camera " << random.camera << ")";
      ASSERT_TRUE(test::sameDepthBits(frame, sampled)) << "seed " << seed;
    }
  }
}

TEST(Watkins, SameBitsAndCountersOnAnyThreadCount) {
  const test::LoadedScene loaded(test::sourcePath("scenes/dragons.toml"), 320);
  Stats one;
  const Frame reference = test::visibilityOf(loaded.prepared, watkins::Knobs{}, 1, one);
  for (const int threads : {2, 3}) {
    Stats many;
    const Frame frame = test::visibilityOf(loaded.prepared, watkins::Knobs{}, threads, many);
    EXPECT_EQ(reference.ids, frame.ids) << threads << " threads";
    EXPECT_TRUE(test::sameDepthBits(reference, frame));
    for (const std::string& counter : one.counterNames()) EXPECT_EQ(one.counter(counter), many.counter(counter)) << counter;
  }
}

// Scenes built for one case each, in pixel units (test::pixelCamera), 64 x 48.
struct Counted {
  Frame frame, sampled;
  Stats stats;
};
Counted scanned(const std::vector<Mesh>& meshes, Split split) {
  const Scene scene = test::sceneOf(test::pixelCamera(48), 64, 48, meshes);
  const PreparedScene prepared(scene);
  Counted counted;
  counted.frame = test::visibilityOf(prepared, splitting(split), 1, counted.stats);
  counted.sampled = test::sampledOneByOne(prepared);
  return counted;
}

TEST(Watkins, APolygonInFrontOfAnotherIsDecidedAtTheSpansEnds) {
  // A small triangle in front of a larger one: on the rows both cover, the span over the
  // small one holds both, and the small one is nearer at both ends.
  const Counted counted = scanned({test::triangleMesh({{-10, -10, 1}, {10, -10, 1}, {0, 10, 1}}),
                                   test::triangleMesh({{-30, -20, -1}, {30, -20, -1}, {0, 22, -1}})},
                                  Split::crossing);
  EXPECT_EQ(counted.frame.ids, counted.sampled.ids);
  EXPECT_EQ(counted.stats.counter("spans split"), 0);
  // One such span on each row the small triangle shows on.
  std::int64_t rowsShowingIt = 0;
  for (int y = 0; y < 48; ++y)
    rowsShowingIt += std::count(counted.frame.ids.begin() + y * 64, counted.frame.ids.begin() + (y + 1) * 64, 1u) > 0;
  EXPECT_GE(rowsShowingIt, 19);
  EXPECT_EQ(counted.stats.counter("spans decided at both ends"), rowsShowingIt);
}

// test::crossingPlanes: every row is one span holding both, nearest one at the left end
// and the other at the right.
using test::crossingPlanes;

TEST(Watkins, ACrossingIsFoundInOneSplitPerRow) {
  const Counted atCrossing = scanned(crossingPlanes(), Split::crossing);
  EXPECT_EQ(atCrossing.frame.ids, atCrossing.sampled.ids);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) ASSERT_EQ(atCrossing.frame.ids[std::size_t(y * 64 + x)], x < 37 ? 2u : 1u) << x << ", " << y;
  EXPECT_EQ(atCrossing.stats.counter("spans split"), 48);
  EXPECT_EQ(atCrossing.stats.counter("spans decided at both ends"), 2 * 48);
  // In halves the same image takes a split per halving until a part's ends agree.
  const Counted inHalves = scanned(crossingPlanes(), Split::halves);
  EXPECT_EQ(inHalves.frame.ids, inHalves.sampled.ids);
  EXPECT_GE(inHalves.stats.counter("spans split"), 4 * 48);
}

TEST(Watkins, WithoutSplitsTheSpanTakesItsLeftEndsPolygonAndIsWrongPastTheCrossing) {
  const Counted counted = scanned(crossingPlanes(), Split::none);
  EXPECT_EQ(counted.stats.counter("spans taken from their left end"), 48);
  std::int64_t wrong = 0;
  for (std::size_t p = 0; p < counted.frame.pixelCount(); ++p) wrong += counted.frame.ids[p] != counted.sampled.ids[p];
  EXPECT_EQ(wrong, 48 * (64 - 37));  // every pixel right of the crossing shows the left end's polygon
  // On the hard case of two triangles through each other, the same: wrong only without splits.
  const test::LoadedScene loaded(test::sourcePath("scenes/hard/interpenetrating.toml"), 320);
  Stats stats;
  const Frame none = test::visibilityOf(loaded.prepared, splitting(Split::none), 1, stats);
  const Frame sampled = test::sampledOneByOne(loaded.prepared);
  EXPECT_NE(none.ids, sampled.ids);
  EXPECT_GT(stats.counter("spans taken from their left end"), 0);
}

// The hard case of six planks through each other (scenes/hard/crossing_blinds): wider
// than the view, so on the rows through the middle of the band every change of plank
// along a row is a crossing of two planks inside a span, which only a split finds.
TEST(Watkins, TheBlindsNeedASplitAtEveryChangeOfPlankAlongARow) {
  const test::LoadedScene loaded(test::sourcePath("scenes/hard/crossing_blinds.toml"));
  const Frame sampled = test::sampledOneByOne(loaded.prepared);
  const int width = sampled.width, middle = sampled.height / 2;
  const auto plank = [&](std::size_t pixel) { return (sampled.ids[pixel] - 1) / 2; };  // two triangles a plank
  std::int64_t changes = 0;
  for (int y = middle - 10; y <= middle + 10; ++y)
    for (int x = 0; x + 1 < width; ++x) {
      const std::size_t pixel = std::size_t(y) * std::size_t(width) + std::size_t(x);
      ASSERT_NE(sampled.ids[pixel], 0u) << "the planks cover the middle rows from edge to edge";
      changes += plank(pixel) != plank(pixel + 1);
    }
  EXPECT_EQ(changes, 5 * 21);  // six planks, each the nearest somewhere along every row
  Stats stats;
  const Frame frame = test::visibilityOf(loaded.prepared, watkins::Knobs{}, 1, stats);
  EXPECT_EQ(frame.ids, sampled.ids);
  EXPECT_GE(stats.counter("spans split"), changes);
  Stats noSplits;
  const Frame none = test::visibilityOf(loaded.prepared, splitting(Split::none), 1, noSplits);
  std::int64_t wrong = 0;
  for (std::size_t p = 0; p < none.pixelCount(); ++p) wrong += none.ids[p] != sampled.ids[p];
  EXPECT_GT(wrong, sampled.pixelCount() / 20);
  std::printf("crossing_blinds: %lld plank changes on the middle 21 rows, %lld spans split; without splits %lld wrong pixels\n",
              static_cast<long long>(changes), static_cast<long long>(stats.counter("spans split")), static_cast<long long>(wrong));
}

// Watkins keeps no depth buffer: at 4096 x 4096 its heap beyond the frame it returns is
// the edge table (a bucket per row) and a row's lists, far below even one float32 row
// per pixel of a full-frame buffer (64 MiB).
TEST(Watkins, WorkingMemoryDoesNotGrowWithTheImage) {
  const Scene cube = loadScene(test::sourcePath("scenes/cube.toml"));
  PreparedScene scene(cube);
  scene.setSize(4096, 4096);
  Visibility answer{Frame(scene.width(), scene.height()), std::nullopt};
  const std::int64_t before = studies::heapBytesInUse();
  studies::resetHeapPeak();
  Stats stats;
  const AlgorithmEntry& entry = findAlgorithm("watkins");
  entry.visibility({scene, scene.camera(), nullptr, 2, stats}, resolveKnobs(entry, {}), answer);
  const std::int64_t working = studies::heapPeakBytes() - before;
  EXPECT_LT(working, 1 << 20);
  EXPECT_LE(stats.counter("most crossings on a row"), 2 * 12);
  std::printf("4096 x 4096 watkins: working heap %.3f MiB (a full-frame float32 depth buffer: 64 MiB)\n", double(working) / (1 << 20));
}

}  // namespace
}  // namespace hsr
