// Warnock's area subdivision: down to one pixel it shows what sampling every pixel on
// its own shows, bit for bit (shipped scenes, hard cases, random scenes); each rule decides the windows made for it; stopping at
// larger windows trades pixels for time, measurably; any thread count, the same bits.
#include <gtest/gtest.h>

#include "property/random_scene.hpp"
#include "renderer/reference/metrics.hpp"
#include "studies/allocation_meter.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

warnock::Knobs stoppingAt(int smallestWindow) {
  warnock::Knobs knobs;
  knobs.smallestWindow = smallestWindow;
  return knobs;
}

// Every shipped scene and hard case, at a size no power of two divides (windows of
// unequal halves, one-pixel-thin windows at the edges): the same ids and depths as the
// per-pixel loop. Rule 3 decides whole windows from depth bounds at their corners; a
// bound too tight, or a tie decided there instead of at a pixel, shows up here.
TEST(Warnock, SameImageAsSamplingEveryPixelOnItsOwn) {
  for (const auto& path : test::shippedScenes()) {
    if (test::isStudyLevel(path)) continue;
    const test::LoadedScene loaded(path, 317);
    Stats stats;
    const Frame frame = test::visibilityOf(loaded.prepared, warnock::Knobs{}, 2, stats);
    const Frame sampled = test::sampledOneByOne(loaded.prepared);
    test::expectSameAsSampledOneByOne(frame, sampled, "warnock on " + path.filename().string());
    EXPECT_GT(stats.counter("windows surrounded"), 0) << path;
  }
}

// The property generator's random scenes (slivers, coplanar pairs, interpenetrating
// triangles, perspective and orthographic cameras) at 150 x 101, the thousand the
// property tests use.
TEST(Warnock, SameImageAsSamplingEveryPixelOnItsOwnOnRandomScenes) {
  for (std::uint64_t seed = 1; seed <= 1000; ++seed) {
    const test::RandomScene random = test::randomScene(seed);
    PreparedScene prepared(random.scene);
    prepared.setSize(150, 101);
    Stats stats;
    const Frame frame = test::visibilityOf(prepared, warnock::Knobs{}, 1, stats);
    const Frame sampled = test::sampledOneByOne(prepared);
    ASSERT_EQ(frame.ids, sampled.ids) << "seed " << seed << " (camera " << random.camera << ")";
    ASSERT_TRUE(test::sameDepthBits(frame, sampled)) << "seed " << seed;
  }
}

TEST(Warnock, SameBitsAndCountersOnAnyThreadCount) {
  const test::LoadedScene loaded(test::sourcePath("scenes/dragons.toml"), 320);
  for (const int smallest : {1, 4}) {
    Stats one;
    const Frame reference = test::visibilityOf(loaded.prepared, stoppingAt(smallest), 1, one);
    for (const int threads : {2, 3}) {
      Stats many;
      const Frame frame = test::visibilityOf(loaded.prepared, stoppingAt(smallest), threads, many);
      EXPECT_EQ(reference.ids, frame.ids) << threads << " threads";
      EXPECT_TRUE(test::sameDepthBits(reference, frame));
      for (const std::string& counter : one.counterNames()) EXPECT_EQ(one.counter(counter), many.counter(counter)) << counter;
    }
  }
}

// Scenes built for one rule each, in pixel units (test::pixelCamera), 64 x 48.
struct Counted {
  Frame frame;
  Stats stats;
};
Counted subdivided(const std::vector<Mesh>& meshes, int smallest = 1) {
  const Scene scene = test::sceneOf(test::pixelCamera(48), 64, 48, meshes);
  const PreparedScene prepared(scene);
  Counted counted;
  counted.frame = test::visibilityOf(prepared, stoppingAt(smallest), 1, counted.stats);
  EXPECT_EQ(counted.frame.ids, test::sampledOneByOne(prepared).ids);
  return counted;
}

TEST(Warnock, OneSurroundingPolygonDecidesTheWholeImage) {
  const Counted counted = subdivided({test::triangleMesh({{-200, -200, 0}, {200, -200, 0}, {0, 200, 0}})});
  EXPECT_EQ(counted.stats.counter("windows examined"), 1);
  EXPECT_EQ(counted.stats.counter("windows surrounded"), 1);
  EXPECT_EQ(counted.stats.counter("polygons surrounding"), 1);
}

TEST(Warnock, APolygonOutsideEveryWindowLeavesItEmpty) {
  // Inside the view volume, but off the image's pixel centers once clipped to the guard band:
  // it reaches the rasterizer (if at all) only beside the image.
  const Counted counted = subdivided({test::triangleMesh({{-31.9, -23.9, 0}, {-31.6, -23.9, 0}, {-31.9, -23.6, 0}})});
  EXPECT_EQ(counted.stats.counter("windows examined"), 1);
  EXPECT_EQ(counted.stats.counter("windows empty"), 1);
}

TEST(Warnock, ALonePolygonIsScanConvertedInTheFirstWindowThatHoldsOnlyIt) {
  // Two small triangles in opposite corners: the first cut separates them, and each
  // quadrant holding one is drawn by rule 2; the other two are empty.
  const Counted counted = subdivided({test::triangleMesh({{-30, 20, 0}, {-20, 20, 0}, {-30, 10, 0}}),
                                      test::triangleMesh({{20, -20, 0}, {30, -20, 0}, {30, -10, 0}})});
  EXPECT_EQ(counted.stats.counter("windows examined"), 5);
  EXPECT_EQ(counted.stats.counter("windows subdivided"), 1);
  EXPECT_EQ(counted.stats.counter("windows with one polygon"), 2);
  EXPECT_EQ(counted.stats.counter("windows empty"), 2);
  EXPECT_EQ(counted.stats.counter("polygons contained"), 4);  // each in the whole image and in its quadrant
}

