// The shipped scenes the benchmarks time, loaded once per program at 1280 x 720.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "renderer/prepare.hpp"

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

}  // namespace hsr::bench
