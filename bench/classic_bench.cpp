// The rest of the classic taxonomy beside the z-buffer (Sutherland, Sproull and
// Schumacker 1974): each algorithm's visibility pass alone (geometry stage included, no
// shading), on counters (fill-bound), trees and dragons (geometry-bound) at 1280 x 720,
// one thread. Read the rows of one run as ratios to the z-buffer's on the same scene.
//
// Run: build/bench/classic_bench --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include "bench_scenes.hpp"

namespace {

// The configurations timed, as `hsr compare --algos` spells them.
struct Configuration {
  const char* algorithm;
  hsr::KnobSettings knobs;
  const char* label;
};
const Configuration kConfigurations[] = {
    {"zbuffer", {}, "zbuffer"},
    {"zbuffer", {{"path", "scalar"}}, "zbuffer path=scalar"},
    {"zbuffer", {{"variant", "scanline"}}, "zbuffer variant=scanline"},
    {"warnock", {}, "warnock"},
    {"warnock", {{"smallest-window", "4"}}, "warnock smallest-window=4"},
    {"warnock", {{"smallest-window", "16"}}, "warnock smallest-window=16"},
    {"watkins", {}, "watkins"},
    {"watkins", {{"split", "halves"}}, "watkins split=halves"},
    {"watkins", {{"split", "none"}}, "watkins split=none"},
    // Timed on the dragons too, past its default budget (the bench calls the pass itself).
    {"weiler_atherton", {}, "weiler_atherton"},
};
const char* const kBenchScenes[] = {"counters", "trees", "dragons"};

// Arguments: scene (index into kBenchScenes), configuration (index into kConfigurations).
void visibility(benchmark::State& state) {
  const char* const sceneName = kBenchScenes[state.range(0)];
  const Configuration& configuration = kConfigurations[state.range(1)];
  const hsr::PreparedScene& scene = *hsr::bench::sceneNamed(sceneName).prepared;
  const hsr::AlgorithmEntry& entry = hsr::findAlgorithm(configuration.algorithm);
  const hsr::KnobValues knobs = hsr::resolveKnobs(entry, configuration.knobs);
  hsr::Visibility answer{hsr::Frame(scene.width(), scene.height()), std::nullopt};
  for (auto _ : state) {
    hsr::Stats stats;
    entry.visibility({scene, scene.camera(), nullptr, 1, stats}, knobs, answer);
    benchmark::DoNotOptimize(answer.frame.ids.data());
  }
  state.SetLabel(std::string(sceneName) + " " + configuration.label);
}

BENCHMARK(visibility)
    ->ArgsProduct({{0, 1, 2}, benchmark::CreateDenseRange(0, std::size(kConfigurations) - 1, 1)})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
