// Occlusion culling: the conservative rule never culls an object the exact reference
// sees, on the hard cases built against it and on every shipped scene, at any map size;
// the center rule's false culls on those cases are counted; the hierarchical-Z pyramid
// and the tile maxima only ever answer as the flat test allows; the previous-frame method
// shows an object that comes into view a frame late, never later.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <cstring>
#include <utility>
#include <vector>
#include <random>

#include "algorithms/culling/occlusion/fast_path.hpp"
#include "algorithms/culling/occlusion/occlusion.hpp"
#include "culling/culling_support.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/simd.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

using namespace culling::occlusion;

std::filesystem::path hard(const std::string& name) { return test::sourcePath("scenes/hard/" + name + ".toml"); }

// ---------------------------------------------------------------------------------
// The map's own machinery

DepthMap randomMap(int width, int height, std::mt19937_64& random) {
  DepthMap map(width, height);
  std::uniform_real_distribution<float> key(-1, 1);
  for (float& value : map.keys) value = random() % 5 == 0 ? std::numeric_limits<float>::infinity() : key(random);
  return map;
}

BoxFootprint randomFootprint(int width, int height, std::mt19937_64& random) {
  BoxFootprint box;
  box.x0 = int(random() % unsigned(width)), box.x1 = box.x0 + 1 + int(random() % unsigned(width - box.x0));
  box.y0 = int(random() % unsigned(height)), box.y1 = box.y0 + 1 + int(random() % unsigned(height - box.y0));
  box.nearest = std::uniform_real_distribution<float>(-1, 1.5f)(random);
  return box;
}

TEST(Occlusion, EveryPyramidLevelBoundsTheTexelsBelowItAtOddSizes) {
  // Odd sizes are where a reduction that drops the last row or column goes wrong.
  std::mt19937_64 random(3);
  for (const auto& [width, height] : {std::pair(1, 1), std::pair(37, 29), std::pair(255, 127), std::pair(100, 75), std::pair(64, 1)}) {
    const DepthMap map = randomMap(width, height, random);
    const Pyramid pyramid(map);
    EXPECT_EQ(pyramid.levels().back().width, 1);
    EXPECT_EQ(pyramid.levels().back().height, 1);
    for (std::size_t level = 1; level < pyramid.levels().size(); ++level)
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
          ASSERT_GE(pyramid.levels()[level].at(x >> level, y >> level), map.at(x, y))
              << width << "x" << height << " level " << level << " over texel " << x << "," << y;
    // A box the pyramid hides, the flat test hides too; and the pyramid hides fewer.
    int pyramidHidden = 0, flatHidden = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const BoxFootprint box = randomFootprint(width, height, random);
      std::int64_t read = 0;
      const bool coarse = pyramid.hidden(box, read), flat = hiddenOnMap(map, box, read);
      ASSERT_TRUE(!coarse || flat);
      pyramidHidden += coarse, flatHidden += flat;
    }
    EXPECT_LE(pyramidHidden, flatHidden);
  }
}

TEST(Occlusion, TileMaximaDecideExactlyAsTheFlatTest) {
  std::mt19937_64 random(5);
  DepthMap map = randomMap(100, 75, random);
  TileMaxima tiles(map);
  for (int trial = 0; trial < 3000; ++trial) {
    const BoxFootprint box = randomFootprint(100, 75, random);
    std::int64_t read = 0;
    ASSERT_EQ(tiles.hidden(box, read), hiddenOnMap(map, box, read)) << "trial " << trial;
    // Draw into a random rectangle and say so, as the occluder pass does.
    if (trial % 3 == 0) {
      const BoxFootprint drawn = randomFootprint(100, 75, random);
      for (int y = drawn.y0; y < drawn.y1; ++y)
        for (int x = drawn.x0; x < drawn.x1; ++x) map.at(x, y) = std::min(map.at(x, y), drawn.nearest);
      tiles.invalidate(drawn);
    }
  }
}

