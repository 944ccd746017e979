#include "studies/common.hpp"

#include <algorithm>

#include "renderer/util/error.hpp"

namespace hsr::studies {

std::vector<std::string> splitList(const std::string& text, const std::string& where) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    items.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (items.back().empty()) throw InputError(where + " " + text + ": empty item in a comma-separated list");
    if (comma == std::string::npos) return items;
    start = comma + 1;
  }
}

pipeline::Configuration parseConfiguration(const std::string& text, const std::string& where) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t colon; (colon = text.find(':', start)) != std::string::npos; start = colon + 1)
    parts.push_back(text.substr(start, colon - start));
  parts.push_back(text.substr(start));
  KnobSettings settings;
  for (std::size_t i = 1; i < parts.size(); ++i) settings.push_back(parseKnobSetting(parts[i], where + " " + text + ":"));
  const AlgorithmEntry& algorithm = findAlgorithm(parts[0], where);
  return {&algorithm, resolveKnobs(algorithm, settings, where + " " + parts[0] + ":")};
}

LoadedScene loadPrepared(const std::string& path, const std::string& size) {
  LoadedScene loaded;
  loaded.name = path;
  loaded.scene = std::make_unique<Scene>(loadScene(sceneFile(path)));
  loaded.prepared = std::make_unique<PreparedScene>(*loaded.scene);
  if (!size.empty()) {
    const auto [width, height] = parseSize(size, "--size");
    loaded.prepared->setSize(width, height);
  }
  return loaded;
}

std::filesystem::path sceneFile(const std::string& given) {
  const std::filesystem::path path = given;
  std::error_code error;
  if (std::filesystem::exists(path, error) || given.empty()) return path;
  for (const std::filesystem::path& shipped : shippedScenes())
    if (path == shipped || path == std::filesystem::path(shipped).replace_extension())
      return std::filesystem::path(HSR_SCENES_DIR) / shipped;
  throw InputError(given + ": cannot open the scene file (no such file), and no shipped scene has that name (hsr list names them)");
}

void makeFolder(const std::filesystem::path& folder, const std::string& where) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error || !std::filesystem::is_directory(folder))
    throw InputError(where + " " + folder.string() + ": cannot create the folder" + (error ? ": " + error.message() : ""));
}

std::vector<std::filesystem::path> shippedScenes() {
  std::vector<std::filesystem::path> scenes;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(HSR_SCENES_DIR))
    if (entry.path().extension() == ".toml") scenes.push_back(std::filesystem::relative(entry.path(), HSR_SCENES_DIR));
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

}  // namespace hsr::studies
