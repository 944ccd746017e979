// Occlusion culling's throughput on the MOC benchmark city (scenes/city.toml without its
// ground: 8,334 boxes, 100,008 triangles, seen at 1920 x 1080), single thread (README "Speed",
// algorithms/culling/README.md):
//   occluders/RULE/WxH   every box offered as an occluder, nearest first, drawn into a
//                        W x H map unless the boxes already drawn hide it; items: the
//                        city's triangles, so items/s is the triangle throughput
//   occludees/TEST       each of the 8,334 boxes tested against the 256 x 128 map of the
//                        conservative rule: flat (every texel until one proves it
//                        visible) or with the hierarchical-Z pyramid; items: tests
//   zbuffer-depth        for scale: hsr's z-buffer (geometry stage and float depth
//                        raster) of the whole city at 1920 x 1080
#include <benchmark/benchmark.h>

#include "algorithms/culling/occlusion/occlusion.hpp"
#include "algorithms/zbuffer/zbuffer.hpp"
#include "bench_scenes.hpp"
#include "renderer/screen_triangles.hpp"

namespace {

using namespace hsr::culling::occlusion;

// The benchmark's scene: the city's buildings alone, as Intel's benchmark draws them.
hsr::Scene buildings() {
  hsr::Scene scene = hsr::loadScene(std::string(HSR_SOURCE_DIR) + "/scenes/city.toml");
  std::erase_if(scene.objects, [](const hsr::SceneObject& object) { return object.name == "ground"; });
  return scene;
}

struct City {
  hsr::Scene scene = buildings();
  hsr::PreparedScene prepared{scene};
  hsr::CameraTransform camera{scene.camera, 1920, 1080};
  std::vector<std::uint32_t> everyObject = chooseOccluders(prepared, camera, Knobs{}, hsr::VisibleSet::everything(prepared));
};

const City& city() {
  static const City made;
  return made;
}

void occluders(benchmark::State& state, Rule rule, int width, int height) {
  const City& c = city();
  Knobs settings;
  settings.rule = rule;
  const MapView view(c.camera, width, height);
  hsr::Stats stats;
  for (auto _ : state) {
    stats = hsr::Stats();
    benchmark::DoNotOptimize(occluderDepthMap(c.prepared, view, settings, c.everyObject, stats).keys.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(c.prepared.triangleCount()));
  state.counters["drawn"] = double(stats.counter("occlusion: occluders rasterized"));
  state.counters["skipped"] = double(stats.counter("occlusion: occluders skipped"));
}

void occludees(benchmark::State& state, bool withPyramid) {
  const City& c = city();
  const MapView view(c.camera, 256, 128);
  hsr::Stats stats;
  const DepthMap map = occluderDepthMap(c.prepared, view, Knobs{}, c.everyObject, stats);
  const Pyramid pyramid(map);
  std::vector<BoxFootprint> boxes;
  for (const hsr::Instance& instance : c.prepared.instances()) boxes.push_back(footprint(view, instance.box));
  std::int64_t hidden = 0, read = 0;
  for (auto _ : state) {
    hidden = 0;
    for (const BoxFootprint& box : boxes) hidden += withPyramid ? pyramid.hidden(box, read) : hiddenOnMap(map, box, read);
    benchmark::DoNotOptimize(hidden);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(boxes.size()));
  state.counters["hidden"] = double(hidden);
}

void zbufferDepth(benchmark::State& state) {
  const City& c = city();
  hsr::PreparedScene prepared(c.scene);
  prepared.setSize(1920, 1080);
  hsr::Frame frame(1920, 1080);
  for (auto _ : state) {
    hsr::Stats stats;
    const hsr::ScreenGeometry geometry = hsr::buildScreenTriangles(prepared, {}, 1, stats);
    hsr::zbuffer::renderFullFrame(geometry, hsr::DepthFormat::float32, 1, frame, stats);
    benchmark::DoNotOptimize(frame.depth.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(prepared.triangleCount()));
}

}  // namespace

// Registered before main (bench_main.cpp), from the lists of variants and scenes.
const bool registered = [] {
  for (const auto& [name, rule] : {std::pair("center", Rule::center), std::pair("conservative", Rule::conservative)})
    for (const auto& [width, height] : {std::pair(256, 128), std::pair(1920, 1080)})
      benchmark::RegisterBenchmark(("occluders/" + std::string(name) + "/" + std::to_string(width) + "x" + std::to_string(height)).c_str(),
                                   occluders, rule, width, height)
          ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("occludees/flat", occludees, false)->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("occludees/pyramid", occludees, true)->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("zbuffer-depth", zbufferDepth)->Unit(benchmark::kMillisecond);
  return true;
}();