// A hard case's occluder map drawn by a rule with every object an occluder, and the
// exact reference traced at `samples` x `samples` pixel centers per texel.
struct MapAndTruth {
  test::LoadedScene loaded;
  ReferenceImage truth;
  CameraTransform camera;
  MapView view;
  DepthMap map;
  MapAndTruth(const std::string& scene, Rule rule, int mapWidth, int mapHeight, int samples)
      : loaded(hard(scene)),
        truth(traced(loaded.prepared, samples * mapWidth, samples * mapHeight)),
        camera(loaded.prepared.camera()),
        view(camera, mapWidth, mapHeight) {
    Knobs settings;
    settings.rule = rule, settings.mapWidth = mapWidth, settings.mapHeight = mapHeight;
    Stats stats;
    map = occluderDepthMap(loaded.prepared, view, settings,
                           chooseOccluders(loaded.prepared, camera, settings, VisibleSet::everything(loaded.prepared)), stats);
  }
  static ReferenceImage traced(PreparedScene& prepared, int width, int height) {
    prepared.setSize(width, height);
    Stats stats;
    return traceReference(prepared, 2, stats);
  }
};

// Every texel the conservative rule writes is covered, at every one of 4x4 sample points
// inside it, by something the exact reference sees at that depth or nearer. The
// reference is traced at four times the map's resolution, so its pixel centers are
// those sample points.
void expectConservativeMap(const std::string& scene, int mapWidth, int mapHeight) {
  const MapAndTruth drawn(scene, Rule::conservative, mapWidth, mapHeight, 4);
  std::int64_t written = 0;
  for (int y = 0; y < mapHeight; ++y)
    for (int x = 0; x < mapWidth; ++x) {
      if (std::isinf(drawn.map.at(x, y))) continue;
      ++written;
      for (int sy = 4 * y; sy < 4 * y + 4; ++sy)
        for (int sx = 4 * x; sx < 4 * x + 4; ++sx) {
          const std::size_t pixel = std::size_t(sy) * std::size_t(4 * mapWidth) + std::size_t(sx);
          ASSERT_NE(drawn.truth.frame.ids[pixel], 0u) << scene << ": texel " << x << "," << y << " written over background";
          ASSERT_LE(drawn.view.key(drawn.truth.frame.depth[pixel]), drawn.map.at(x, y)) << scene << ": texel " << x << "," << y << " too near";
        }
    }
  EXPECT_GT(written, mapWidth * mapHeight / 10) << scene << ": the occluders drew something";
}

// The center rule writes, at every texel whose center the reference sees an occluder
// at, that occluder's key to within the float arithmetic of a row (relative 1e-5), and
// nothing where the reference sees the background. The reference is traced at the
// map's own resolution, so its pixel centers are the texel centers; a center the
// reference finds ambiguous (exactly on an edge) may go either way.
void expectCenterMap(const std::string& scene, int mapWidth, int mapHeight) {
  const MapAndTruth drawn(scene, Rule::center, mapWidth, mapHeight, 1);
  std::int64_t compared = 0;
  for (int y = 0; y < mapHeight; ++y)
    for (int x = 0; x < mapWidth; ++x) {
      const std::size_t pixel = std::size_t(y) * std::size_t(mapWidth) + std::size_t(x);
      if (drawn.truth.ambiguous[pixel]) continue;
      ++compared;
      if (drawn.truth.frame.ids[pixel] == 0) {
        ASSERT_TRUE(std::isinf(drawn.map.at(x, y))) << scene << ": texel " << x << "," << y << " written over background";
        continue;
      }
      const double expected = drawn.view.key(drawn.truth.frame.depth[pixel]);
      ASSERT_NEAR(drawn.map.at(x, y), expected, 1e-5 * std::abs(expected)) << scene << ": texel " << x << "," << y;
    }
  EXPECT_GT(compared, mapWidth * mapHeight * 9 / 10) << scene << ": most centers are not ambiguous";
}

TEST(Occlusion, TheCenterRuleWritesTheNearestOccludersKeyAtEveryTexelCenter) {
  expectCenterMap("occ_orbit", 64, 48);          // boxes drawn as outlines, and a ground of two triangles
  expectCenterMap("occ_gap", 97, 61);            // odd sizes
  expectCenterMap("occ_edge_opening", 33, 25);
}

