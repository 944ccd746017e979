// Ray casting's speed: primary rays per second for the bvh variant on dragons and
// counters at 1280x720, 1 and 2 threads (the visibility pass: a ray per pixel center,
// nearest hit, ids and depth written; the BVH already built), the march at its
// defaults on the same scenes for scale, and the BVH build with its node count.
//
// Protocol: one warm-up (which builds the BVH), then Google Benchmark's repetitions.
// Run: build/bench/ray_casting_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <algorithm>

#include "algorithms/ray_casting/ray_casting.hpp"
#include "bench_scenes.hpp"

namespace {

using hsr::bench::kScenes;
using hsr::bench::sceneNamed;

// Arguments: scene, variant (0 bvh, 2 march), threads.
void primaryRays(benchmark::State& state) {
  const hsr::PreparedScene& scene = *sceneNamed(kScenes[state.range(0)]).prepared;
  hsr::ray_casting::Knobs knobs;
  knobs.variant = static_cast<hsr::ray_casting::Variant>(state.range(1));
  const int threads = static_cast<int>(state.range(2));
  hsr::Visibility visibility{hsr::Frame(scene.width(), scene.height()), std::nullopt};
  hsr::Stats warmUp;
  hsr::ray_casting::visibility({scene, scene.camera(), nullptr, threads, warmUp}, knobs, visibility);
  for (auto _ : state) {
    hsr::Stats stats;
    hsr::ray_casting::visibility({scene, scene.camera(), nullptr, threads, stats}, knobs, visibility);
    benchmark::DoNotOptimize(visibility.frame.ids.data());
  }
  state.SetLabel(std::string(kScenes[state.range(0)]) + (state.range(1) == 0 ? " bvh" : " march (defaults)") +
                 " threads=" + std::to_string(threads));
  state.counters["rays/s"] = benchmark::Counter(double(scene.width()) * scene.height(), benchmark::Counter::kIsIterationInvariantRate);
  const double rays = double(scene.width()) * scene.height();
  if (state.range(1) == 0) {
    state.counters["nodes/ray"] = double(warmUp.counter("bvh nodes visited")) / rays;
    state.counters["triangles/ray"] = double(warmUp.counter("ray-triangle tests")) / rays;
  } else {
    state.counters["samples/ray"] = double(warmUp.counter("march samples")) / rays;
  }
}

void bvhBuild(benchmark::State& state) {
  const hsr::Scene& scene = sceneNamed(kScenes[state.range(0)]).scene;
  std::int64_t nodes = 0;
  for (auto _ : state) {
    const hsr::PreparedScene prepared(scene);
    hsr::Stats stats;
    nodes = std::int64_t(prepared.triangleBvh(stats).nodes().size());
    benchmark::DoNotOptimize(nodes);
  }
  state.SetLabel(std::string(kScenes[state.range(0)]) + " flatten + SAH build");
  state.counters["nodes"] = double(nodes);
}

double minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }
double maximum(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

}  // namespace

BENCHMARK(primaryRays)->ArgsProduct({{0, 1}, {0, 2}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()
    ->ComputeStatistics("min", minimum)->ComputeStatistics("max", maximum);
BENCHMARK(bvhBuild)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
