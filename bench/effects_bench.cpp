// The cost of each effect (README "Effects on demand"): the z-buffer on counters and
// dragons at 1280 x 720, single thread, with each effect added in turn
// (studies/effect_ladder). Compare each step's time with "none" in the same
// run: the ratio is what the effects cost; absolute times vary with the machine.
//   effects/SCENE/STEP   one render, visibility and every pass the step declares
#include <benchmark/benchmark.h>

#include <memory>

#include "algorithms/registry.hpp"
#include "bench_scenes.hpp"
#include "pipeline/pipeline.hpp"
#include "studies/effect_ladder.hpp"

namespace {

void renderStep(benchmark::State& state, const std::string& scene, std::size_t step) {
  static std::map<std::string, std::vector<hsr::studies::EffectStep>> ladders;
  auto& ladder = ladders[scene];
  if (ladder.empty()) ladder = hsr::studies::effectLadder(hsr::bench::sceneNamed(scene).scene);
  if (step >= ladder.size()) {
    state.SkipWithError("no such step");
    return;
  }
  hsr::PreparedScene prepared(ladder[step].scene);
  prepared.setSize(1280, 720);
  const hsr::pipeline::Configuration zbuffer = hsr::pipeline::configurationOf(hsr::findAlgorithm("zbuffer"), {});
  {
    hsr::Stats warmUp;  // builds the corner normals and the edge adjacency once, as a second frame would find them
    hsr::pipeline::render(prepared, zbuffer, 1, warmUp);
  }
  for (auto _ : state) {
    hsr::Stats stats;
    benchmark::DoNotOptimize(hsr::pipeline::render(prepared, zbuffer, 1, stats).frame.color.data());
  }
  state.SetLabel(ladder[step].name);
}

const bool registered = [] {
  for (const char* scene : hsr::bench::kScenes)
    for (std::size_t step = 0; step < 7; ++step)  // none .. + outline; neither scene is transparent
      benchmark::RegisterBenchmark(("effects/" + std::string(scene) + "/" + std::to_string(step)).c_str(),
                                   [scene, step](benchmark::State& state) { renderStep(state, scene, step); })
          ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