// Each rule's fast path (fast_path.hpp) writes a row as its textbook loop does, bit for
// bit: random faces' keys (negative, as -1 / d under perspective, and positive, as d
// under orthographic, of magnitudes from 1e-4 to 1e4; in one trial of five, keys that
// cross zero along the row, a run the conservative fast path leaves to the textbook
// loop), random runs of a row (shorter than eight texels among them), over texels
// holding random keys, empty ones among them. write(row, first, last, keys, count, fast)
// writes the run one way or the other.
template <typename Key, typename Write>
void expectRowsBitForBit(unsigned seed, Write&& write) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 2000; ++trial) {
    const double magnitude = std::pow(10.0, -4 + 8 * unit(random)), sign = trial % 3 == 0 ? 1.0 : -1.0;
    Key keys[3];
    const int count = 1 + trial % 3;
    for (Key& key : keys) {
      using Real = decltype(key.atZero);
      const bool crossesZero = trial % 5 == 4;
      key = crossesZero ? Key{Real(magnitude * (unit(random) - 0.5)), Real(magnitude * (unit(random) - 0.5) * 0.1)}
                        : Key{Real(sign * magnitude * (1 + unit(random))), Real(magnitude * (unit(random) - 0.5) * 1e-3)};
    }
    std::vector<float> held(64);
    for (float& texel : held) texel = unit(random) < 0.2 ? std::numeric_limits<float>::infinity() : float(sign * magnitude * (1 + 2 * unit(random)));
    const int first = int(unit(random) * 20), last = first + int(unit(random) * 43);
    std::vector<float> textbook = held, fast = held;
    write(textbook.data(), first, last, keys, count, false);
    write(fast.data(), first, last, keys, count, true);
    ASSERT_EQ(std::memcmp(fast.data(), textbook.data(), fast.size() * sizeof(float)), 0) << "trial " << trial;
  }
}

TEST(Occlusion, ConservativeRowsEightAtATimeAreTheTextbookLoopsBitForBit) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: rows are written one texel at a time here";
  int runsWrittenFast = 0;
  expectRowsBitForBit<RowKey>(27, [&](float* row, int first, int last, const RowKey* keys, int count, bool fast) {
    // The fast path writes the whole run, or nothing where it cannot be sure of its
    // rounding (a sign change), and the textbook loop writes it.
    const bool writtenFast = fast && conservativeRowEightAtATime(row, first, last, keys, count);
    runsWrittenFast += writtenFast;
    if (!writtenFast) conservativeRow(row, first, last, keys, count);
  });
  // Every run of keys of one sign (four trials of five) was the fast path's; not every
  // run that crosses zero.
  EXPECT_GE(runsWrittenFast, 1600);
  EXPECT_LT(runsWrittenFast, 2000);
}

// The conservative fast path's rounding by bits (fast_path.hpp) at its edges, where
// random keys almost never fall: keys that are floats exactly (a power of two, and
// not), a hair above a float, a hair below a power of two (rounding up carries into the
// exponent), of either sign, from 2^-90 to 2^90; each rounded as roundedUp rounds it.
// And keys beyond the range it takes (magnitudes under 1e-30 or over 1e30, within
// float's), which it must leave to the textbook loop. Each run is 11 texels: one vector
// and a tail of three under a mask.
TEST(Occlusion, TheConservativeRoundingByBitsAtItsEdges) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: rows are written one texel at a time here";
  std::vector<std::pair<double, bool>> magnitudes;  // and whether the fast path takes it
  for (const double power : {0x1p-90, 0x1p-20, 1.0, 0x1p20, 0x1p90})
    for (const double factor : {1.0, 1 - 0x1p-40, 1 + 0x1p-40, 1.5, 1.5 + 0x1p-30, 1.5 - 0x1p-30})
      magnitudes.emplace_back(power * factor, true);
  for (const double beyond : {1e-31, 0.5e-30, 1e31, 1e36}) magnitudes.emplace_back(beyond, false);
  for (const auto& [magnitude, taken] : magnitudes)
    for (const double sign : {1.0, -1.0}) {
      const RowKey key{sign * magnitude, 0};
      std::vector<float> textbook(11, std::numeric_limits<float>::infinity()), fast = textbook;
      conservativeRow(textbook.data(), 0, 10, &key, 1);
      const bool writtenFast = conservativeRowEightAtATime(fast.data(), 0, 10, &key, 1);
      EXPECT_EQ(writtenFast, taken) << sign * magnitude;
      if (!writtenFast) conservativeRow(fast.data(), 0, 10, &key, 1);
      EXPECT_EQ(std::memcmp(fast.data(), textbook.data(), fast.size() * sizeof(float)), 0) << sign * magnitude;
      EXPECT_GT(double(textbook[0]), sign * magnitude) << "rounded up";
    }
}

