// The stages every rasterizing algorithm shares (README "Speed"), on one thread at
// 1280 x 720:
//   geometry/SCENE              the geometry stage (renderer/raster/screen_triangles): per triangle in
//   shading/SCENE/SHADING/REAL  the shading pass (renderer/shading/shading) over the z-buffer's
//                               ids: per shaded pixel, set-ups included; REAL float is what
//                               every algorithm runs, double what the exact reference runs
//   shading/SCENE/lambert+shadows/float   the same with shadow-map lookups (maps built once, outside the timing)
// "per item" is the time per triangle or per shaded pixel. Compare rows of one run only:
// absolute times move with the machine's load.
//   Run: build/bench/stages_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <optional>

#include "bench_scenes.hpp"
#include "pipeline/shadow_maps.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "renderer/shading/shading.hpp"

namespace {

void geometryStage(benchmark::State& state, const std::string& sceneName) {
  const hsr::PreparedScene& scene = *hsr::bench::sceneNamed(sceneName).prepared;
  for (auto _ : state) {
    hsr::Stats stats;
    benchmark::DoNotOptimize(hsr::buildScreenTriangles(scene, {}, 1, stats).triangles.data());
  }
  state.counters["per item"] =
      benchmark::Counter(double(scene.triangleCount()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <class Real>
void shadingPass(benchmark::State& state, const std::string& sceneName, hsr::Shading shading, bool shadows) {
  hsr::Scene scene = hsr::bench::sceneNamed(sceneName).scene;
  scene.effects.shading = shading;
  scene.effects.shadows = shadows;
  hsr::PreparedScene prepared(scene);
  prepared.setSize(1280, 720);
  hsr::Stats setUp;
  hsr::Visibility visibility;
  hsr::pipeline::renderVisibility(prepared, hsr::pipeline::configurationOf(hsr::findAlgorithm("zbuffer"), {}), 1, setUp, visibility);
  std::optional<hsr::pipeline::ShadowMaps> maps;
  if (shadows) maps.emplace(prepared, scene.effects.shadow, 1, setUp);
  hsr::Frame& frame = visibility.frame;
  std::int64_t shaded = 0;
  for (auto _ : state) {
    hsr::Stats stats;
    hsr::PixelShader<Real> shader(prepared, prepared.camera(), maps ? &*maps : nullptr);
    hsr::shadeFrame(prepared, frame, shader, 1, stats);
    benchmark::DoNotOptimize(frame.color.data());
    shaded = stats.counter("shading invocations");
  }
  state.counters["per item"] = benchmark::Counter(double(shaded), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

const bool registered = [] {
  for (const char* scene : {"city", "dragons", "counters"})
    benchmark::RegisterBenchmark(("geometry/" + std::string(scene)).c_str(), geometryStage, std::string(scene))->Unit(benchmark::kMillisecond);
  for (const char* scene : {"counters", "city", "dragons"}) {
    const std::string prefix = "shading/" + std::string(scene) + "/";
    for (const hsr::Shading shading : {hsr::Shading::none, hsr::Shading::flat, hsr::Shading::lambert, hsr::Shading::phong}) {
      const std::string name = prefix + hsr::shadingName(shading);
      benchmark::RegisterBenchmark((name + "/float").c_str(), shadingPass<float>, std::string(scene), shading, false)->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark((name + "/double").c_str(), shadingPass<double>, std::string(scene), shading, false)->Unit(benchmark::kMillisecond);
    }
    benchmark::RegisterBenchmark((prefix + "lambert+shadows/float").c_str(), shadingPass<float>, std::string(scene), hsr::Shading::lambert, true)
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace
