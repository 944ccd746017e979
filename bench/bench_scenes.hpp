// The shipped scenes the benchmarks time, loaded once per program at 1280 x 720, and a
// whole render of one of them (the pipeline) with an algorithm's knobs as its struct.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "algorithms/registry.hpp"
#include "pipeline/pipeline.hpp"
#include "renderer/scene/prepare.hpp"

namespace hsr::bench {

inline constexpr const char* kScenes[] = {"dragons", "counters"};

struct LoadedScene {
  Scene scene;
  std::unique_ptr<PreparedScene> prepared;
};

inline const LoadedScene& sceneNamed(const std::string& name) {
  static std::map<std::string, LoadedScene> loaded;
  LoadedScene& entry = loaded[name];
  if (!entry.prepared) {
    entry.scene = loadScene(std::string(HSR_SOURCE_DIR) + "/scenes/" + name + ".toml");
    entry.prepared = std::make_unique<PreparedScene>(entry.scene);
    entry.prepared->setSize(1280, 720);
  }
  return entry;
}

// The whole render (visibility and the passes the scene's effects call for) of an
// algorithm with these knobs (made by its knob table from its Knobs struct).
inline Frame render(const PreparedScene& scene, const char* algorithm, const KnobValues& knobs, int threads, Stats& stats) {
  return pipeline::render(scene, {&findAlgorithm(algorithm), knobs}, threads, stats).frame;
}

}  // namespace hsr::bench
