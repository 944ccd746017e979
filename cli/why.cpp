// hsr why: a pixel's history in an algorithm, beside the exact reference's answer
// (pipeline/why.hpp).
#include <cstdio>
#include <regex>
#include <set>

#include "algorithms/registry.hpp"
#include "cli/commands.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/why.hpp"
#include "renderer/util/error.hpp"
#include "studies/common.hpp"

namespace hsr::cli {
namespace {

PixelWitness::Pixel pixelOf(const std::string& text, int width, int height) {
  std::smatch match;
  if (!std::regex_match(text, match, std::regex(R"(\s*(\d{1,9})\s*,\s*(\d{1,9})\s*)")))
    throw InputError("--pixel " + text + ": expected X,Y (a column and a row counted from the top left, e.g. 640,360)");
  const long long x = std::stoll(match[1]), y = std::stoll(match[2]);
  if (x >= width || y >= height)
    throw InputError("--pixel " + text + ": outside the " + std::to_string(width) + "x" + std::to_string(height) + " image; expected X in [0, " +
                     std::to_string(width - 1) + "] and Y in [0, " + std::to_string(height - 1) + "]");
  return {int(x), int(y)};
}

}  // namespace

int why(const WhyOptions& options) {
  const AlgorithmEntry& algorithm = findAlgorithm(options.algorithm);
  if (!algorithm.answersWhy)
    throw InputError("--algo " + algorithm.name + ": hsr why follows the loops of " + pipeline::algorithmsAnsweringWhy() +
                     " so far; expected one of those");
  KnobSettings settings;
  if (!options.variant.empty()) settings.emplace_back("variant", options.variant);
  if (!options.depthFormat.empty()) settings.emplace_back("depth-format", options.depthFormat);
  for (const std::string& knob : options.knobs) settings.push_back(parseKnobSetting(knob, "--knob"));
  pipeline::Configuration configuration = pipeline::configurationOf(algorithm, settings);
  configuration.culling = pipeline::cullingOf(options.cull, algorithm);

  const studies::LoadedScene scene = studies::loadPrepared(options.scene, options.size);
  pipeline::checkRenders(configuration, scene.name, *scene.prepared);
  std::vector<PixelWitness::Pixel> pixels;
  std::set<std::pair<int, int>> seen;
  for (const std::string& text : options.pixels) {
    const PixelWitness::Pixel pixel = pixelOf(text, scene.prepared->width(), scene.prepared->height());
    if (!seen.insert({pixel.x, pixel.y}).second) throw InputError("--pixel " + text + ": given twice; expected each pixel once");
    pixels.push_back(pixel);
  }
  Stats stats;
  std::vector<pipeline::PixelAnswer> answers;
  try {
    answers = pipeline::explainPixels(*scene.prepared, configuration, pixels, options.threads, stats);
  } catch (const std::bad_alloc&) {
    throw InputError(pipeline::outOfMemory(scene.prepared->width(), scene.prepared->height(), algorithm.name));
  }
  const std::string shown = options.json ? pipeline::whyJson(*scene.prepared, scene.name, configuration, answers)
                                         : pipeline::whyText(*scene.prepared, scene.name, configuration, answers);
  std::fputs(shown.c_str(), stdout);
  return 0;
}

}  // namespace hsr::cli
