// hsr render and hsr list.
#include <cstdio>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "renderer/frame.hpp"

namespace hsr::cli {

int render(const RenderOptions& options) {
  const AlgorithmEntry& algorithm = findAlgorithm(options.algorithm);
  KnobSettings settings;
  if (!options.variant.empty()) settings.emplace_back("variant", options.variant);
  if (!options.depthFormat.empty()) settings.emplace_back("depth-format", options.depthFormat);
  for (const std::string& knob : options.knobs) settings.push_back(parseKnobSetting(knob, "--knob"));
  const KnobValues knobs = resolveKnobs(algorithm, settings);

  const LoadedScene scene = loadPrepared(options.scene, options.size);
  checkRenders(algorithm, knobs, scene.name, *scene.prepared);
  Stats stats;
  const Frame frame = algorithm.render(*scene.prepared, knobs, options.threads, stats);

  OutputFiles outputs;
  outputs.addColorPng(options.output, frame);
  if (!options.depth.empty()) outputs.addDepthExr(options.depth, frame);
  if (!options.ids.empty()) outputs.addIdsPng(options.ids, frame);
  outputs.commit();
  if (!frame.partial.empty()) std::fprintf(stderr, "hsr: warning: the image is partial: %s\n", frame.partial.c_str());
  if (options.stats) std::printf("%s", stats.report().c_str());
  return 0;
}

int list() {
  std::printf("algorithms:\n");
  for (const auto& algorithm : algorithms()) {
    std::printf("  %-12s %-9s %s\n", algorithm.name.c_str(), algorithm.kind.c_str(), algorithm.summary.c_str());
    for (const auto& knob : algorithm.knobs) {
      std::string choices;
      for (const auto& choice : knob.choices) choices += (choices.empty() ? "" : " | ") + choice;
      if (knob.range) {
        char range[96];
        std::snprintf(range, sizeof range, "%s in [%g, %g]%s, e.g. ", knob.range->integer ? "INTEGER" : "NUMBER",
                      knob.range->minimum, knob.range->maximum, knob.range->percent ? " or P%" : "");
        choices = range + choices;
      }
      std::string applies;
      for (const auto& variant : knob.variants) applies += (applies.empty() ? ", variant " : " or ") + variant;
      std::printf("    --knob %s=%s   (default %s%s)\n      %s\n", knob.name.c_str(), choices.c_str(),
                  knob.choices.front().c_str(), applies.c_str(), knob.help.c_str());
    }
  }
  std::printf("scenes (in %s):\n", HSR_SCENES_DIR);
  for (const auto& scene : shippedScenes()) std::printf("  %s\n", scene.string().c_str());
  return 0;
}

}  // namespace hsr::cli
