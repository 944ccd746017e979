// The cost of each effect (README "Effects on demand"): the z-buffer on counters and
// dragons at 1280 x 720, single thread, with each effect added in turn
// (algorithms/effects: effectLadder). Compare each step's time with "none" in the same
// run: the ratio is what the effects cost; absolute times vary with the machine.
//   effects/SCENE/STEP   one render, visibility and every pass the step declares
#include <benchmark/benchmark.h>

#include <memory>

#include "algorithms/effects/effects.hpp"
#include "algorithms/registry.hpp"
#include "bench_scenes.hpp"

namespace {

void renderStep(benchmark::State& state, const std::string& scene, std::size_t step) {
  static std::map<std::string, std::vector<hsr::effects::EffectStep>> ladders;
  auto& ladder = ladders[scene];
  if (ladder.empty()) ladder = hsr::effects::effectLadder(hsr::bench::sceneNamed(scene).scene);
  if (step >= ladder.size()) {
    state.SkipWithError("no such step");
    return;
  }
  hsr::PreparedScene prepared(ladder[step].scene);
  prepared.setSize(1280, 720);
  const hsr::AlgorithmEntry& zbuffer = hsr::findAlgorithm("zbuffer");
  const hsr::KnobValues knobs = hsr::resolveKnobs(zbuffer, {});
  {
    hsr::Stats warmUp;  // builds the corner normals and the edge adjacency once, as a second frame would find them
    zbuffer.render(prepared, knobs, 1, warmUp);
  }
  for (auto _ : state) {
    hsr::Stats stats;
    benchmark::DoNotOptimize(zbuffer.render(prepared, knobs, 1, stats).color.data());
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

BENCHMARK_MAIN();
