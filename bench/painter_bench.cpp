// The painter's speed: each variant on counters at 1280x720 (sort; newell; the BSP tree's
// build, once per scene, apart from its walk and painting, once per view), and Newell's
// quadratic worst case: n long strips that all cross the view and all overlap in depth,
// so that every pair must be tested (Google Benchmark fits the exponent).
//
// Protocol: one warm-up, then Google Benchmark's repetitions, one thread (the ordering
// is sequential; the painting is tile-parallel like the z-buffer's).
// Run: build/bench/painter_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <cmath>

#include "algorithms/painter/bsp.hpp"
#include "bench_scenes.hpp"

namespace {

using hsr::bench::sceneNamed;
using hsr::painter::Variant;

hsr::painter::Knobs knobsFor(Variant variant) {
  hsr::painter::Knobs knobs;
  knobs.variant = variant;
  knobs.budget = 1e15;
  return knobs;
}

// Arguments: variant (as painter::Variant).
void orderAndPaint(benchmark::State& state) {
  const hsr::PreparedScene& scene = *sceneNamed("counters").prepared;
  const hsr::painter::Knobs knobs = knobsFor(static_cast<Variant>(state.range(0)));
  for (auto _ : state) {
    hsr::Stats stats;
    benchmark::DoNotOptimize(hsr::bench::render(scene, "painter", hsr::painter::knobTable().valuesOf(knobs), 1, stats).ids.data());
  }
  state.SetLabel(knobs.variant == Variant::sort ? "counters sort" : "counters newell");
}

void bspBuild(benchmark::State& state) {
  const hsr::PreparedScene& scene = *sceneNamed("counters").prepared;
  for (auto _ : state) {
    hsr::Stats stats;
    const hsr::painter::BspTree tree(scene, knobsFor(Variant::bsp), stats);
    benchmark::DoNotOptimize(tree.nodeCount());
    state.counters["nodes"] = double(tree.nodeCount());
    state.counters["fragments"] = double(tree.fragmentCount());
  }
  state.SetLabel("counters bsp build (once per scene)");
}

void bspWalkAndPaint(benchmark::State& state) {
  const hsr::PreparedScene& scene = *sceneNamed("counters").prepared;
  hsr::Stats buildStats;
  const hsr::painter::BspTree tree(scene, knobsFor(Variant::bsp), buildStats);
  for (auto _ : state) {
    hsr::Stats stats;
    hsr::PaintedPieces painted{hsr::buildScreenTriangles(scene, {}, 1, stats), {}};
    painted.order = tree.backToFront(scene, painted.geometry, stats);
    hsr::Frame frame(scene.width(), scene.height());
    hsr::painter::paint(scene, painted, 1, frame, stats);
    benchmark::DoNotOptimize(frame.ids.data());
  }
  state.SetLabel("counters bsp walk + paint (once per view; visibility only)");
}

// n strips, each a long thin triangle pair across the whole view, at angles spread
// over 180 degrees and tilted in depth: all pairs overlap in depth and on screen.
struct Strips {
  hsr::Scene scene;
  std::unique_ptr<hsr::PreparedScene> prepared;
  explicit Strips(int n) {
    hsr::Mesh mesh;
    for (int i = 0; i < n; ++i) {
      const double angle = M_PI * i / n, c = std::cos(angle), s = std::sin(angle);
      const double z = 0.001 * i;
      const auto at = [&](double along, double across, double tilt) {
        return hsr::dvec3(c * along - s * across, s * along + c * across, z + tilt);
      };
      const auto first = static_cast<std::uint32_t>(mesh.positions.size());
      for (const hsr::dvec3& p : {at(-3, -0.02, -0.3), at(3, -0.02, 0.3), at(3, 0.02, 0.3), at(-3, 0.02, -0.3)})
        mesh.positions.push_back(p);
      mesh.triangles.push_back({first, first + 1, first + 2});
      mesh.triangles.push_back({first, first + 2, first + 3});
    }
    scene.width = 512;
    scene.height = 512;
    scene.camera.eye = {0, 0, 6};
    hsr::SceneObject object;
    object.mesh = std::make_shared<const hsr::Mesh>(mesh);
    scene.objects.push_back(object);
    prepared = std::make_unique<hsr::PreparedScene>(scene);
  }
};

void newellWorstCase(benchmark::State& state) {
  const Strips strips(static_cast<int>(state.range(0)));
  hsr::Stats last;
  for (auto _ : state) {
    hsr::Stats stats;
    benchmark::DoNotOptimize(hsr::bench::render(*strips.prepared, "painter", hsr::painter::knobTable().valuesOf(knobsFor(Variant::newell)), 1, stats).ids.data());
    last = stats;
  }
  state.counters["pairs tested"] = double(last.counter("newell pairs tested"));
  state.counters["splits"] = double(last.counter("newell splits"));
  state.SetComplexityN(state.range(0));
}

}  // namespace

BENCHMARK(orderAndPaint)->Arg(int(Variant::sort))->Arg(int(Variant::newell))->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bspBuild)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(bspWalkAndPaint)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(newellWorstCase)->RangeMultiplier(2)->Range(16, 128)->Unit(benchmark::kMillisecond)->UseRealTime()->Complexity();