TEST(Occlusion, CenterRowsEightAtATimeAreTheTextbookLoopsBitForBit) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: rows are written one texel at a time here";
  expectRowsBitForBit<CenterRowKey>(28, [](float* row, int first, int last, const CenterRowKey* keys, int count, bool fast) {
    if (fast) centerRowEightAtATime(row, first, last, keys, count);  // the whole run, its last few texels under a mask
    else centerRow(row, first, last, keys, count);
  });
}

TEST(Occlusion, TheConservativeRuleWritesOnlyWhatTheReferenceConfirms) {
  expectConservativeMap("occ_orbit", 64, 48);        // boxes, and a ground of two triangles
  expectConservativeMap("occ_near", 40, 30);         // a box through the near plane, drawn clipped
  expectConservativeMap("occ_edge_opening", 33, 25);  // odd sizes
}

// An occluder whose box's footprint misses the map is not drawn (counted "outside the
// map"): drawn alone into an empty map, by either rule, it writes no texel. The city
// seen from its street has 1,945 such buildings beside it at the benchmark's 1920 x
// 1080; this checks them at a map of a tenth of that.
TEST(Occlusion, AnOccluderWhoseFootprintMissesTheMapWouldDrawNothing) {
  test::LoadedScene loaded(test::sourcePath("scenes/city.toml"));
  const PreparedScene& prepared = loaded.prepared;
  const CameraTransform camera = prepared.camera();
  const MapView view(camera, 192, 108);
  std::int64_t outside = 0;
  for (const Instance& instance : prepared.instances()) {
    const BoxFootprint box = footprint(view, instance.box);
    if (!box.empty() || box.crossesNear) continue;
    ++outside;
    for (const Rule rule : {Rule::center, Rule::conservative}) {
      DepthMap map(view.width, view.height);
      OccluderRasterizer rasterizer(view, rule, map);
      drawOccluder(prepared, instance, rasterizer);
      ASSERT_EQ(rasterizer.texelsWritten, 0) << "instance " << &instance - prepared.instances().data();
    }
  }
  EXPECT_GT(outside, 1000);
  Knobs settings;
  settings.mapWidth = view.width, settings.mapHeight = view.height;
  Stats stats;
  occluderDepthMap(prepared, view, settings, chooseOccluders(prepared, camera, settings, VisibleSet::everything(prepared)), stats);
  EXPECT_EQ(stats.counter("occlusion: occluders outside the map"), outside);
}

// ---------------------------------------------------------------------------------
// The hard cases

TEST(Occlusion, AnObjectSeenThroughAOnePixelGapIsCulledOnlyByTheCenterRule) {
  for (const std::string scene : {"occ_gap", "occ_edge_opening"}) {
    Judged judged(hard(scene));
    const PreparedScene& prepared = judged.loaded.prepared;
    const std::int64_t objects = std::int64_t(prepared.instances().size());
    ASSERT_EQ(judged.objectsFalselyCulled(VisibleSet{}), objects) << scene << ": the reference sees every object";
    for (const std::string pyramid : {"off", "on"}) {
      // At the default map, and at sizes that are no power of two.
      for (const std::string size : {"", ":map-width=255:map-height=127", ":map-width=100:map-height=75"}) {
        const std::string knobs = ":pyramid=" + pyramid + size;
        EXPECT_EQ(judged.objectsFalselyCulled(cull(prepared, "occlusion" + knobs)), 0) << scene << knobs;
      }
    }
    // The center rule writes the wall's depth into the texels around the opening, whose
    // centers lie on the wall: the object behind it is culled though one column of
    // pixels sees it.
    Stats stats;
    const VisibleSet center = cull(prepared, "occlusion:raster=center", stats);
    EXPECT_EQ(judged.objectsFalselyCulled(center), 1) << scene;
    EXPECT_EQ(stats.counter("occlusion: occludees culled"), 1) << scene;
    EXPECT_GT(surfaceError(renderKept(prepared, center), judged.truth).wrongPixels, 0) << scene << ": the object is missing";
  }
}

