// Ray casting against the exact reference and against itself: bvh is exact on every
// shipped scene, naive gives bvh's image bit for bit, march's errors are the ones the
// method is known for, every variant is deterministic across thread counts, and the
// work budget refuses runs before they start.
#include <gtest/gtest.h>

#include <cmath>

#include "algorithms/ray_casting/ray_casting.hpp"
#include "algorithms/registry.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/util/error.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

using ray_casting::Variant;
using test::renderRayCasting;
using test::rayCastingKnobs;

// 320 pixels wide, the scene's aspect: the size the goldens use.
void goldenSize(PreparedScene& scene) {
  scene.setSize(320, std::max(1, 320 * scene.scene().height / scene.scene().width));
}

TEST(RayCasting, BvhHasNoWrongPixelAgainstTheReferenceOnEveryShippedScene) {
  for (const std::filesystem::path& file : test::shippedScenes()) {
    const std::string path = file.string();
    const Scene scene = loadScene(path);
    PreparedScene prepared(scene);
    goldenSize(prepared);
    if (!test::refusalOf(prepared, rayCastingKnobs(Variant::bvh)).empty()) continue;  // transparency: the z-buffer's or the painter's
    Stats stats;
    const ReferenceImage truth = traceReference(prepared, 2, stats);
    const Frame frame = renderRayCasting(prepared, rayCastingKnobs(Variant::bvh));
    const SurfaceError error = surfaceError(frame, truth);
    EXPECT_EQ(error.wrongPixels, 0) << path;
    EXPECT_GT(error.comparedPixels, std::int64_t(frame.pixelCount()) / 2) << path;
    // Both answer the same question for the same ray, so the depths agree to rounding.
    EXPECT_LT(error.depthErrorMax, 1e-6) << path;
  }
}

TEST(RayCasting, NaiveGivesBvhsImageBitForBit) {
  // dragons (399,136 triangles) is left out: naive would run 4e9 ray-triangle tests even
  // at this size; the other scenes still hold closed meshes, ties and the hard cases.
  for (const std::filesystem::path& file : test::shippedScenes()) {
    const std::string path = file.string();
    if (path.find("dragons") != std::string::npos) continue;
    const Scene scene = loadScene(path);
    PreparedScene prepared(scene);
    prepared.setSize(96, std::max(1, 96 * scene.height / scene.width));
    if (!test::refusalOf(prepared, rayCastingKnobs(Variant::naive)).empty()) continue;  // transparency
    const Frame naive = renderRayCasting(prepared, rayCastingKnobs(Variant::naive));
    const Frame bvh = renderRayCasting(prepared, rayCastingKnobs(Variant::bvh));
    EXPECT_EQ(naive.ids, bvh.ids) << path;
    EXPECT_EQ(naive.depth, bvh.depth) << path;
    EXPECT_EQ(naive.color, bvh.color) << path;
  }
}

TEST(RayCasting, EveryVariantGivesTheSameBitsOnAnyThreadCount) {
  const Scene trees = loadScene(test::sourcePath("scenes/trees.toml"));
  const Scene bunny = loadScene(test::sourcePath("scenes/bunny.toml"));  // naive: 57k triangles would take long
  for (const Variant which : {Variant::bvh, Variant::naive, Variant::march}) {
    PreparedScene prepared(which == Variant::naive ? bunny : trees);
    prepared.setSize(160, 90);
    const Frame one = renderRayCasting(prepared, rayCastingKnobs(which), 1);
    for (const int threads : {2, 3, 5}) {
      const Frame many = renderRayCasting(prepared, rayCastingKnobs(which), threads);
      EXPECT_EQ(one.ids, many.ids) << int(which) << " threads " << threads;
      EXPECT_EQ(one.depth, many.depth) << int(which) << " threads " << threads;
      EXPECT_EQ(one.color, many.color) << int(which) << " threads " << threads;
    }
  }
}

