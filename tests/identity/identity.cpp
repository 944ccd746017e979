// The renders every target must give bit for bit the same (identity.hpp).
#include "identity/identity.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "algorithms/registry.hpp"
#include "pipeline/pipeline.hpp"
#include "property/random_scene.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/util/error.hpp"

namespace hsr::identity {
namespace {

// FNV-1a over bytes: the same everywhere (std::hash is not).
std::uint64_t hashOf(const void* data, std::size_t bytes, std::uint64_t hash = 1469598103934665603ull) {
  const auto* byte = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) hash = (hash ^ byte[i]) * 1099511628211ull;
  return hash;
}
template <typename T, typename Allocator>
std::uint64_t hashOf(const std::vector<T, Allocator>& values) {
  return hashOf(values.data(), values.size() * sizeof(T));
}

// A drawing's bits: every edge's projection and every piece with its QI.
std::uint64_t hashOf(const LineSet& drawing) {
  std::uint64_t hash = 1469598103934665603ull;
  for (const FeatureEdge& edge : drawing.edges) {
    const double ends[4] = {edge.pixelFrom.x, edge.pixelFrom.y, edge.pixelTo.x, edge.pixelTo.y};
    hash = hashOf(ends, sizeof ends, hash);
  }
  for (const LineSegment& segment : drawing.segments) {
    hash = hashOf(&segment.edge, sizeof segment.edge, hash);
    hash = hashOf(&segment.begin, sizeof segment.begin, hash);
    hash = hashOf(&segment.end, sizeof segment.end, hash);
    hash = hashOf(&segment.qi, sizeof segment.qi, hash);
  }
  return hash;
}

struct Configuration {
  const char* algorithm;
  KnobSettings knobs;
};

// The configurations the goldens cover (tests/golden/golden_test.cpp), and the reference.
const std::vector<Configuration> kConfigurations = {
    {"reference", {}},
    {"zbuffer", {}},
    {"zbuffer", {{"variant", "scanline"}}},
    {"zbuffer", {{"depth-format", "unorm16"}}},
    {"ray_casting", {}},
    {"ray_casting", {{"variant", "march"}}},
    {"painter", {}},
    {"painter", {{"variant", "newell"}}},
    {"painter", {{"variant", "sort"}}},
    {"warnock", {}},
    {"watkins", {}},
    {"weiler_atherton", {}},
    {"abuffer", {}},
    {"roberts", {}},
    {"appel", {}},
    {"floating_horizon", {}},
};

std::string describe(const Configuration& configuration) {
  std::string text = configuration.algorithm;
  for (const auto& [knob, value] : configuration.knobs) text += ":" + knob + "=" + value;
  return text;
}

std::string hex(std::uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

// One render's line: its hashes, or why it was refused.
std::string renderLine(const std::string& sceneName, const Scene& scene, const Configuration& wanted, int width, int threads) {
  PreparedScene prepared(scene);
  prepared.setSize(width, std::max(1, width * scene.height / scene.width));
  const std::string start = sceneName + " " + describe(wanted) + " ";
  try {
    const pipeline::Configuration configuration = pipeline::configurationOf(findAlgorithm(wanted.algorithm), wanted.knobs);
    if (const std::string refusal = pipeline::refusal(prepared, configuration); !refusal.empty()) return start + "refused: " + refusal;
    Stats stats;
    const pipeline::Rendered rendered = pipeline::render(prepared, configuration, threads, stats);
    if (configuration.algorithm->kind == AlgorithmKind::line) return start + "drawing=" + hex(hashOf(rendered.drawing));
    return start + "ids=" + hex(hashOf(rendered.frame.ids)) + " depth=" + hex(hashOf(rendered.frame.distances())) +
           " color=" + hex(hashOf(rendered.frame.color));
  } catch (const InputError& error) {
    return start + "refused: " + error.what();
  }
}

}  // namespace

void renderLines(const std::filesystem::path& scenes, const Options& options, const std::function<void(const std::string&)>& line) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(scenes))
    if (entry.path().extension() == ".toml" && entry.path().parent_path().filename() != "study")
      names.push_back(std::filesystem::relative(entry.path(), scenes).generic_string());
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) {
    if (!options.only.empty() && name.find(options.only) == std::string::npos) continue;
    try {
      const Scene scene = loadScene(scenes / name);
      for (const Configuration& configuration : kConfigurations) line(renderLine(name, scene, configuration, options.width, options.threads));
    } catch (const InputError& error) {
      line(name + " refused: " + error.what());
    }
  }
  for (int seed = 1; seed <= options.randomScenes; ++seed) {
    const test::RandomScene generated = test::randomScene(std::uint64_t(seed));
    for (const Configuration& configuration : kConfigurations)
      if (findAlgorithm(configuration.algorithm).kind != AlgorithmKind::line)
        line(renderLine("random/" + std::to_string(seed), generated.scene, configuration, 32, options.threads));
  }
}

}  // namespace hsr::identity

