// What the hsr subcommands share: parsing sizes and algorithm choices, loading scenes
// up front (so bad input fails before any work), and the output folder.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "algorithms/registry.hpp"
#include "pipeline/pipeline.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/scene/scene.hpp"

namespace hsr::studies {

constexpr int kBadInput = 2;

// Comma-separated values of a list option ("a,b,c"); empty items are an error.
std::vector<std::string> splitList(const std::string& text, const std::string& where);

// An algorithm with validated knobs: "zbuffer" or "zbuffer:variant=scanline:depth-format=unorm16".
pipeline::Configuration parseConfiguration(const std::string& text, const std::string& where);

// A loaded scene and its prepared geometry (PreparedScene keeps a pointer to the Scene).
struct LoadedScene {
  std::string name;  // as given on the command line
  std::unique_ptr<Scene> scene;
  std::unique_ptr<PreparedScene> prepared;
};
LoadedScene loadPrepared(const std::string& path, const std::string& size);

// A scene file as given: a path, or the name of a shipped scene as `hsr list` prints it,
// with or without ".toml" ("counters", "hard/coplanar"). A path that exists wins; a name
// that is neither is an InputError saying both were tried.
std::filesystem::path sceneFile(const std::string& given);


// Creates the folder (and parents) or throws InputError naming it.
void makeFolder(const std::filesystem::path& folder, const std::string& where);

// The shipped scene files (relative to HSR_SCENES_DIR), sorted.
std::vector<std::filesystem::path> shippedScenes();

}  // namespace hsr::studies
