// Ray casting's speed: primary rays per second for the bvh variant by each path (the
// default packets of eight rays, single rays through the wide BVH, the textbook
// traversal of the binary BVH) on dragons and counters at 1280x720, 1 and 2 threads (the
// visibility pass: a ray per pixel center, nearest hit, ids and depth written; the BVHs
// already built), the march at its defaults on the same scenes for scale, and the BVH
// builds with their node counts, on 1 and 2 threads.
//
// Protocol: one warm-up (which builds the BVHs), then Google Benchmark's repetitions.
// Run: build/bench/ray_casting_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <algorithm>

#include "algorithms/ray_casting/ray_casting.hpp"
#include "bench_scenes.hpp"

namespace {

using hsr::bench::kScenes;
using hsr::bench::sceneNamed;

// The configurations timed: the bvh variant by path, and the march.
struct Configuration {
  const char* name;
  hsr::ray_casting::Variant variant;
  hsr::ray_casting::Path path;
};
constexpr Configuration kConfigurations[] = {{"bvh path=packet", hsr::ray_casting::Variant::bvh, hsr::ray_casting::Path::packet},
                                             {"bvh path=simd", hsr::ray_casting::Variant::bvh, hsr::ray_casting::Path::simd},
                                             {"bvh path=scalar", hsr::ray_casting::Variant::bvh, hsr::ray_casting::Path::scalar},
                                             {"march (defaults)", hsr::ray_casting::Variant::march, hsr::ray_casting::Path::packet}};

// Arguments: scene, configuration (kConfigurations), threads.
void primaryRays(benchmark::State& state) {
  const hsr::PreparedScene& scene = *sceneNamed(kScenes[state.range(0)]).prepared;
  const Configuration& configuration = kConfigurations[state.range(1)];
  hsr::ray_casting::Knobs knobs;
  knobs.variant = configuration.variant;
  knobs.path = configuration.path;
  const int threads = static_cast<int>(state.range(2));
  hsr::Visibility visibility{hsr::Frame(scene.width(), scene.height()), std::nullopt};
  hsr::Stats warmUp;
  hsr::ray_casting::visibility({scene, scene.camera(), nullptr, threads, warmUp}, knobs, visibility);
  for (auto _ : state) {
    hsr::Stats stats;
    hsr::ray_casting::visibility({scene, scene.camera(), nullptr, threads, stats}, knobs, visibility);
    benchmark::DoNotOptimize(visibility.frame.ids.data());
  }
  state.SetLabel(std::string(kScenes[state.range(0)]) + " " + configuration.name + " threads=" + std::to_string(threads));
  state.counters["rays/s"] = benchmark::Counter(double(scene.width()) * scene.height(), benchmark::Counter::kIsIterationInvariantRate);
  const double rays = double(scene.width()) * scene.height();
  if (configuration.variant == hsr::ray_casting::Variant::bvh) {
    state.counters["nodes/ray"] = double(warmUp.counter("bvh nodes visited")) / rays;
    state.counters["triangles/ray"] = double(warmUp.counter("ray-triangle tests")) / rays;
  } else {
    state.counters["samples/ray"] = double(warmUp.counter("march samples")) / rays;
  }
}

// Arguments: scene, threads. The BVH is the same for any thread count (a test asserts
// it).
void bvhBuild(benchmark::State& state) {
  const hsr::Scene& scene = sceneNamed(kScenes[state.range(0)]).scene;
  const int threads = static_cast<int>(state.range(1));
  std::int64_t nodes = 0, wideNodes = 0;
  for (auto _ : state) {
    const hsr::PreparedScene prepared(scene);
    hsr::Stats stats;
    nodes = std::int64_t(prepared.triangleBvh(stats, threads).nodes().size());
    wideNodes = std::int64_t(prepared.wideTriangleBvh(stats, threads).nodes().size());
    benchmark::DoNotOptimize(nodes);
  }
  state.SetLabel(std::string(kScenes[state.range(0)]) + " flatten + SAH build + collapse to eight children, threads=" +
                 std::to_string(threads));
  state.counters["nodes"] = double(nodes);
  state.counters["wide nodes"] = double(wideNodes);
}

// The SAH build alone, from the triangles' boxes, on 1 and 2 threads (arguments:
// scene, threads): after the first repetition its memory comes back from the
// allocator already touched, so this is the build's own work, without the first-touch
// page faults a fresh process pays (bvhBuild above).
void bvhFromBoxes(benchmark::State& state) {
  const hsr::PreparedScene& scene = *sceneNamed(kScenes[state.range(0)]).prepared;
  const int threads = static_cast<int>(state.range(1));
  std::vector<hsr::Aabb> boxes(scene.triangles().size());
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (const std::uint32_t v : scene.triangles()[i]) boxes[i].grow(scene.positions()[v]);
  for (auto _ : state) {
    const hsr::Bvh bvh(boxes, threads);
    benchmark::DoNotOptimize(bvh.nodes().data());
  }
  state.SetLabel(std::string(kScenes[state.range(0)]) + " SAH build, threads=" + std::to_string(threads));
}

double minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }
double maximum(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

}  // namespace

BENCHMARK(primaryRays)->ArgsProduct({{0, 1}, {0, 1, 2, 3}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()
    ->ComputeStatistics("min", minimum)->ComputeStatistics("max", maximum);
BENCHMARK(bvhBuild)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()
    ->ComputeStatistics("min", minimum)->ComputeStatistics("max", maximum);
BENCHMARK(bvhFromBoxes)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()
    ->ComputeStatistics("min", minimum)->ComputeStatistics("max", maximum);