TEST(Occlusion, OccludersAtTheEyeAndAnOccludeeThroughTheNearPlane) {
  Judged judged(hard("occ_near"));
  const PreparedScene& prepared = judged.loaded.prepared;
  for (const std::string knobs : {"", ":pyramid=on", ":map-width=37:map-height=23"}) {
    Stats stats;
    const VisibleSet kept = cull(prepared, "occlusion" + knobs, stats);
    EXPECT_EQ(judged.objectsFalselyCulled(kept), 0) << knobs;
    // The box through the near plane (the last object) is never culled.
    const Instance& crossing = prepared.instances().back();
    EXPECT_TRUE(std::binary_search(kept.triangles.begin(), kept.triangles.end(), crossing.firstTriangle)) << knobs;
  }
  // The slab through the near plane is drawn clipped and still hides the box straight
  // behind it; the center rule culls what that does and more.
  Stats conservative, center;
  cull(prepared, "occlusion", conservative);
  const VisibleSet centerKept = cull(prepared, "occlusion:raster=center", center);
  EXPECT_GE(conservative.counter("occlusion: occludees culled"), 1);
  EXPECT_GE(center.counter("occlusion: occludees culled"), conservative.counter("occlusion: occludees culled"));
  EXPECT_EQ(judged.objectsFalselyCulled(centerKept), 0) << "nothing here is seen through a gap";
}

TEST(Occlusion, ThePreviousFrameShowsAnObjectComingIntoViewOneFrameLate) {
  Judged judged(hard("occ_orbit"));
  PreparedScene& prepared = judged.loaded.prepared;
  const culling::Pipeline pipeline = culling::parsePipeline("occlusion:previous-frame");
  // Frame 1: no previous frame, so nothing is culled.
  Stats first;
  const VisibleSet kept1 = culling::runPipeline(prepared, pipeline, 1, first, nullptr);
  EXPECT_EQ(kept1.triangles.size(), prepared.triangleCount());
  EXPECT_EQ(first.counter("occlusion: no previous frame"), 1);
  const Frame frame1 = renderKept(prepared, kept1);
  // Frame 2: the eye swings 35 degrees around the wall. Boxes the wall hid from the old
  // eye now show beside it, but the old depth still says hidden: they are late.
  const Camera before = judged.loaded.scene.camera;
  Camera& camera = judged.loaded.scene.camera;
  camera.eye = dvec3(glm::rotate(dmat4(1), glm::radians(35.0), dvec3(0, 1, 0)) * dvec4(camera.eye, 1));
  judged.retrace();
  const culling::PreviousFrame previous1{before, &frame1};
  ASSERT_FALSE(frame1.decoded()) << "the fast path leaves the distances for a reader to decode";
  Stats second;
  const VisibleSet kept2 = culling::runPipeline(prepared, pipeline, 1, second, &previous1);
  const std::int64_t late = judged.objectsFalselyCulled(kept2);
  EXPECT_GE(late, 1) << "a box behind the wall's end comes into view";
  EXPECT_EQ(second.counter("occlusion: occluders rasterized"), 0) << "the previous-frame method draws no occluders";
  EXPECT_GT(second.counter("occlusion: occludees culled"), late) << "it still culls the boxes that stay hidden";
  // The first frame's pass left its distances undecoded; this frame's map decoded them, and counted it.
  EXPECT_EQ(second.counter(kDistancesDecodedCounter), std::int64_t(frame1.pixelCount()));
  // Frame 3, the eye still: the late boxes are back, a frame late and no later.
  const Frame frame2 = renderKept(prepared, kept2);
  const culling::PreviousFrame previous2{camera, &frame2};
  Stats third;
  EXPECT_EQ(judged.objectsFalselyCulled(culling::runPipeline(prepared, pipeline, 1, third, &previous2)), 0);
  EXPECT_EQ(third.counter(kDistancesDecodedCounter), std::int64_t(frame2.pixelCount()));
  // Read again, the same frame's distances are not decoded again.
  Stats fourth;
  culling::runPipeline(prepared, pipeline, 1, fourth, &previous2);
  EXPECT_EQ(fourth.counter(kDistancesDecodedCounter), 0);
  // The same frame with occluders drawn for it culls nothing visible.
  EXPECT_EQ(judged.objectsFalselyCulled(cull(prepared, "occlusion")), 0);
}

