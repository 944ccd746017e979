// hsr why: a pixel's history in an algorithm, beside the exact reference's answer
// (pipeline/why.hpp).
#include <cstdio>
#include <set>

#include "algorithms/registry.hpp"
#include "cli/commands.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/why.hpp"
#include "renderer/util/error.hpp"
#include "studies/common.hpp"

namespace hsr::cli {

int why(const WhyOptions& options) {
  pipeline::checkAnswersWhy(findAlgorithm(options.algorithm));
  const pipeline::Configuration configuration = configurationOf(options);

  const studies::LoadedScene scene = studies::loadPrepared(options.scene, options.size);
  pipeline::checkRenders(configuration, scene.name, *scene.prepared);
  std::vector<PixelWitness::Pixel> pixels;
  std::set<std::pair<int, int>> seen;
  for (const std::string& text : options.pixels) {
    const PixelWitness::Pixel pixel = pipeline::pixelOf(text, scene.prepared->width(), scene.prepared->height());
    if (!seen.insert({pixel.x, pixel.y}).second) throw InputError("--pixel " + text + ": given twice; expected each pixel once");
    pixels.push_back(pixel);
  }
  Stats stats;
  std::vector<pipeline::PixelAnswer> answers;
  try {
    answers = pipeline::explainPixels(*scene.prepared, configuration, pixels, options.threads, stats);
  } catch (const std::bad_alloc&) {
    throw InputError(pipeline::outOfMemory(scene.prepared->width(), scene.prepared->height(), configuration.algorithm->name));
  }
  const std::string shown = options.json ? pipeline::whyJson(*scene.prepared, scene.name, configuration, answers)
                                         : pipeline::whyText(*scene.prepared, scene.name, configuration, answers);
  std::fputs(shown.c_str(), stdout);
  return 0;
}

}  // namespace hsr::cli
