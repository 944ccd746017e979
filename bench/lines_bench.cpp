// The hidden-line algorithms' speed: Roberts (screen grid on and off) against Appel on
// grown scenes of boxes, k x k boxes for k = 3 ... 45 (9 to 2,025 bodies), with the
// fitted exponent; Appel on the bunny and the dragon at 1280 x 720, warm (adjacency and
// BVH built by an earlier run, as in a walkthrough) and cold (a fresh PreparedScene per
// run: adjacency, BVH, facing, contours, walk); and the exact line reference on both.
//
// Protocol: one thread (both algorithms are sequential), Google Benchmark's repetitions.
// Run: build/bench/lines_bench --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include "algorithms/appel/appel.hpp"
#include "algorithms/roberts/roberts.hpp"
#include "bench_scenes.hpp"
#include "renderer/reference/line_reference.hpp"

namespace {

// k x k unit boxes, 1.6 apart, seen from above at a slant so that rows hide each other.
hsr::Scene boxes(int k) {
  hsr::Scene scene;
  scene.width = 1280;
  scene.height = 720;
  scene.camera.eye = {0, 0.9 * k, 1.4 * k + 3};
  scene.camera.target = {0, 0, 0};
  scene.camera.fovYDegrees = 50;
  hsr::SceneObject box;
  box.name = "box";
  box.mesh = std::make_shared<hsr::Mesh>(hsr::makeBox({1, 1, 1}));
  box.instancing.kind = hsr::Instancing::Kind::grid;
  box.instancing.gridCount = {k, 1, k};
  box.instancing.gridSpacing = {1.6, 0, 1.6};
  scene.objects.push_back(box);
  return scene;
}

template <typename Draw>
void onBoxes(benchmark::State& state, Draw&& draw) {
  const int k = static_cast<int>(state.range(0));
  const hsr::Scene scene = boxes(k);
  const hsr::PreparedScene prepared(scene);
  for (auto _ : state) {
    hsr::Stats stats;
    benchmark::DoNotOptimize(draw(prepared, stats).segments.data());
  }
  state.SetComplexityN(k * k);
  state.SetLabel(std::to_string(k * k) + " boxes");
}

void robertsGrid(benchmark::State& state) {
  onBoxes(state, [](const hsr::PreparedScene& scene, hsr::Stats& stats) { return hsr::roberts::run(scene, {}, stats); });
}
void robertsNoGrid(benchmark::State& state) {
  hsr::roberts::Knobs knobs;
  knobs.grid = false;
  onBoxes(state, [&](const hsr::PreparedScene& scene, hsr::Stats& stats) { return hsr::roberts::run(scene, knobs, stats); });
}
void appelBoxes(benchmark::State& state) {
  onBoxes(state, [](const hsr::PreparedScene& scene, hsr::Stats& stats) { return hsr::appel::run(scene, {}, stats); });
}

hsr::appel::Knobs knobsFor(const std::string& model) {
  hsr::appel::Knobs knobs;
  if (model == "dragon") knobs.surfaces = hsr::appel::Surfaces::any;  // not a closed mesh
  return knobs;
}

void appelWarm(benchmark::State& state, const std::string& model) {
  const hsr::PreparedScene& scene = *hsr::bench::sceneNamed(model).prepared;
  for (auto _ : state) {
    hsr::Stats stats;
    benchmark::DoNotOptimize(hsr::appel::run(scene, knobsFor(model), stats).segments.data());
  }
}

void appelCold(benchmark::State& state, const std::string& model) {
  const hsr::Scene& scene = hsr::bench::sceneNamed(model).scene;
  for (auto _ : state) {
    hsr::PreparedScene prepared(scene);
    prepared.setSize(1280, 720);
    hsr::Stats stats;
    benchmark::DoNotOptimize(hsr::appel::run(prepared, knobsFor(model), stats).segments.data());
  }
}

void lineReference(benchmark::State& state, const std::string& model) {
  const hsr::PreparedScene& scene = *hsr::bench::sceneNamed(model).prepared;
  hsr::Stats drawStats;
  const hsr::LineSet lines = hsr::appel::run(scene, knobsFor(model), drawStats);
  for (auto _ : state) {
    hsr::Stats stats;
    benchmark::DoNotOptimize(hsr::traceLineReference(scene, lines.edges, 1, stats).data());
  }
  state.counters["edges"] = double(lines.edges.size());
}

}  // namespace

BENCHMARK(robertsGrid)->Arg(3)->Arg(6)->Arg(13)->Arg(25)->Arg(45)->Complexity()->Unit(benchmark::kMillisecond);
BENCHMARK(robertsNoGrid)->Arg(3)->Arg(6)->Arg(13)->Arg(25)->Arg(45)->Complexity()->Unit(benchmark::kMillisecond);
BENCHMARK(appelBoxes)->Arg(3)->Arg(6)->Arg(13)->Arg(25)->Arg(45)->Complexity()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(appelWarm, bunny, std::string("bunny"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(appelWarm, dragon, std::string("dragon"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(appelCold, dragon, std::string("dragon"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(lineReference, bunny, std::string("bunny"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(lineReference, dragon, std::string("dragon"))->Unit(benchmark::kMillisecond);
