// Occlusion culling's throughput on the MOC benchmark city (scenes/city.toml without its
// ground: 8,334 boxes, 100,008 triangles, seen at 1920 x 1080), single thread (README "Speed",
// algorithms/culling/README.md):
//   occluders/RULE/WxH   every box offered as an occluder, nearest first, drawn into a
//                        W x H map unless the boxes already drawn hide it; items: the
//                        city's triangles, so items/s is the triangle throughput;
//                        counters: occluders drawn, skipped and outside the map, texels
//                        written and texels covered at the end
//   occluders/floor/WxH  the machine's floor for such a map: its keys cleared (every
//                        texel to +infinity, as each map starts), the least either rule's
//                        pass could take; measured in the same run as the passes
//   occludees/TEST       each of the 8,334 boxes tested against the 256 x 128 map of the
//                        conservative rule: flat (every texel until one proves it
//                        visible) or with the hierarchical-Z pyramid; items: tests
//   zbuffer-depth        for scale: hsr's z-buffer (geometry stage and float depth
//                        raster) of the whole city at 1920 x 1080
//   gpu/query, gpu/draw  on the simulated GPU (algorithms/culling/occlusion/simulated_gpu.hpp), at 1920 x 1080
//                        with the 500 nearest buildings drawn: the next 100 buildings'
//                        boxes queried, or the buildings themselves drawn (what a query
//                        spares); items: buildings
//   queries/STRATEGY     ten frames of a walk down a street of study/city_walk (640 x 360)
//                        by each query strategy on one simulated GPU; items: frames
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "algorithms/culling/culling.hpp"
#include "algorithms/culling/occlusion/occlusion.hpp"
#include "algorithms/culling/occlusion/simulated_gpu.hpp"
#include "algorithms/zbuffer/zbuffer.hpp"
#include "bench_scenes.hpp"
#include "renderer/raster/screen_triangles.hpp"

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
  // Texels written against texels covered at the end (the overdraw), from one more map.
  stats = hsr::Stats();
  const DepthMap map = occluderDepthMap(c.prepared, view, settings, c.everyObject, stats);
  state.counters["written"] = double(stats.counter("occlusion: texels written"));
  state.counters["covered"] = double(std::count_if(map.keys.begin(), map.keys.end(), [](float key) { return std::isfinite(key); }));
  state.SetItemsProcessed(state.iterations() * std::int64_t(c.prepared.triangleCount()));
  state.counters["drawn"] = double(stats.counter("occlusion: occluders rasterized"));
  state.counters["skipped"] = double(stats.counter("occlusion: occluders skipped"));
  state.counters["outside"] = double(stats.counter("occlusion: occluders outside the map"));
}

void clearedMap(benchmark::State& state, int width, int height) {
  DepthMap map(width, height);
  for (auto _ : state) {
    std::fill(map.keys.begin(), map.keys.end(), std::numeric_limits<float>::infinity());
    benchmark::DoNotOptimize(map.keys.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * std::int64_t(map.keys.size() * sizeof(float)));
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

// The city on a simulated GPU at 1920 x 1080 with its 500 nearest buildings drawn, and
// the next 100 to query or draw.
struct GpuCity {
  hsr::PreparedScene prepared{city().scene};
  hsr::SimulatedGpu gpu;
  std::vector<std::uint32_t> next;
  GpuCity() {
    prepared.setSize(1920, 1080);
    gpu.beginFrame(prepared.camera());
    const std::vector<std::uint32_t>& nearestFirst = city().everyObject;
    for (std::size_t i = 0; i < 600 && i < nearestFirst.size(); ++i) {
      if (i < 500)
        draw(nearestFirst[i]);
      else
        next.push_back(nearestFirst[i]);
    }
  }
  void draw(std::uint32_t object) {
    const hsr::Instance& building = prepared.instances()[object];
    std::vector<std::uint32_t> triangles(building.triangleCount);
    for (std::uint32_t t = 0; t < building.triangleCount; ++t) triangles[t] = building.firstTriangle + t;
    gpu.draw(prepared, object, triangles);
  }
};

void gpuQuery(benchmark::State& state) {
  static GpuCity c;
  std::int64_t passed = 0;
  for (auto _ : state)
    for (const std::uint32_t object : c.next) passed += c.gpu.answer(c.gpu.query({&c.prepared.instances()[object].box, 1}));
  benchmark::DoNotOptimize(passed);
  state.SetItemsProcessed(state.iterations() * std::int64_t(c.next.size()));
}

void gpuDraw(benchmark::State& state) {
  static GpuCity c;
  for (auto _ : state)
    for (const std::uint32_t object : c.next) c.draw(object);  // drawn again and again: the same work each time
  state.SetItemsProcessed(state.iterations() * std::int64_t(c.next.size()));
}

void queryWalk(benchmark::State& state, const std::string& strategy) {
  hsr::Scene scene = hsr::loadScene(std::string(HSR_SOURCE_DIR) + "/scenes/study/city_walk.toml");
  hsr::PreparedScene prepared(scene);
  prepared.setSize(640, 360);
  const hsr::culling::Pipeline pipeline = hsr::culling::parsePipeline("frustum,occlusion:queries:" + strategy);
  const hsr::Camera start = scene.camera;
  hsr::Stats stats;
  for (auto _ : state) {
    std::vector<std::unique_ptr<hsr::culling::StageMemory>> memory;
    hsr::SimulatedGpu gpu;
    scene.camera = start;
    for (int frame = 0; frame < 10; ++frame) {
      gpu.beginFrame(prepared.camera());
      const hsr::culling::PreviousFrame previous{scene.camera, nullptr, &memory, &gpu};
      benchmark::DoNotOptimize(hsr::culling::runPipeline(prepared, pipeline, 1, stats, &previous).triangles.data());
      gpu.endFrame();
      scene.camera.eye.z -= 0.5, scene.camera.target.z -= 0.5;
    }
  }
  state.SetItemsProcessed(state.iterations() * 10);
}

}  // namespace

// Registered before main (bench_main.cpp), from the lists of variants and scenes.
const bool registered = [] {
  for (const auto& [name, rule] : {std::pair("center", Rule::center), std::pair("conservative", Rule::conservative)})
    for (const auto& [width, height] : {std::pair(256, 128), std::pair(1920, 1080)})
      benchmark::RegisterBenchmark(("occluders/" + std::string(name) + "/" + std::to_string(width) + "x" + std::to_string(height)).c_str(),
                                   occluders, rule, width, height)
          ->Unit(benchmark::kMillisecond);
  for (const auto& [width, height] : {std::pair(256, 128), std::pair(1920, 1080)})
    benchmark::RegisterBenchmark(("occluders/floor/" + std::to_string(width) + "x" + std::to_string(height)).c_str(), clearedMap, width, height)
        ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("occludees/flat", occludees, false)->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("occludees/pyramid", occludees, true)->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("zbuffer-depth", zbufferDepth)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("gpu/query", gpuQuery)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("gpu/draw", gpuDraw)->Unit(benchmark::kMillisecond);
  for (const std::string strategy : {"stop-and-wait", "delayed", "chc", "chcpp"})
    benchmark::RegisterBenchmark(("queries/" + strategy).c_str(), queryWalk, strategy)->Unit(benchmark::kMillisecond);
  return true;
}();
