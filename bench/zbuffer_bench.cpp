// The z-buffer's speed: dragons and counters at 1280x720, per depth format, full-frame
// vs one-scanline, 1 vs 2 threads. Measures the visibility pass (geometry stage and
// depth-tested rasterization: what Mesa's peer run does too); "shaded" adds the
// deferred Lambert shading of the whole render. "reference" traces the exact reference
// (renderer/reference/reference) over the same scenes, by packets (its default) or by the textbook
// traversal, BVHs already built, so the cost of ground truth comes out as a ratio to the
// z-buffer from one run (ray_casting_bench times the BVH builds). "memsetFloor" clears the
// frame's ids and depth as fast as memory allows: the floor under "raster".
//
// Protocol: one warm-up render, then Google Benchmark's repetitions; it reports
// mean, median, min, max. Run: build/bench/zbuffer_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstring>
#include <memory>

#include "algorithms/zbuffer/zbuffer.hpp"
#include "bench_scenes.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/shading/shading.hpp"
#include "renderer/util/parallel.hpp"

namespace {

using hsr::bench::kScenes;
using hsr::bench::sceneNamed;

void visibility(benchmark::State& state) {
  const hsr::PreparedScene& scene = *sceneNamed(kScenes[state.range(0)]).prepared;
  const auto variant = static_cast<hsr::zbuffer::Variant>(state.range(1));
  const auto format = static_cast<hsr::DepthFormat>(state.range(2));
  const int threads = static_cast<int>(state.range(3));
  // Reused, as a real-time renderer reuses its framebuffer and its triangle buffers.
  hsr::Frame frame(scene.width(), scene.height());
  hsr::ScreenGeometry geometry{scene.camera(), {}, {}};
  const auto once = [&](hsr::Stats& stats) {
    const bool clipFar = hsr::clipsFarPlane(format, scene.scene().camera.projection);
    buildScreenTriangles(scene, scene.camera(), {.clipFar = clipFar}, threads, stats, geometry);
    if (variant == hsr::zbuffer::Variant::full)
      hsr::zbuffer::renderFullFrame(geometry, format, threads, frame, stats);
    else
      hsr::zbuffer::renderScanline(geometry, format, threads, frame, stats);
    benchmark::DoNotOptimize(frame.ids.data());
  };
  hsr::Stats warmUp;
  once(warmUp);
  for (auto _ : state) {
    hsr::Stats stats;
    once(stats);
  }
  state.SetLabel(std::string(kScenes[state.range(0)]) + " " + (variant == hsr::zbuffer::Variant::full ? "full" : "scanline") +
                 " " + hsr::depthFormatName(format) + " threads=" + std::to_string(threads));
  state.counters["triangles/s"] = benchmark::Counter(double(scene.triangleCount()), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["pixels/s"] = benchmark::Counter(double(scene.width()) * scene.height(), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["fragments"] = double(warmUp.counter("fragments tested"));
}

// The rasterization alone (steps 1 and 2 of the full frame, the geometry stage built once;
// step 3 waits for a reader, timed by decode below),
// by the textbook loop and by the fast path: their ratio is the fast path's gain.
constexpr const char* kRasterScenes[] = {"counters", "city", "dragons"};

void raster(benchmark::State& state) {
  const char* name = kRasterScenes[state.range(0)];
  const hsr::PreparedScene& scene = *sceneNamed(name).prepared;
  const auto path = static_cast<hsr::zbuffer::Path>(state.range(1));
  const int threads = static_cast<int>(state.range(2));
  hsr::Stats setUp;
  const hsr::ScreenGeometry geometry = buildScreenTriangles(scene, {}, threads, setUp);
  hsr::Frame frame(scene.width(), scene.height());
  hsr::Stats warmUp;
  hsr::zbuffer::renderFullFrame(geometry, hsr::DepthFormat::float32, threads, frame, warmUp, {.path = path});
  for (auto _ : state) {
    hsr::Stats stats;
    hsr::zbuffer::renderFullFrame(geometry, hsr::DepthFormat::float32, threads, frame, stats, {.path = path});
    benchmark::DoNotOptimize(frame.ids.data());
  }
  state.SetLabel(std::string(name) + (path == hsr::zbuffer::Path::simd ? " simd" : " scalar") + " threads=" + std::to_string(threads));
  state.counters["fragments"] = double(warmUp.counter("fragments tested"));
  state.counters["skipped"] = double(warmUp.counter("fragments skipped by block depth"));
}

// Step 3 when a stage asks for distances: the depth the full frame kept (as float32 z),
// decoded by Frame::distances(), timed alone (the pass before it is not timed). What a
// frame that no stage reads the distances of saves.
void decode(benchmark::State& state) {
  const char* name = kRasterScenes[state.range(0)];
  const hsr::PreparedScene& scene = *sceneNamed(name).prepared;
  const int threads = static_cast<int>(state.range(1));
  hsr::Stats setUp;
  const hsr::ScreenGeometry geometry = buildScreenTriangles(scene, {}, threads, setUp);
  hsr::Frame frame(scene.width(), scene.height());
  for (auto _ : state) {
    state.PauseTiming();
    hsr::Stats stats;
    hsr::zbuffer::renderFullFrame(geometry, hsr::DepthFormat::float32, threads, frame, stats);
    state.ResumeTiming();
    benchmark::DoNotOptimize(frame.distances().data());
  }
  state.SetLabel(std::string(name) + " distances decoded threads=" + std::to_string(threads));
}

// The machine's floor under raster: clearing what a visibility pass must write at least
// once, the frame's ids and its depth (8 bytes a pixel), with memset, one part per
// thread on the same threads as the pass. A pass that fills a few large triangles (counters)
// approaches it; raster's time over this one says how far from memory bandwidth a pass is.
void memsetFloor(benchmark::State& state) {
  const char* name = kRasterScenes[state.range(0)];
  const hsr::PreparedScene& scene = *sceneNamed(name).prepared;
  const int threads = static_cast<int>(state.range(1));
  hsr::Frame frame(scene.width(), scene.height(), threads);
  const std::size_t parts = std::size_t(hsr::parallelWorkers(frame.pixelCount(), threads));
  const auto clear = [&] {
    hsr::parallelFor(parts, threads, [&](std::size_t part, int) {
      const auto [first, end] = hsr::partRange(frame.pixelCount(), parts, part);
      std::memset(frame.ids.data() + first, 0, (end - first) * sizeof frame.ids[0]);
      std::memset(frame.depth.data() + first, 0, (end - first) * sizeof frame.depth[0]);
    });
  };
  for (auto _ : state) {
    clear();
    benchmark::DoNotOptimize(frame.ids.data());
    benchmark::ClobberMemory();
  }
  state.SetLabel(std::string(name) + " memset of ids and depth threads=" + std::to_string(threads));
  state.counters["bytes/s"] = benchmark::Counter(double(frame.pixelCount()) * 8, benchmark::Counter::kIsIterationInvariantRate);
}

void shaded(benchmark::State& state) {
  const hsr::PreparedScene& scene = *sceneNamed(kScenes[state.range(0)]).prepared;
  const int threads = static_cast<int>(state.range(1));
  hsr::Stats warmUp;
  hsr::bench::render(scene, "zbuffer", hsr::zbuffer::knobTable().valuesOf({}), threads, warmUp);  // also builds the normals, once
  for (auto _ : state) {
    hsr::Stats stats;
    benchmark::DoNotOptimize(hsr::bench::render(scene, "zbuffer", hsr::zbuffer::knobTable().valuesOf({}), threads, stats).color.data());
  }
  state.SetLabel(std::string(kScenes[state.range(0)]) + " full float32 lambert threads=" + std::to_string(threads));
  state.counters["triangles/s"] = benchmark::Counter(double(scene.triangleCount()), benchmark::Counter::kIsIterationInvariantRate);
}

// Arguments: scene, traversal (0 packets, 1 textbook), threads.
void reference(benchmark::State& state) {
  const hsr::PreparedScene& scene = *sceneNamed(kScenes[state.range(0)]).prepared;
  const auto traversal = state.range(1) == 0 ? hsr::ReferenceTraversal::packets : hsr::ReferenceTraversal::textbook;
  const int threads = static_cast<int>(state.range(2));
  hsr::Stats warmUp;
  hsr::ReferenceImage image;  // reused, as the z-buffer's benchmarks reuse their frame
  hsr::traceReference(scene, threads, warmUp, traversal, image);  // also builds the BVHs, once
  for (auto _ : state) {
    hsr::Stats stats;
    hsr::traceReference(scene, threads, stats, traversal, image);
    benchmark::DoNotOptimize(image.frame.ids.data());
  }
  state.SetLabel(std::string(kScenes[state.range(0)]) + " exact reference, " + (state.range(1) == 0 ? "packets" : "textbook") +
                 " threads=" + std::to_string(threads));
  state.counters["exact fall-backs"] = double(warmUp.counter("reference exact fall-backs"));
  state.counters["rays/s"] = benchmark::Counter(double(scene.width()) * scene.height(), benchmark::Counter::kIsIterationInvariantRate);
}

void visibilityArguments(benchmark::internal::Benchmark* benchmark) {
  for (int scene = 0; scene < 2; ++scene)
    for (int variant = 0; variant < 2; ++variant)
      for (int format = 0; format < int(hsr::depthFormatNames().size()); ++format)
        for (int threads : {1, 2}) benchmark->Args({scene, variant, format, threads});
}

double minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }
double maximum(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

}  // namespace

const bool contextAdded = [] {
  benchmark::AddCustomContext("threads", "as in each benchmark's name (1 or 2)");
  return true;
}();

BENCHMARK(visibility)->Apply(visibilityArguments)->Unit(benchmark::kMillisecond)->UseRealTime()
    ->ComputeStatistics("min", minimum)->ComputeStatistics("max", maximum);
BENCHMARK(raster)->ArgsProduct({{0, 1, 2}, {0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()
    ->ComputeStatistics("min", minimum)->ComputeStatistics("max", maximum);
BENCHMARK(reference)->ArgsProduct({{0, 1}, {0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()
    ->ComputeStatistics("min", minimum)->ComputeStatistics("max", maximum);
BENCHMARK(decode)->ArgsProduct({{0, 1, 2}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()
    ->ComputeStatistics("min", minimum)->ComputeStatistics("max", maximum);
BENCHMARK(memsetFloor)->ArgsProduct({{0, 1, 2}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()
    ->ComputeStatistics("min", minimum)->ComputeStatistics("max", maximum);
BENCHMARK(shaded)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime()
    ->ComputeStatistics("min", minimum)->ComputeStatistics("max", maximum);