TEST(Warnock, ANearerSurroundingPolygonHidesWhateverIsBehindIt) {
  // A large triangle in front of a small one behind it: rule 3 fills the image at once.
  const Counted counted = subdivided({test::triangleMesh({{-5, -5, -1}, {5, -5, -1}, {0, 5, -1}}),
                                      test::triangleMesh({{-200, -200, 1}, {200, -200, 1}, {0, 200, 1}})});
  EXPECT_EQ(counted.stats.counter("windows examined"), 1);
  EXPECT_EQ(counted.stats.counter("windows surrounded"), 1);
  // Swapped in depth, the small one shows through: the subdivision goes down to its outline.
  const Counted behind = subdivided({test::triangleMesh({{-5, -5, 1}, {5, -5, 1}, {0, 5, 1}}),
                                     test::triangleMesh({{-200, -200, -1}, {200, -200, -1}, {0, 200, -1}})});
  EXPECT_GT(behind.stats.counter("windows subdivided"), 4);
  EXPECT_GT(std::count(behind.frame.ids.begin(), behind.frame.ids.end(), 1u), 40);
}

TEST(Warnock, InterpenetratingPolygonsAreDecidedPixelByPixelAlongWhereTheyCross) {
  // Two planes covering the image, z = (x - 5.3) / 100 and its opposite, crossing along
  // the vertical line x = 5.3 (pixel x 37.3, between the centers of columns 36 and 37,
  // and off every cut of the subdivision): no window straddling it has a surrounding
  // polygon in front, so the windows along it shrink to single pixels, one per row.
  const Counted counted = subdivided(test::crossingPlanes());
  EXPECT_GE(counted.stats.counter("windows examined"), 48);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) EXPECT_EQ(counted.frame.ids[std::size_t(y * 64 + x)], x < 37 ? 2u : 1u) << x << ", " << y;
}

TEST(Warnock, ExactTiesAreLeftToThePixelsAndGoToTheEarlierPolygon) {
  // The same triangle twice: every window holds two surrounding polygons at equal depth,
  // rule 3 never decides, and each pixel is decided at the smallest size.
  const Mesh twice = test::triangleMesh({{-200, -200, 0}, {200, -200, 0}, {0, 200, 0}, {-200, -200, 0}, {200, -200, 0}, {0, 200, 0}});
  const Counted counted = subdivided({twice});
  EXPECT_EQ(counted.stats.counter("windows at smallest size"), 64 * 48);
  EXPECT_EQ(std::count(counted.frame.ids.begin(), counted.frame.ids.end(), 1u), 64 * 48);
}

// Sixty coplanar squares leave every pixel they cover to the smallest windows: 1.4
// million one-pixel windows at 2048 x 2048. Level by level over the whole image, the
// last level's windows and lists took about 140 MB (560 MB at 4096 x 4096, measured
// before the hand-off); handed off in windows of 64 pixels, each subdivided by itself,
// the heap beyond the frame stays near a megabyte.
TEST(Warnock, WorkingMemoryStaysBoundedWhenEveryPixelNeedsItsOwnWindow) {
  const Scene coplanar = loadScene(test::sourcePath("scenes/hard/many_coplanar.toml"));
  PreparedScene scene(coplanar);
  scene.setSize(2048, 2048);
  Visibility answer{Frame(scene.width(), scene.height()), std::nullopt};
  const std::int64_t before = studies::heapBytesInUse();
  studies::resetHeapPeak();
  Stats stats;
  const AlgorithmEntry& entry = findAlgorithm("warnock");
  entry.visibility({scene, scene.camera(), nullptr, 2, stats}, resolveKnobs(entry, {}), answer);
  const std::int64_t working = studies::heapPeakBytes() - before;
  EXPECT_GT(stats.counter("windows at smallest size"), 1'000'000);
  EXPECT_LT(working, 16 << 20);
  std::printf("2048 x 2048 many_coplanar: %lld windows at the smallest size, working heap %.1f MiB\n",
              static_cast<long long>(stats.counter("windows at smallest size")), double(working) / (1 << 20));
}

// Stopping early is the accuracy-against-time knob: fewer windows, more wrong pixels.
TEST(Warnock, LargerStopsExamineFewerWindowsAndGetMorePixelsWrong) {
  const test::LoadedScene loaded(test::sourcePath("scenes/counters.toml"), 320);
  Stats referenceStats;
  const ReferenceImage truth = traceReference(loaded.prepared, 2, referenceStats);
  std::int64_t previousWindows = std::numeric_limits<std::int64_t>::max(), previousWrong = -1;
  for (const int smallest : {1, 2, 4, 8, 16}) {
    Stats stats;
    const Frame frame = test::visibilityOf(loaded.prepared, stoppingAt(smallest), 2, stats);
    const std::int64_t windows = stats.counter("windows examined"), wrong = surfaceError(frame, truth).wrongPixels;
    EXPECT_LT(windows, previousWindows) << "smallest-window=" << smallest;
    EXPECT_GT(wrong, previousWrong) << "smallest-window=" << smallest;
    if (smallest == 1) {
      EXPECT_EQ(test::classifyWrongPixels(loaded.prepared, frame, truth).unexplained, 0);
    }
    std::printf("smallest-window %2d: %6ld windows, %5ld wrong pixels\n", smallest, long(windows), long(wrong));
    previousWindows = windows, previousWrong = wrong;
  }
}

}  // namespace
}  // namespace hsr
