// hsr render and hsr list.
#include <cstdio>

#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "algorithms/culling/culling.hpp"
#include "algorithms/effects/effects.hpp"
#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "cli/results.hpp"
#include "renderer/depth.hpp"
#include "renderer/error.hpp"
#include "renderer/frame.hpp"
#include "renderer/line_set.hpp"
#include "renderer/line_drawing.hpp"

namespace hsr::cli {
namespace {

LineStyle lineStyleOf(const std::string& name, bool lineAlgorithm) {
  if (name.empty()) return LineStyle::visible;
  if (!lineAlgorithm) {
    std::string names;
    for (const AlgorithmEntry& entry : algorithms())
      if (entry.kind == "line") names += (names.empty() ? "" : ", ") + entry.name;
    throw InputError("--line-style " + name + ": applies only to line algorithms (" + names + ")");
  }
  if (name == "visible") return LineStyle::visible;
  if (name == "hidden") return LineStyle::hidden;
  if (name == "qi") return LineStyle::qi;
  throw InputError("--line-style " + name + ": expected visible, hidden or qi");
}

// The algorithms that can draw a culled set of triangles: "zbuffer or painter".
std::string cullableAlgorithms() {
  std::string names;
  for (const AlgorithmEntry& entry : algorithms())
    if (entry.renderVisible) names += (names.empty() ? "" : " or ") + entry.name;
  return names;
}

// The culling stages asked for, checked against what the algorithm can take.
culling::Pipeline cullingPipelineOf(const std::string& text, const AlgorithmEntry& algorithm) {
  if (text.empty()) return {};
  culling::Pipeline pipeline = culling::parsePipeline(text, "--cull");
  if (!algorithm.renderVisible)
    throw InputError("--cull: " + algorithm.name + " does not draw from a culled set of triangles; expected --algo " +
                     cullableAlgorithms());
  return pipeline;
}

// Each knob with its values, default and help; `prefix` is how it is given ("--knob "
// for an algorithm, ":" after a culling stage).
void printKnobs(const std::vector<KnobSpec>& knobs, const std::string& prefix) {
  for (const auto& knob : knobs) {
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
    std::printf("    %s%s=%s   (default %s%s)\n      %s\n", prefix.c_str(), knob.name.c_str(), choices.c_str(),
                knob.choices.front().c_str(), applies.c_str(), knob.help.c_str());
  }
}

void printPlan(const LoadedScene& scene, const AlgorithmEntry& algorithm, const KnobValues& knobs, const std::string& culling) {
  std::printf("passes for %s with %s (%s):\n", scene.name.c_str(), algorithm.name.c_str(), describeKnobs(algorithm, knobs).c_str());
  for (const effects::PlannedPass& pass : effects::planPasses(*scene.prepared, algorithm, culling))
    std::printf("  %-5s %-28s %s\n", pass.runs ? "run" : "skip", pass.pass.c_str(), pass.reason.c_str());
}

// The nearest and farthest view distances a frame shows (its finite depths), if any.
std::optional<std::pair<double, double>> visibleDepths(const Frame& frame) {
  double nearest = std::numeric_limits<double>::infinity(), farthest = 0;
  for (const float d : frame.depth)
    if (std::isfinite(d)) nearest = std::min(nearest, double(d)), farthest = std::max(farthest, double(d));
  if (!(nearest <= farthest)) return std::nullopt;
  return std::pair(nearest, farthest);
}

// Each depth format's resolution (depth.hpp) at the nearest and farthest visible depth.
void printDepthResolutions(const CameraTransform& camera, std::pair<double, double> depths) {
  std::printf("depth resolution (the smallest separation stored apart) at the nearest (%.4g) and farthest (%.4g) visible depth:\n",
              depths.first, depths.second);
  for (std::size_t f = 0; f < depthFormatNames().size(); ++f)
    std::printf("  %-22s %10.3g %10.3g\n", depthFormatNames()[f].c_str(), depthResolution(DepthFormat(f), camera, depths.first),
                depthResolution(DepthFormat(f), camera, depths.second));
}

// One line when the z-buffer's format could not order some fragments: how many, and the
// format that resolves the finest separation at the farthest visible depth, if finer.
void warnAboutDepthTies(std::int64_t ties, const std::string& formatName, const CameraTransform& camera, double farthest) {
  const auto& names = depthFormatNames();
  const auto current = DepthFormat(std::find(names.begin(), names.end(), formatName) - names.begin());
  const auto resolution = [&](DepthFormat format) { return depthResolution(format, camera, farthest); };
  DepthFormat finest = current;
  for (std::size_t f = 0; f < names.size(); ++f)
    if (resolution(DepthFormat(f)) < resolution(finest)) finest = DepthFormat(f);
  const std::string atFarthest = " at the farthest visible depth (" + formatted(farthest) + ")";
  const std::string advice =
      finest != current ? std::string(depthFormatName(finest)) + " resolves " + formatted(resolution(finest), "%.3g") + atFarthest +
                              " where " + formatName + " resolves " + formatted(resolution(current), "%.3g") +
                              " (--depth-format; --explain lists every format)"
                        : "no format resolves finer than " + formatName + "'s " + formatted(resolution(current), "%.3g") + atFarthest +
                              ": the surfaces may be coplanar";
  std::fprintf(stderr, "hsr: warning: %lld depth ties: fragments of different triangles stored at the same %s depth, where drawing order decided the pixel; %s\n",
               static_cast<long long>(ties), formatName.c_str(), advice.c_str());
}

void printDecisions(const Stats& stats, double seconds) {
  std::printf("decided while rendering:\n");
  for (const std::string& decision : effects::decisionsTaken(stats)) std::printf("  %s\n", decision.c_str());
  std::printf("time per pass (%.1f ms in all):\n", seconds * 1e3);
  for (const effects::PassTime& pass : effects::passTimes(stats, seconds))
    std::printf("  %-14s %8.2f ms\n", pass.pass.c_str(), pass.seconds * 1e3);
}

}  // namespace

int render(const RenderOptions& options) {
  const AlgorithmEntry& algorithm = findAlgorithm(options.algorithm);
  KnobSettings settings;
  if (!options.variant.empty()) settings.emplace_back("variant", options.variant);
  if (!options.depthFormat.empty()) settings.emplace_back("depth-format", options.depthFormat);
  for (const std::string& knob : options.knobs) settings.push_back(parseKnobSetting(knob, "--knob"));
  const KnobValues knobs = resolveKnobs(algorithm, settings);

  const bool lines = algorithm.kind == "line";
  const std::filesystem::path output = options.output;
  const LineStyle style = lineStyleOf(options.lineStyle, lines);
  const culling::Pipeline pipeline = cullingPipelineOf(options.cull, algorithm);
  if (output.extension() == ".svg" && !lines)
    throw InputError("-o " + options.output + ": SVG is for line drawings, and " + algorithm.name +
                     " draws surfaces; expected a .png file");
  if (lines && (!options.depth.empty() || !options.ids.empty()))
    throw InputError(std::string(options.depth.empty() ? "--ids" : "--depth") + ": " + algorithm.name +
                     " draws lines, which have no depth or id image");

  const LoadedScene scene = loadPrepared(options.scene, options.size);
  checkRenders(algorithm, knobs, scene.name, *scene.prepared);
  if (options.explain) printPlan(scene, algorithm, knobs, options.cull);
  const auto start = std::chrono::steady_clock::now();
  Stats stats;
  OutputFiles outputs;
  Frame frame;
  std::string partial;  // why the image or drawing may be wrong somewhere, as the algorithm says
  if (lines) {
    const LineSet drawing = algorithm.drawLines(*scene.prepared, knobs, options.threads, stats);
    if (output.extension() == ".svg") outputs.addText(output, lineSetSvg(drawing, style));
    else outputs.addColorPng(output, lineSetFrame(drawing, style));
    partial = drawing.partial;
  } else {
    if (pipeline.empty()) {
      frame = algorithm.render(*scene.prepared, knobs, options.threads, stats);
    } else {
      const VisibleSet visible = culling::runPipeline(*scene.prepared, pipeline, options.threads, stats);
      frame = algorithm.renderVisible(*scene.prepared, knobs, visible, options.threads, stats);
    }
    outputs.addColorPng(output, frame);
    partial = frame.partial;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!options.depth.empty()) outputs.addDepthExr(options.depth, frame);
  if (!options.ids.empty()) outputs.addIdsPng(options.ids, frame);
  outputs.commit();
  if (!partial.empty()) std::fprintf(stderr, "hsr: warning: the %s is partial: %s\n", lines ? "drawing" : "image", partial.c_str());
  const CameraTransform& camera = scene.prepared->camera();
  const std::optional<std::pair<double, double>> depths = lines ? std::nullopt : visibleDepths(frame);
  if (stats.counter("depth ties") > 0 && depths)
    warnAboutDepthTies(stats.counter("depth ties"), knobs.at("depth-format"), camera, depths->second);
  if (options.stats) std::printf("%s", stats.report().c_str());
  if (options.explain) {
    printDecisions(stats, seconds);
    if (depths) printDepthResolutions(camera, *depths);
  }
  return 0;
}

int list() {
  std::printf("algorithms:\n");
  for (const auto& algorithm : algorithms()) {
    std::printf("  %-12s %-9s %s\n", algorithm.name.c_str(), algorithm.kind.c_str(), algorithm.summary.c_str());
    printKnobs(algorithm.knobs, "--knob ");
  }
  std::printf("culling stages (hsr render --cull STAGE[:VARIANT][:KNOB=VALUE...],...; before %s):\n", cullableAlgorithms().c_str());
  for (const auto& stage : culling::stages()) {
    std::printf("  %-12s %s\n", stage.name.c_str(), stage.summary.c_str());
    for (const auto& [variant, help] : stage.variants)
      std::printf("    %s:%-16s %s%s\n", stage.name.c_str(), variant.c_str(), help.c_str(),
                  variant == stage.variants.front().first ? " (default)" : "");
    printKnobs(stage.knobs, ":");
  }
  std::printf("effects (a scene's effects list: one shading, then any of the others):\n");
  for (const EffectName& effect : effectNames()) std::printf("  %-12s %s\n", effect.name, effect.summary);
  std::printf("scenes (in %s):\n", HSR_SCENES_DIR);
  for (const auto& scene : shippedScenes()) std::printf("  %s\n", scene.string().c_str());
  return 0;
}

}  // namespace hsr::cli
