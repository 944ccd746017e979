// The floating horizon's speed on the ripple (scenes/ripple.toml, 41 curves each way) at
// 1280 x 720: by samples per curve and horizon columns, rows and mesh, and the exact
// drawing it is judged by. Accuracy for the same settings: hsr sweep (README).
//
// Protocol: one thread (the algorithm is sequential), Google Benchmark's repetitions.
// Run: build/bench/floating_horizon_bench --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include "algorithms/floating_horizon/floating_horizon.hpp"
#include "bench_scenes.hpp"

namespace {

const hsr::PreparedScene& ripple() { return *hsr::bench::sceneNamed("ripple").prepared; }

// samples and columns as a percentage of the image width, as the knobs take them.
void floatingHorizon(benchmark::State& state) {
  hsr::floating_horizon::Knobs knobs;
  knobs.samples = {double(std::max(2, static_cast<int>(state.range(0) * ripple().width() / 100)))};
  knobs.columns = {double(std::max(1, static_cast<int>(state.range(1) * ripple().width() / 100)))};
  knobs.mesh = state.range(2) != 0;
  for (auto _ : state) {
    hsr::Stats stats;
    benchmark::DoNotOptimize(hsr::floating_horizon::run(ripple(), knobs, stats).segments.data());
  }
  state.SetLabel("samples " + std::to_string(int(knobs.samples.value)) + ", columns " + std::to_string(int(knobs.columns.value)) +
                 (knobs.mesh ? ", mesh" : ", rows"));
}

void exactDrawing(benchmark::State& state) {
  for (auto _ : state) {
    hsr::Stats stats;
    benchmark::DoNotOptimize(hsr::floating_horizon::exactDrawing(ripple(), state.range(0) != 0, 1, stats).lines.edges.data());
  }
}

}  // namespace

BENCHMARK(floatingHorizon)
    ->ArgsProduct({{5, 25, 100}, {25, 100}, {0}})
    ->Args({100, 100, 1})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(exactDrawing)->Arg(0)->Unit(benchmark::kMillisecond);