// ---------------------------------------------------------------------------------
// Every shipped scene

class OcclusionShippedScene : public testing::TestWithParam<std::filesystem::path> {};

TEST_P(OcclusionShippedScene, TheConservativeRuleCullsNothingTheReferenceSees) {
  Judged judged(GetParam(), 160);
  const PreparedScene& scene = judged.loaded.prepared;
  const std::int64_t unculledWrong = surfaceError(test::renderZBuffer(scene), judged.truth).wrongPixels;
  for (const std::string pipeline : {"frustum,occlusion", "occlusion:pyramid=on:map-width=63:map-height=31",
                                     "occlusion:occluders=solid-angle:fraction=20%"}) {
    const VisibleSet kept = cull(scene, pipeline);
    EXPECT_EQ(judged.falseCulls(kept), 0) << pipeline;
    // Culling only what nobody sees can only mend the z-buffer's own wrong pixels.
    EXPECT_LE(surfaceError(renderKept(scene, kept), judged.truth).wrongPixels, unculledWrong) << pipeline;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, OcclusionShippedScene, testing::ValuesIn(test::shippedScenes()),
                         [](const testing::TestParamInfo<std::filesystem::path>& param) {
                           std::string name = param.param.parent_path().filename().string() + "_" + param.param.stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

// ---------------------------------------------------------------------------------
// Choosing occluders, and what the counters prove

TEST(Occlusion, AFractionOfOccludersIsTheLargestByTheChosenMeasure) {
  test::LoadedScene city(test::sourcePath("scenes/city.toml"), 480);
  const PreparedScene& scene = city.prepared;
  const CameraTransform& camera = scene.camera();
  const VisibleSet all = VisibleSet::everything(scene);
  for (const auto& [measure, name] : {std::pair(Occluders::volume, "volume"), std::pair(Occluders::solidAngle, "solid-angle")}) {
    Knobs settings;
    settings.occluders = measure, settings.fraction = {5, true};
    const std::vector<std::uint32_t> chosen = chooseOccluders(scene, camera, settings, all);
    EXPECT_EQ(chosen.size(), std::size_t(std::ceil(0.05 * 8334))) << name;
    // Every chosen object measures at least as much as every other one.
    const auto measureOf = [&](std::uint32_t instance) {
      const Instance& object = scene.instances()[instance];
      if (settings.occluders == Occluders::volume) {
        const dvec3 size = object.box.hi - object.box.lo;
        return size.x * size.y * size.z;
      }
      return object.sphereRadius / glm::length(object.sphereCenter - city.scene.camera.eye);
    };
    double smallestChosen = std::numeric_limits<double>::infinity(), largestOther = 0;
    std::vector<std::uint8_t> isChosen(scene.instances().size(), 0);
    for (const std::uint32_t instance : chosen) isChosen[instance] = 1, smallestChosen = std::min(smallestChosen, measureOf(instance));
    for (std::uint32_t instance = 0; instance < scene.instances().size(); ++instance)
      if (!isChosen[instance]) largestOther = std::max(largestOther, measureOf(instance));
    EXPECT_GE(smallestChosen, largestOther) << name;
  }
}

TEST(Occlusion, TheCityIsMostlyHiddenAndTheOccluderPassSkipsWhatIsBehind) {
  Judged judged(test::sourcePath("scenes/city.toml"), 480);
  const PreparedScene& scene = judged.loaded.prepared;
  Stats stats;
  const VisibleSet kept = cull(scene, "frustum,occlusion", stats, 1);
  EXPECT_EQ(judged.falseCulls(kept), 0);
  const std::int64_t tested = stats.counter("occlusion: occludees tested");
  EXPECT_GT(stats.counter("occlusion: occludees culled"), tested * 8 / 10) << "the near boxes hide most of the city";
  // Nearest first, an occluder behind the ones already drawn is not drawn at all.
  EXPECT_GT(stats.counter("occlusion: occluders skipped"), 5 * stats.counter("occlusion: occluders rasterized"));
  // The same set on any number of threads.
  EXPECT_EQ(cull(scene, "frustum,occlusion", stats, 3).triangles, kept.triangles);
}

// Occlusion culling pays only where objects hide one another; with min-depth-complexity
// the stage first estimates how many times over the objects' boxes cover the view, and
// runs only above the threshold: in the city it runs, on the cube it skips everything.
TEST(Occlusion, TheStageRunsOnlyWhereTheDepthComplexityCanPay) {
  const test::LoadedScene city(test::sourcePath("scenes/city.toml"), 480);
  Stats cityStats;
  const VisibleSet kept = cull(city.prepared, "frustum,occlusion:min-depth-complexity=2", cityStats, 1);
  EXPECT_GT(cityStats.counter("occlusion: estimated depth complexity x100"), 200);
  EXPECT_EQ(cityStats.counter("occlusion: skipped, below min-depth-complexity"), 0);
  EXPECT_EQ(kept.triangles, cull(city.prepared, "frustum,occlusion", cityStats, 1).triangles) << "the same stage once it runs";

  const test::LoadedScene cube(test::sourcePath("scenes/cube.toml"));
  Stats cubeStats;
  const VisibleSet all = cull(cube.prepared, "occlusion:min-depth-complexity=2", cubeStats);
  EXPECT_EQ(all.triangles, VisibleSet::everything(cube.prepared).triangles);
  EXPECT_LT(cubeStats.counter("occlusion: estimated depth complexity x100"), 100) << "one cube covers part of the view";
  EXPECT_EQ(cubeStats.counter("occlusion: skipped, below min-depth-complexity"), 1);
  EXPECT_EQ(cubeStats.counter("occlusion: occluders rasterized"), 0);
  EXPECT_EQ(cubeStats.counter("occlusion: occludees tested"), 0);
  // With the default 0 nothing is estimated: the stage always runs.
  Stats always;
  cull(cube.prepared, "occlusion", always);
  EXPECT_EQ(always.counter("occlusion: estimated depth complexity x100"), 0);
  EXPECT_EQ(always.counter("occlusion: occludees tested"), 1);
}

TEST(Occlusion, KnobsAreCheckedWhenThePipelineIsRead) {
  EXPECT_EQ(culling::parsePipeline("occlusion:depth-map:raster=center:map-width=64").front().name(),
            "occlusion:depth-map:map-width=64:raster=center");
  EXPECT_TRUE(culling::parsePipeline("occlusion:raster=center").front().wrong());
  EXPECT_TRUE(culling::parsePipeline("occlusion:previous-frame").front().wrong());
  EXPECT_FALSE(culling::parsePipeline("occlusion:pyramid=on").front().wrong());
  EXPECT_EQ(pipelineError("occlusion:map-width=0"),
            "--cull map-width=0: culling stage occlusion map-width must be an integer in [1, 4096]");
  EXPECT_EQ(pipelineError("occlusion:previous-frame:raster=center"),
            "--cull raster=center: culling stage occlusion raster applies only to variant depth-map, not to variant previous-frame");
  EXPECT_EQ(pipelineError("occlusion:fraction=5%"), "--cull: occlusion:fraction=5%: fraction applies only with occluders=volume or solid-angle");
  EXPECT_EQ(pipelineError("occlusion:depth-map:center"),
            "--cull: 'center' in 'occlusion:depth-map:center' is not a setting; expected occlusion[:VARIANT] followed by :KNOB=VALUE settings");
  EXPECT_EQ(pipelineError("frustum:sphere:raster=center"), "--cull raster=center: culling stage frustum has no knob 'raster'; expected one of variant");
}

}  // namespace
}  // namespace hsr
