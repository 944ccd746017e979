// The culling stages' throughput (README "Speed", algorithms/culling/README.md):
//   backface/VARIANT/SCENE     triangles tested per second
//   frustum/VARIANT/SCENE      the per-object and per-triangle tests on a shipped scene
//   objects/VARIANT/N          N one-triangle objects scattered around the camera:
//                              sphere and aabb test every object against six planes,
//                              bvh walks the object BVH with plane masking
#include <benchmark/benchmark.h>

#include <map>

#include "algorithms/culling/culling.hpp"
#include "bench_scenes.hpp"

namespace {

void cull(benchmark::State& state, const hsr::PreparedScene& scene, const std::string& pipeline, int threads) {
  const hsr::culling::Pipeline stages = hsr::culling::parsePipeline(pipeline);
  hsr::Stats warmUp;
  hsr::culling::runPipeline(scene, stages, threads, warmUp);  // builds the object BVH once
  std::int64_t kept = 0;
  for (auto _ : state) {
    hsr::Stats stats;
    kept = static_cast<std::int64_t>(hsr::culling::runPipeline(scene, stages, threads, stats).triangles.size());
    benchmark::DoNotOptimize(kept);
  }
  state.counters["kept"] = double(kept);
}

// Items: objects for a per-object stage, triangles otherwise.
void sceneStage(benchmark::State& state, const std::string& pipeline, const std::string& scene, bool perObject) {
  const hsr::PreparedScene& prepared = *hsr::bench::sceneNamed(scene).prepared;
  cull(state, prepared, pipeline, 1);
  state.SetItemsProcessed(state.iterations() * std::int64_t(perObject ? prepared.instances().size() : prepared.triangleCount()));
}

// N one-triangle objects scattered over a disc of radius 100 around a camera at its
// center: about a sixth of them in view.
const hsr::PreparedScene& scatteredObjects(std::size_t count) {
  static std::map<std::size_t, std::pair<std::unique_ptr<hsr::Scene>, std::unique_ptr<hsr::PreparedScene>>> made;
  auto& entry = made[count];
  if (!entry.second) {
    entry.first = std::make_unique<hsr::Scene>();
    hsr::Scene& scene = *entry.first;
    scene.width = 1280;
    scene.height = 720;
    scene.camera.eye = {0, 1, 0};
    scene.camera.target = {0, 1, -1};
    scene.camera.fovYDegrees = 60;
    scene.camera.far = 80;
    hsr::SceneObject object;
    object.mesh = std::make_shared<const hsr::Mesh>(hsr::Mesh{{{-0.2, 0, 0}, {0.2, 0, 0}, {0, 0.5, 0}}, {{0, 1, 2}}, {}});
    object.instancing.kind = hsr::Instancing::Kind::scatter;
    object.instancing.count = int(count);
    object.instancing.innerRadius = 1;
    object.instancing.radius = 100;
    scene.objects.push_back(object);
    entry.second = std::make_unique<hsr::PreparedScene>(scene);
  }
  return *entry.second;
}

void objects(benchmark::State& state, const std::string& variant) {
  const hsr::PreparedScene& scene = scatteredObjects(std::size_t(state.range(0)));
  cull(state, scene, "frustum:" + variant, 1);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

}  // namespace

// Registered before main (bench_main.cpp), from the lists of variants and scenes.
const bool registered = [] {
  for (const char* scene : {"dragons", "counters"}) {
    for (const char* variant : {"object", "screen", "view-direction"})
      benchmark::RegisterBenchmark((std::string("backface/") + variant + "/" + scene).c_str(), sceneStage,
                                   std::string("backface:") + variant, std::string(scene), false)
          ->Unit(benchmark::kMillisecond);
    for (const std::string variant : {"sphere", "aabb", "bvh", "triangle", "any-vertex"})
      benchmark::RegisterBenchmark(("frustum/" + variant + "/" + scene).c_str(), sceneStage, "frustum:" + variant, std::string(scene),
                                   variant == "sphere" || variant == "aabb" || variant == "bvh")
          ->Unit(benchmark::kMicrosecond);
  }
  for (const char* variant : {"sphere", "aabb", "bvh"})
    benchmark::RegisterBenchmark((std::string("objects/") + variant).c_str(), objects, std::string(variant))
        ->RangeMultiplier(10)
        ->Range(10000, 1000000)
        ->Unit(benchmark::kMicrosecond);
  return true;
}();