// The budget counts the work before any is done, and the message names the knob.
TEST(RayCasting, NaiveAndMarchRefuseRunsOverTheirBudget) {
  const Scene scene = loadScene(test::sourcePath("scenes/bunny.toml"));
  PreparedScene prepared(scene);  // 640 x 480 x 3,674 triangles = 1.13e9 tests
  ray_casting::Knobs naive = rayCastingKnobs(Variant::naive);
  EXPECT_NE(ray_casting::refusal(prepared, naive).find("--knob budget="), std::string::npos);
  EXPECT_THROW(renderRayCasting(prepared, naive), InputError);
  naive.budget = 1.2e9;
  EXPECT_EQ(ray_casting::refusal(prepared, naive), "");
  prepared.setSize(64, 48);
  EXPECT_EQ(ray_casting::refusal(prepared, rayCastingKnobs(Variant::naive)), "");

  ray_casting::Knobs march = rayCastingKnobs(Variant::march);
  march.step = {1e-5, true};  // 1e-7 of the diagonal: 1e7 samples per ray
  const std::string reason = ray_casting::refusal(prepared, march);
  EXPECT_NE(reason.find("samples"), std::string::npos) << reason;
  EXPECT_NE(reason.find("--knob step"), std::string::npos) << reason;
  EXPECT_EQ(ray_casting::refusal(prepared, rayCastingKnobs(Variant::bvh)), "");
}

TEST(RayCasting, StepIsInWorldUnitsOrAPercentageOfTheSceneDiagonal) {
  const Scene scene = loadScene(test::sourcePath("scenes/cube.toml"));
  PreparedScene prepared(scene);
  prepared.setSize(64, 48);
  Aabb bounds;
  for (const dvec3& p : prepared.positions()) bounds.grow(p);
  const double diagonal = glm::length(bounds.hi - bounds.lo);
  ray_casting::Knobs percent = rayCastingKnobs(Variant::march), world = rayCastingKnobs(Variant::march);
  percent.step = {2, true};
  world.step = {0.02 * diagonal, false};
  Stats percentStats, worldStats;
  const Frame a = test::render(prepared, percent, 1, percentStats);
  const Frame b = test::render(prepared, world, 1, worldStats);
  EXPECT_EQ(a.ids, b.ids);
  EXPECT_EQ(percentStats.counter("march samples"), worldStats.counter("march samples"));
}

// Through the registry, as the CLI and hsr compare reach it.
TEST(RayCasting, RegistryChecksNumericAndVariantOnlyKnobs) {
  const AlgorithmEntry& entry = findAlgorithm("ray_casting");
  EXPECT_EQ(resolveKnobs(entry, {}).at("variant"), "bvh");
  EXPECT_NO_THROW(resolveKnobs(entry, {{"variant", "march"}, {"step", "0.25"}, {"grid", "32"}, {"refine", "4"}}));
  EXPECT_NO_THROW(resolveKnobs(entry, {{"variant", "march"}, {"step", "1.5%"}}));
  EXPECT_THROW(resolveKnobs(entry, {{"variant", "march"}, {"grid", "12.5"}}), InputError);    // not an integer
  EXPECT_THROW(resolveKnobs(entry, {{"variant", "march"}, {"grid", "100000"}}), InputError);  // over the limit
  EXPECT_THROW(resolveKnobs(entry, {{"variant", "march"}, {"step", "fast"}}), InputError);
  EXPECT_THROW(resolveKnobs(entry, {{"variant", "march"}, {"refine", "2%"}}), InputError);  // no percentage here
  EXPECT_THROW(resolveKnobs(entry, {{"step", "1%"}}), InputError);                          // bvh has no step
  try {
    resolveKnobs(entry, {{"variant", "naive"}, {"refine", "2"}});
    ADD_FAILURE() << "refine was accepted for naive";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("applies only to variant march"), std::string::npos) << error.what();
  }
}

// The march's two knobs of accuracy: a shorter step finds more of what a long one
// skips, and, once refinement has found the surface, a finer grid names the right
// triangle more often (the grid thickens a mesh's surface by up to a voxel).
TEST(RayCasting, MarchErrorFallsWithTheStepAndTheGrid) {
  const Scene scene = loadScene(test::sourcePath("scenes/trees.toml"));
  PreparedScene prepared(scene);
  prepared.setSize(320, 180);
  Stats stats;
  const ReferenceImage truth = traceReference(prepared, 2, stats);
  const auto errorWith = [&](double stepPercent, int grid, int refine) {
    ray_casting::Knobs knobs = rayCastingKnobs(Variant::march);
    knobs.step = {stepPercent, true};
    knobs.grid = grid;
    knobs.refine = refine;
    return surfaceError(renderRayCasting(prepared, knobs), truth).pixelError;
  };
  EXPECT_GT(errorWith(2, 64, 0), 1.3 * errorWith(0.25, 64, 0));
  const double coarseGrid = errorWith(0.25, 16, 8), fineGrid = errorWith(0.25, 64, 8);
  EXPECT_GT(coarseGrid, 1.5 * fineGrid);
  EXPECT_GT(fineGrid, 0);  // still an approximation
}

}  // namespace
}  // namespace hsr
