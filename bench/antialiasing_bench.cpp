// Antialiasing: what accurate edge coverage costs. The A-buffer at each mask size (and
// with Carpenter's one depth per fragment) beside the z-buffer supersampled k x k at the
// same subsamples (rendered k times larger, then each pixel the mean of its k x k), whole
// renders (visibility and shading), on counters, trees and dragons at 320 x 180, one
// thread. Each row's counters hold its coverage error against the exact shares (the
// reference at 32 x 32 samples per pixel, traceExactShares in renderer/reference/reference.hpp): the mean
// over all pixels, and over the pixels where more than one thing shows.
//
// Run: build/bench/antialiasing_bench --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include <map>

#include "bench_scenes.hpp"
#include "renderer/raster/coverage.hpp"
#include "renderer/reference/reference.hpp"

namespace {

constexpr int kWidth = 320, kHeight = 180, kExactSamples = 32;
const char* const kAntialiasedScenes[] = {"counters", "trees", "dragons"};

// A configuration: the A-buffer with these knobs, or the z-buffer at k x k samples per pixel.
struct Configuration {
  const char* algorithm;
  hsr::KnobSettings knobs;
  int supersampling;  // the z-buffer's k; 0 for the A-buffer
  const char* label;
};
const Configuration kConfigurations[] = {
    {"zbuffer", {}, 1, "zbuffer, 1 sample"},
    {"zbuffer", {}, 2, "zbuffer supersampled 2x2"},
    {"zbuffer", {}, 4, "zbuffer supersampled 4x4"},
    {"zbuffer", {}, 8, "zbuffer supersampled 8x8"},
    {"abuffer", {{"mask", "2x2"}}, 0, "abuffer mask=2x2"},
    {"abuffer", {{"mask", "4x4"}}, 0, "abuffer mask=4x4"},
    {"abuffer", {{"mask", "8x8"}}, 0, "abuffer mask=8x8"},
    {"abuffer", {{"mask", "4x4"}, {"depth", "center"}}, 0, "abuffer mask=4x4 depth=center"},
};

std::unique_ptr<hsr::PreparedScene> sized(const char* name, int k) {
  auto prepared = std::make_unique<hsr::PreparedScene>(hsr::bench::sceneNamed(name).scene);
  prepared->setSize(kWidth * k, kHeight * k);
  return prepared;
}

const hsr::PixelShares& exactShares(const char* name) {
  static std::map<std::string, hsr::PixelShares> cache;
  auto found = cache.find(name);
  if (found == cache.end()) {
    hsr::Stats stats;
    found = cache.emplace(name, hsr::traceExactShares(*sized(name, 1), kExactSamples, 0, stats)).first;
  }
  return found->second;
}

// The configuration's shares of each pixel, from its visibility pass.
hsr::PixelShares sharesOf(const hsr::PreparedScene& scene, const Configuration& configuration) {
  const hsr::AlgorithmEntry& entry = hsr::findAlgorithm(configuration.algorithm);
  hsr::Visibility answer{hsr::Frame(scene.width(), scene.height()), std::nullopt};
  hsr::Stats stats;
  entry.visibility({scene, scene.camera(), nullptr, 0, stats}, hsr::resolveKnobs(entry, configuration.knobs), answer);
  if (configuration.supersampling > 0) return hsr::sharesOfSamples(answer.frame.ids, kWidth, kHeight, configuration.supersampling);
  return hsr::sharesOf(*answer.coverage);
}

// Each pixel the mean of its k x k subsamples' colours: the supersampled z-buffer's resolve.
void averageDown(const hsr::Frame& fine, int k, std::vector<std::uint8_t>& color) {
  color.assign(std::size_t(kWidth) * kHeight * 4, 255);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (std::size_t c = 0; c < 3; ++c) {
        int sum = 0;
        for (int sy = 0; sy < k; ++sy)
          for (int sx = 0; sx < k; ++sx) sum += fine.color[4 * (std::size_t(y * k + sy) * std::size_t(kWidth * k) + std::size_t(x * k + sx)) + c];
        color[4 * (std::size_t(y) * kWidth + std::size_t(x)) + c] = static_cast<std::uint8_t>((sum + k * k / 2) / (k * k));
      }
}

// Arguments: scene (index into kAntialiasedScenes), configuration (index into kConfigurations).
void antialiased(benchmark::State& state) {
  const char* const name = kAntialiasedScenes[state.range(0)];
  const Configuration& configuration = kConfigurations[state.range(1)];
  const auto scene = sized(name, std::max(1, configuration.supersampling));
  const hsr::AlgorithmEntry& entry = hsr::findAlgorithm(configuration.algorithm);
  const hsr::KnobValues knobs = hsr::resolveKnobs(entry, configuration.knobs);
  std::vector<std::uint8_t> color;
  for (auto _ : state) {
    hsr::Stats stats;
    const hsr::Frame frame = hsr::bench::render(*scene, configuration.algorithm, knobs, 1, stats);
    if (configuration.supersampling > 1) averageDown(frame, configuration.supersampling, color);
    benchmark::DoNotOptimize(frame.color.data());
  }
  const hsr::CoverageError error = hsr::coverageError(sharesOf(*scene, configuration), exactShares(name));
  state.counters["error_all"] = error.mean;
  state.counters["error_mixed"] = error.meanOverMixed;
  state.SetLabel(std::string(name) + " " + configuration.label);
}

BENCHMARK(antialiased)
    ->ArgsProduct({{0, 1, 2}, benchmark::CreateDenseRange(0, std::size(kConfigurations) - 1, 1)})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
