// hsr: the command-line front end. Every subcommand turns bad input into one line on
// stderr ("hsr: error: what, where, expected") and exit status 2, and writes no file.
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "algorithms/registry.hpp"
#include "renderer/error.hpp"
#include "renderer/frame.hpp"
#include "renderer/memory.hpp"
#include "renderer/prepare.hpp"
#include "renderer/scene.hpp"

namespace {

constexpr int kBadInput = 2;

struct RenderOptions {
  std::string scene;
  std::string algorithm = "zbuffer";
  std::string variant, depthFormat, size;
  std::vector<std::string> knobs;
  int threads = 0;
  std::string output, depth, ids;
  bool stats = false;
};

std::pair<int, int> parseSize(const std::string& text) {
  std::smatch match;
  if (!std::regex_match(text, match, std::regex(R"((\d{1,9})x(\d{1,9}))")))
    throw hsr::InputError("--size " + text + ": expected WIDTHxHEIGHT, e.g. 1280x720");
  const long long width = std::stoll(match[1]), height = std::stoll(match[2]);
  hsr::checkImageSize(width, height, "--size " + text);
  return {static_cast<int>(width), static_cast<int>(height)};
}

int render(const RenderOptions& options) {
  const hsr::AlgorithmEntry& algorithm = hsr::findAlgorithm(options.algorithm);
  std::vector<std::pair<std::string, std::string>> settings;
  if (!options.variant.empty()) settings.emplace_back("variant", options.variant);
  if (!options.depthFormat.empty()) settings.emplace_back("depth-format", options.depthFormat);
  for (const std::string& knob : options.knobs) {
    const auto equals = knob.find('=');
    if (equals == std::string::npos) throw hsr::InputError("--knob " + knob + ": expected NAME=VALUE");
    settings.emplace_back(knob.substr(0, equals), knob.substr(equals + 1));
  }
  const hsr::KnobValues knobs = hsr::resolveKnobs(algorithm, settings);

  const hsr::Scene scene = hsr::loadScene(options.scene);
  hsr::PreparedScene prepared(scene);
  if (!options.size.empty()) {
    const auto [width, height] = parseSize(options.size);
    prepared.setSize(width, height);
  }

  hsr::Stats stats;
  const hsr::Frame frame = algorithm.render(prepared, knobs, options.threads, stats);

  hsr::OutputFiles outputs;
  outputs.addColorPng(options.output, frame);
  if (!options.depth.empty()) outputs.addDepthExr(options.depth, frame);
  if (!options.ids.empty()) outputs.addIdsPng(options.ids, frame);
  outputs.commit();
  if (options.stats) std::printf("%s", stats.report().c_str());
  return 0;
}

int list() {
  std::printf("algorithms:\n");
  for (const auto& algorithm : hsr::algorithms()) {
    std::printf("  %-10s %-8s %s\n", algorithm.name.c_str(), algorithm.kind.c_str(), algorithm.summary.c_str());
    for (const auto& knob : algorithm.knobs) {
      std::string choices;
      for (const auto& choice : knob.choices) choices += (choices.empty() ? "" : " | ") + choice;
      std::printf("    --knob %s=%s   (default %s)\n      %s\n", knob.name.c_str(), choices.c_str(),
                  knob.choices.front().c_str(), knob.help.c_str());
    }
  }
  std::printf("scenes (in %s):\n", HSR_SCENES_DIR);
  std::vector<std::filesystem::path> scenes;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(HSR_SCENES_DIR))
    if (entry.path().extension() == ".toml") scenes.push_back(std::filesystem::relative(entry.path(), HSR_SCENES_DIR));
  std::sort(scenes.begin(), scenes.end());
  for (const auto& scene : scenes) std::printf("  %s\n", scene.string().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  hsr::keepFreedMemoryForReuse();
  CLI::App app{"hsr: classic hidden-surface algorithms on one software rasterizer"};
  app.require_subcommand(1);

  RenderOptions options;
  CLI::App* renderCommand = app.add_subcommand("render", "render a scene with one algorithm");
  renderCommand->add_option("scene", options.scene, "scene file (TOML)")->required();
  renderCommand->add_option("--algo", options.algorithm, "algorithm (see `hsr list`)")->capture_default_str();
  renderCommand->add_option("--variant", options.variant, "shorthand for --knob variant=V");
  renderCommand->add_option("--depth-format", options.depthFormat, "shorthand for --knob depth-format=F");
  renderCommand->add_option("--knob", options.knobs, "NAME=VALUE, any knob `hsr list` shows (repeatable)");
  renderCommand->add_option("--size", options.size, "WIDTHxHEIGHT, overrides the scene's image size");
  renderCommand->add_option("--threads", options.threads, "worker threads, 0 = all cores")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  renderCommand->add_option("-o,--output", options.output, "color image (.png)")->required();
  renderCommand->add_option("--depth", options.depth, "depth image (.exr): distance along the view axis");
  renderCommand->add_option("--ids", options.ids, "id image (.png): triangle index + 1 as 24-bit RGB, R high");
  renderCommand->add_flag("--stats", options.stats, "print counters and phase times");

  CLI::App* listCommand = app.add_subcommand("list", "list algorithms, their knobs, and the shipped scenes");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // Help is not an error; a usage mistake is one line and exit 2 like any bad input.
    if (error.get_exit_code() == 0) return app.exit(error);
    std::fprintf(stderr, "hsr: error: %s (see --help)\n", error.what());
    return kBadInput;
  }

  try {
    if (*renderCommand) return render(options);
    if (*listCommand) return list();
  } catch (const hsr::InputError& error) {
    std::fprintf(stderr, "hsr: error: %s\n", error.what());
    return kBadInput;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "hsr: error: %s\n", error.what());
    return 1;
  }
  return 0;
}
