// Cells, portals and potentially visible sets (algorithms/culling/cells/), single
// thread, at the levels' own 960 x 540 (README "Cells, portals and potentially visible
// sets", algorithms/culling/README.md):
//   portals/NARROWING/LEVEL   one frame's portal traversal and object tests, from the
//                             level's camera; items: frames
//   pvs-lookup/LEVEL          one frame's lookup of the eye's cell's set, the sets built
//   pvs-build/BUILD/LEVEL     the sets of every cell: conservative (portal chains) or
//                             sampled (8 and 64 eye points a cell, 32 x 32 cube faces);
//                             items: cells
//   frustum/LEVEL             for scale: frustum culling of the same frame
#include <benchmark/benchmark.h>

#include "algorithms/culling/cells/portals.hpp"
#include "algorithms/culling/cells/pvs.hpp"
#include "algorithms/culling/frustum.hpp"

namespace {

using namespace hsr::culling;

struct Level {
  hsr::Scene scene;
  hsr::PreparedScene prepared{scene};
  cells::CellMap map{prepared, "bench"};
  hsr::VisibleSet all = hsr::VisibleSet::everything(prepared);
  explicit Level(const std::string& name) : scene(hsr::loadScene(std::string(HSR_SOURCE_DIR) + "/scenes/study/" + name + ".toml")) {}
};

const Level& level(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Level>> loaded;
  auto& entry = loaded[name];
  if (!entry) entry = std::make_unique<Level>(name);
  return *entry;
}

void portalFrame(benchmark::State& state, portals::Narrowing narrowing, const std::string& name) {
  const Level& at = level(name);
  hsr::Stats stats;
  for (auto _ : state)
    benchmark::DoNotOptimize(portals::cull(at.prepared, at.map, at.prepared.camera(), {0, narrowing}, at.all, stats).triangles.data());
  state.SetItemsProcessed(state.iterations());
}

void pvsLookup(benchmark::State& state, const std::string& name) {
  const Level& at = level(name);
  hsr::Stats stats;
  const pvs::VisibleSets sets = pvs::build(at.prepared, at.map, {}, 1, stats);
  for (auto _ : state) benchmark::DoNotOptimize(pvs::cull(at.prepared, at.map, sets, at.prepared.camera(), at.all, stats).triangles.data());
  state.SetItemsProcessed(state.iterations());
}

void pvsBuild(benchmark::State& state, const pvs::Knobs& knobs, const std::string& name) {
  const Level& at = level(name);
  hsr::Stats stats;
  for (auto _ : state) benchmark::DoNotOptimize(pvs::build(at.prepared, at.map, knobs, 1, stats).objects.data());
  state.SetItemsProcessed(state.iterations() * std::int64_t(at.map.size()));
}

void frustumFrame(benchmark::State& state, const std::string& name) {
  const Level& at = level(name);
  hsr::Stats stats;
  for (auto _ : state)
    benchmark::DoNotOptimize(frustum::cull(at.prepared, at.prepared.camera(), frustum::Variant::aabb, at.all, 1, stats).triangles.data());
  state.SetItemsProcessed(state.iterations());
}

pvs::Knobs sampled(int samples) {
  pvs::Knobs knobs;
  knobs.build = pvs::Build::sampled, knobs.samples = samples, knobs.resolution = 32;
  return knobs;
}

}  // namespace

// Registered before main (bench_main.cpp), from the lists of levels and variants.
const bool registered = [] {
  for (const std::string name : {"indoor", "corridors"}) {
    benchmark::RegisterBenchmark(("frustum/" + name).c_str(), frustumFrame, name)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("portals/rect/" + name).c_str(), portalFrame, portals::Narrowing::rect, name)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("portals/polygon/" + name).c_str(), portalFrame, portals::Narrowing::polygon, name)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("pvs-lookup/" + name).c_str(), pvsLookup, name)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("pvs-build/conservative/" + name).c_str(), pvsBuild, pvs::Knobs{}, name)->Unit(benchmark::kMillisecond);
    for (const int samples : {8, 64})
      benchmark::RegisterBenchmark(("pvs-build/sampled-" + std::to_string(samples) + "/" + name).c_str(), pvsBuild, sampled(samples), name)
          ->Unit(benchmark::kMillisecond);
  }
  return true;
}();
