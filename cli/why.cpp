// hsr why: a pixel's history in an algorithm, beside the exact reference's answer
// (pipeline/why.hpp).
#include <cstdio>
#include <optional>
#include <set>

#include "algorithms/registry.hpp"
#include "cli/commands.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/why.hpp"
#include "renderer/util/error.hpp"
#include "studies/common.hpp"

namespace hsr::cli {

namespace {

// hsr why --edge: how a line algorithm's walk decided one edge.
int whyAlongEdge(const WhyOptions& options) {
  pipeline::checkAnswersWhyAlongEdges(findAlgorithm(options.algorithm));
  const pipeline::Configuration configuration = configurationOf(options);
  const studies::LoadedScene scene = studies::loadPrepared(options.scene, options.size);
  pipeline::checkRenders(configuration, scene.name, *scene.prepared);
  Stats stats;
  const pipeline::EdgeAnswer answer = pipeline::explainEdge(*scene.prepared, configuration, options.edge, options.threads, stats);
  const std::string shown = options.json ? pipeline::edgeJson(*scene.prepared, scene.name, configuration, answer)
                                         : pipeline::edgeText(*scene.prepared, scene.name, configuration, answer);
  std::fputs(shown.c_str(), stdout);
  return 0;
}

}  // namespace

int why(const WhyOptions& options) {
  if (!options.edge.empty()) return whyAlongEdge(options);
  if (options.pixels.empty()) throw InputError("hsr why: --pixel X,Y or --edge E is required");
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
  std::optional<pipeline::StepAsked> step;
  if (options.step < 0 && options.every > 0) throw InputError("--every " + std::to_string(options.every) + ": applies only with --step N");
  if (options.step >= 0) {
    step.emplace();
    step->number = std::size_t(options.step);
    step->every = std::size_t(options.every);
  }
  pipeline::StepAsked* asked = step ? &*step : nullptr;
  Stats stats;
  std::vector<pipeline::PixelAnswer> answers;
  try {
    answers = pipeline::explainPixels(*scene.prepared, configuration, pixels, options.threads, stats, asked);
  } catch (const std::bad_alloc&) {
    throw InputError(pipeline::outOfMemory(scene.prepared->width(), scene.prepared->height(), configuration.algorithm->name));
  }
  const std::string shown = options.json ? pipeline::whyJson(*scene.prepared, scene.name, configuration, answers, asked)
                                         : pipeline::whyText(*scene.prepared, scene.name, configuration, answers, asked);
  std::fputs(shown.c_str(), stdout);
  return 0;
}

}  // namespace hsr::cli
