// hsr render and hsr list.
#include <cstdio>

#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "algorithms/culling/culling.hpp"
#include "algorithms/registry.hpp"
#include "cli/commands.hpp"
#include "pipeline/pipeline.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/image/pfm.hpp"
#include "renderer/lines/line_drawing.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/raster/depth.hpp"
#include "renderer/scene/triangle_file.hpp"
#include "renderer/steps/steps.hpp"
#include "renderer/util/error.hpp"
#include "studies/common.hpp"
#include "studies/results.hpp"

namespace hsr::cli {
namespace {

using studies::formatted;
using studies::LoadedScene;

LineStyle lineStyleOf(const std::string& name, bool lineAlgorithm) {
  if (name.empty()) return LineStyle::visible;
  if (!lineAlgorithm) {
    std::string names;
    for (const AlgorithmEntry& entry : algorithms())
      if (entry.kind == AlgorithmKind::line) names += (names.empty() ? "" : ", ") + entry.name;
    throw InputError("--line-style " + name + ": applies only to line algorithms (" + names + ")");
  }
  if (name == "visible") return LineStyle::visible;
  if (name == "hidden") return LineStyle::hidden;
  if (name == "qi") return LineStyle::qi;
  throw InputError("--line-style " + name + ": expected visible, hidden or qi");
}

// Each knob with its values, default and help; `prefix` is how it is given ("--knob "
// for an algorithm, ":" after a culling stage).
void printKnobs(const std::vector<KnobSpec>& knobs, const std::string& prefix) {
  for (const auto& knob : knobs) {
    std::string choices = knob.file ? "FILE" : "";
    for (const auto& choice : knob.choices) choices += (choices.empty() ? "" : " | ") + choice;
    if (knob.range) {
      char range[96];
      std::snprintf(range, sizeof range, "%s in [%g, %g]%s, e.g. ", knob.range->integer ? "INTEGER" : "NUMBER",
                    knob.range->minimum, knob.range->maximum, knob.range->percent ? " or P%" : "");
      choices = range + choices;
    }
    std::string applies;
    for (const auto& variant : knob.variants) applies += (applies.empty() ? ", variant " : " or ") + variant;
    std::printf("    %s%s=%s   (default %s%s)\n      %s%s\n", prefix.c_str(), knob.name.c_str(), choices.c_str(),
                knob.defaultValue.c_str(), applies.c_str(), knob.help.c_str(),
                knob.bare ? " (may be given bare, right after the variant: VARIANT:VALUE)" : "");
  }
}

void printPlan(const LoadedScene& scene, const pipeline::Configuration& configuration) {
  std::printf("passes for %s with %s (%s):\n", scene.name.c_str(), configuration.algorithm->name.c_str(),
              configuration.knobs.described().c_str());
  for (const pipeline::PlannedPass& pass : pipeline::plan(*scene.prepared, configuration)) {
    std::printf("  %-5s %-28s %s\n", pass.runs ? "run" : "skip", pass.pass.c_str(), pass.reason.c_str());
    for (const pipeline::PlannedPass& work : pass.work)
      std::printf("  %-5s   %-26s %s\n", pass.runs && work.runs ? "run" : "skip", work.pass.c_str(), work.reason.c_str());
  }
}

// The nearest and farthest view distances a frame shows (its finite depths), if any.
std::optional<std::pair<double, double>> visibleDepths(const Frame& frame, Stats& stats) {
  double nearest = std::numeric_limits<double>::infinity(), farthest = 0;
  for (const float d : frame.distances(&stats))
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

// When the z-buffer's format could not order some fragments: a short note, and with
// `advise` (--stats, --explain) one line of advice instead: how many, and the format that
// resolves the finest separation at the farthest visible depth, if finer. Ties are
// common (faces that touch, coplanar decals) and drawing order settles them the same way
// every time, so by default they get a note, not a warning that reads as a failure.
void reportDepthTies(std::int64_t ties, DepthFormat current, const CameraTransform& camera, double farthest, bool advise) {
  const std::string formatName = depthFormatName(current);
  if (!advise) {
    std::fprintf(stderr, "hsr: note: %lld depth ties (fragments at one %s depth, ordered by drawing order); --stats says more\n",
                 static_cast<long long>(ties), formatName.c_str());
    return;
  }
  const auto& names = depthFormatNames();
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
  for (const std::string& decision : pipeline::decisionsTaken(stats)) std::printf("  %s\n", decision.c_str());
  std::printf("time per pass (%.1f ms in all):\n", seconds * 1e3);
  for (const pipeline::PassTime& pass : pipeline::passTimes(stats))
    std::printf("  %-14s %8.2f ms\n", pass.pass.c_str(), pass.seconds * 1e3);
}

// The folder --steps names: made if absent (its parent must exist), and removed again if
// the command fails before its steps are written; its writer takes the steps as they are
// recorded; a previous run's frames beyond this run's count are removed once this run's
// are in place, so the folder holds one run.
class StepsFolder {
 public:
  explicit StepsFolder(const std::filesystem::path& folder) : folder_(folder), writer_(folder) {
    std::error_code error;
    if (std::filesystem::is_directory(folder_, error)) return;
    if (std::filesystem::exists(folder_, error)) throw InputError("--steps " + folder_.string() + ": exists and is not a folder");
    const std::filesystem::path parent = folder_.has_parent_path() ? folder_.parent_path() : ".";
    if (!std::filesystem::is_directory(parent, error))
      throw InputError("--steps " + folder_.string() + ": the folder it would go in (" + parent.string() + ") does not exist");
    if (!std::filesystem::create_directory(folder_, error))
      throw InputError("--steps " + folder_.string() + ": cannot make the folder: " + error.message());
    made_ = true;
  }
  StepsFolder(const StepsFolder&) = delete;
  StepsFolder& operator=(const StepsFolder&) = delete;
  ~StepsFolder() {
    std::error_code error;
    if (made_ && !written_) std::filesystem::remove_all(folder_, error);
  }

  StepsWriter& writer() { return writer_; }

  void finish(const std::string& title, const PixelQuestion& question) {
    writer_.finish(title, question);
    written_ = true;
    std::error_code error;
    for (std::size_t stale = writer_.count();; ++stale)
      if (!std::filesystem::remove(folder_ / stepPictureName(stale), error)) break;
  }

 private:
  std::filesystem::path folder_;
  StepsWriter writer_;
  bool made_ = false, written_ = false;
};

// The scene and the options that configure its render, as they were given (unquoted):
// what hsr render and hsr why share.
std::string configuredWords(const ConfiguredScene& options) {
  std::string words = options.scene + " --algo " + options.algorithm;
  if (!options.variant.empty()) words += " --variant " + options.variant;
  if (!options.depthFormat.empty()) words += " --depth-format " + options.depthFormat;
  for (const std::string& knob : options.knobs) words += " --knob " + knob;
  if (!options.cull.empty()) words += " --cull " + options.cull;
  if (!options.size.empty()) words += " --size " + options.size;
  return words;
}

// The steps page's title: the command that records the same steps again.
std::string stepsTitle(const RenderOptions& options) {
  return "hsr render " + configuredWords(options) + (options.lineStyle.empty() ? "" : " --line-style " + options.lineStyle) +
         (options.every > 0 ? " --every " + std::to_string(options.every) : "") + " -o " + options.output + " --steps " + options.steps;
}

// What a click on a step's pixel asks (the page adds --pixel and --step): hsr why on the
// same render, for an algorithm that answers why at a pixel, as README's commands run it
// from the suite's folder.
PixelQuestion stepsQuestion(const RenderOptions& options, const AlgorithmEntry& algorithm, const PreparedScene& scene) {
  if (!algorithm.answersWhy) return {};
  return {"./build/hsr why " + configuredWords(options) + (options.every > 0 ? " --every " + std::to_string(options.every) : ""), scene.width(),
          scene.height()};
}

}  // namespace

pipeline::Configuration configurationOf(const ConfiguredScene& options) {
  const AlgorithmEntry& algorithm = findAlgorithm(options.algorithm);
  KnobSettings settings;
  if (!options.variant.empty()) settings.emplace_back("variant", options.variant);
  if (!options.depthFormat.empty()) settings.emplace_back("depth-format", options.depthFormat);
  for (const std::string& knob : options.knobs) settings.push_back(parseKnobSetting(knob, "--knob"));
  pipeline::Configuration configuration = pipeline::configurationOf(algorithm, settings);
  configuration.culling = pipeline::cullingOf(options.cull, algorithm);
  return configuration;
}

int render(const RenderOptions& options) {
  const pipeline::Configuration configuration = configurationOf(options);
  const AlgorithmEntry& algorithm = *configuration.algorithm;

  const bool lines = algorithm.kind == AlgorithmKind::line;
  const std::filesystem::path output = options.output;
  const LineStyle style = lineStyleOf(options.lineStyle, lines);
  const bool polygonSvg = output.extension() == ".svg" && algorithm.drawsPolygons;
  if (output.extension() == ".svg" && !lines && !polygonSvg)
    throw InputError("-o " + options.output + ": SVG is for line drawings and visible polygons, and " + algorithm.name +
                     " draws pixels; expected a .png file");
  if (lines && (!options.depth.empty() || !options.ids.empty()))
    throw InputError(std::string(options.depth.empty() ? "--ids" : "--depth") + ": " + algorithm.name +
                     " draws lines, which have no depth or id image");

  const std::filesystem::path depthFile = options.depth;
  if (!options.depth.empty() && depthFile.extension() != ".exr" && depthFile.extension() != ".pfm")
    throw InputError("--depth " + options.depth + ": expected a file name ending in .exr (OpenEXR) or .pfm (a portable float map)");

  if (!lines && !options.segments.empty())
    throw InputError("--segments " + options.segments + ": " + algorithm.name + " draws pixels; segments come from a line algorithm");

  if (options.every > 0 && options.steps.empty()) throw InputError("--every " + std::to_string(options.every) + ": applies only with --steps DIR");
  std::optional<StepsFolder> stepsFolder;
  if (!options.steps.empty()) stepsFolder.emplace(options.steps);

  const LoadedScene scene = studies::loadPrepared(options.scene, options.size);
  pipeline::checkRenders(configuration, scene.name, *scene.prepared);
  if (options.explain) printPlan(scene, configuration);
  std::optional<StepRecorder> steps;
  if (stepsFolder) steps.emplace(std::size_t(options.every), [&](const Step& step) { stepsFolder->writer().add(step); });
  const auto start = std::chrono::steady_clock::now();
  Stats stats;
  pipeline::Rendered rendered;
  double seconds = 0;
  OutputFiles outputs;
  try {
    rendered = pipeline::render(*scene.prepared, configuration, options.threads, stats, nullptr, steps ? &*steps : nullptr);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (lines && output.extension() == ".svg") outputs.addText(output, lineSetSvg(rendered.drawing, style, edgeNamesOf(*scene.prepared)));
    else if (polygonSvg) outputs.addText(output, visiblePolygonsSvg(rendered.polygons, rendered.frame));
    else if (lines && style != LineStyle::visible) outputs.addColorPng(output, lineSetFrame(rendered.drawing, style));
    else outputs.addColorPng(output, rendered.frame);
    if (!options.depth.empty()) {
      const PixelBuffer<float>& distances = rendered.frame.distances(&stats);  // decoded here, where it is counted
      if (depthFile.extension() == ".pfm") outputs.addText(depthFile, pfmBytes(rendered.frame.width, rendered.frame.height, distances));
      else outputs.addDepthExr(depthFile, rendered.frame);
    }
    if (!options.ids.empty()) outputs.addIdsPng(options.ids, rendered.frame);
    if (!options.segments.empty()) outputs.addText(options.segments, visibleSegmentsText(rendered.drawing));
    if (!options.triangles.empty()) outputs.addText(options.triangles, triangleFileText(*scene.prepared));
  } catch (const std::bad_alloc&) {
    throw InputError(pipeline::outOfMemory(scene.prepared->width(), scene.prepared->height(), algorithm.name));
  }
  outputs.commit();
  const Frame& frame = rendered.frame;
  if (stepsFolder) {
    const Frame shown = lines && style != LineStyle::visible ? lineSetFrame(rendered.drawing, style) : frame;
    pipeline::recordFinishedStep(*steps, shown, lines);
    stepsFolder->finish(stepsTitle(options), stepsQuestion(options, algorithm, *scene.prepared));
  }
  // Why the image or drawing may be wrong somewhere, as the algorithm says.
  const std::string& partial = lines ? rendered.drawing.partial : frame.partial;
  if (!partial.empty()) std::fprintf(stderr, "hsr: warning: the %s is partial: %s\n", lines ? "drawing" : "image", partial.c_str());
  // The visible depths read the distances, which the z-buffer then decodes: only for the
  // depth ties' warning, and for --explain's resolutions after what the render decided.
  if (stats.counter(kDepthTiesCounter) > 0 && algorithm.depthFormat && !lines)
    if (const auto depths = visibleDepths(frame, stats))
      reportDepthTies(stats.counter(kDepthTiesCounter), algorithm.depthFormat(configuration.knobs), scene.prepared->camera(),
                      depths->second, options.stats || options.explain);
  if (options.stats) {
    // Asked for here, not counted by any pass: the pixels a surface shows (for depth
    // complexity, fragments per covered pixel).
    if (!lines) stats.add("covered pixels", std::count_if(frame.ids.begin(), frame.ids.end(), [](std::uint32_t id) { return id != 0; }));
    std::printf("%s", stats.report().c_str());
  }
  if (options.explain) {
    printDecisions(stats, seconds);
    if (const auto depths = lines ? std::nullopt : visibleDepths(frame, stats)) printDepthResolutions(scene.prepared->camera(), *depths);
  }
  return 0;
}

int list() {
  std::printf("algorithms:\n");
  for (const auto& algorithm : algorithms()) {
    std::printf("  %-12s %-9s %s\n", algorithm.name.c_str(), algorithmKindName(algorithm.kind), algorithm.summary.c_str());
    printKnobs(algorithm.knobs, "--knob ");
  }
  std::printf("culling stages (hsr render --cull STAGE[:VARIANT][:KNOB=VALUE...],...; before %s):\n", pipeline::cullableAlgorithms().c_str());
  for (const auto& stage : culling::stages()) {
    std::printf("  %-12s %s\n", stage.name.c_str(), stage.summary.c_str());
    const KnobSpec& variants = stage.variantKnob();
    for (std::size_t v = 0; v < variants.choices.size(); ++v)
      std::printf("    %s:%-16s %s%s\n", stage.name.c_str(), variants.choices[v].c_str(), variants.choiceHelp[v].c_str(),
                  variants.choices[v] == variants.defaultValue ? " (default)" : "");
    printKnobs({stage.knobs.begin() + 1, stage.knobs.end()}, ":");
  }
  std::printf("effects (a scene's effects list: one shading, then any of the others):\n");
  for (const EffectName& effect : effectNames()) std::printf("  %-12s %s\n", effect.name, effect.summary);
  std::printf("scenes (in %s):\n", HSR_SCENES_DIR);
  for (const auto& scene : studies::shippedScenes()) std::printf("  %s\n", scene.string().c_str());
  return 0;
}

}  // namespace hsr::cli
