// hsr study culling-combos: which combinations of culling stages pay for themselves.
//
// The experiment (after the published one the README cites): four scenes, from one
// object to four 100k-triangle dragons; every object turning about its own vertical
// axis at 60 degrees per second; a whole turn rendered frame by frame under eight
// pipelines, from no culling and no depth test to backface + z-buffer + frustum. A
// frame is the visibility pass (culling, the geometry stage, the rasterization into a
// depth buffer, or in submission order without one); what every frame needs anyway
// (the world-space vertices of the turned objects, their bounds) is prepared before the
// clock starts, as a renderer would have it from the previous frame's update.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <cstdio>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "algorithms/culling/culling.hpp"
#include "algorithms/registry.hpp"
#include "algorithms/zbuffer/zbuffer.hpp"
#include "pipeline/pipeline.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/util/error.hpp"
#include "studies/common.hpp"
#include "studies/interrupt.hpp"
#include "studies/plot.hpp"
#include "studies/results.hpp"
#include "studies/studies.hpp"

namespace hsr::studies {
namespace {

struct Mode {
  std::string name;
  std::string cull;  // the culling pipeline (algorithms/culling), "" for none
  bool depthTest;    // false: drawn in submission order, the last triangle at a pixel wins
};

// The six pipelines of the experiment, frustum culling in its two variants. In the
// combinations the per-object test runs first: it is the cheapest per triangle removed.
const std::vector<Mode>& modes() {
  static const std::vector<Mode> list = {
      {"none", "", false},
      {"backface", "backface", false},
      {"z-buffer", "", true},
      {"frustum (triangle)", "frustum:triangle", false},
      {"frustum (sphere)", "frustum:sphere", false},
      {"backface + z-buffer", "backface", true},
      {"backface + z-buffer + frustum (triangle)", "frustum:triangle,backface", true},
      {"backface + z-buffer + frustum (sphere)", "frustum:sphere,backface", true},
  };
  return list;
}

const std::vector<std::string> kStudyScenes = {"cube", "counters", "trees", "dragons"};
constexpr double kDegreesPerSecond = 60;

// One mode's measurements over the frames of one scene.
struct ModeResult {
  std::vector<double> seconds;
  double trianglesIn = 0, rasterized = 0, vertices = 0, fragments = 0;  // summed over frames
  double cullingSeconds = 0, frustumSeconds = 0;                          // in the culling stages (all; frustum), summed
  double errorSum = 0;
  int errorFrames = 0;
  Visibility visibility;  // reused from frame to frame: the last one rendered
};

struct FrameTimes {
  double mean, best, worst;  // milliseconds; best and worst: the mean of the fastest and slowest 5% of frames
};

FrameTimes frameTimes(std::vector<double> seconds) {
  std::sort(seconds.begin(), seconds.end());
  const std::size_t tail = std::max<std::size_t>(1, seconds.size() / 20);
  const auto mean = [](auto begin, auto end) { return 1e3 * std::accumulate(begin, end, 0.0) / double(end - begin); };
  return {mean(seconds.begin(), seconds.end()), mean(seconds.begin(), seconds.begin() + std::ptrdiff_t(tail)),
          mean(seconds.end() - std::ptrdiff_t(tail), seconds.end())};
}

// A mode as the pipeline runs it: its culling stages, then the full-frame z-buffer
// (float32 depth), with or without its test; timed through the visibility pass.
pipeline::Configuration configurationOf(const Mode& mode) {
  pipeline::Configuration configuration =
      pipeline::configurationOf(zbuffer::entry, zbuffer::knobTable(), {.depthTest = mode.depthTest});
  if (!mode.cull.empty()) configuration.culling = culling::parsePipeline(mode.cull);
  return configuration;
}

struct SceneResult {
  std::string name;
  std::size_t objects = 0, triangles = 0;
  int width = 0, height = 0;
  std::vector<ModeResult> modes;
  double meanMs(const std::string& mode) const;
};

std::size_t modeIndex(const std::string& name) {
  const auto found = std::find_if(modes().begin(), modes().end(), [&](const Mode& mode) { return mode.name == name; });
  HSR_CHECK(found != modes().end());
  return std::size_t(found - modes().begin());
}

double SceneResult::meanMs(const std::string& mode) const { return frameTimes(modes[modeIndex(mode)].seconds).mean; }

SceneResult runScene(const std::string& name, const StudyOptions& options, Progress& progress, std::size_t& done) {
  const LoadedScene loaded = loadPrepared((std::filesystem::path(HSR_SCENES_DIR) / (name + ".toml")).string(), options.size);
  SceneResult result;
  result.name = name;
  result.objects = loaded.prepared->instances().size();
  result.triangles = loaded.prepared->triangleCount();
  result.width = loaded.prepared->width();
  result.height = loaded.prepared->height();
  result.modes.resize(modes().size());
  std::vector<pipeline::Configuration> configurations;
  for (const Mode& mode : modes()) configurations.push_back(configurationOf(mode));

  for (int f = 0; f < options.frames; ++f) {
    // Untimed: this frame's world, every object turned about its own vertical axis.
    const double degrees = 360.0 * f / options.frames;
    const dmat4 turn = rotate(dmat4(1.0), glm::radians(degrees), dvec3(0, 1, 0));
    PreparedScene prepared(*loaded.scene, {dmat4(1.0)}, turn);
    prepared.setSize(result.width, result.height);
    // The modes in a different order each frame, so that no mode always runs first
    // after the preparation (with cold caches) or last.
    for (std::size_t k = 0; k < modes().size(); ++k) {
      const std::size_t m = (k + std::size_t(f)) % modes().size();
      ModeResult& mode = result.modes[m];
      Stats stats;
      const auto start = std::chrono::steady_clock::now();
      pipeline::renderVisibility(prepared, configurations[m], options.threads, stats, mode.visibility);
      mode.seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      mode.trianglesIn += double(stats.counter("triangles in"));
      mode.rasterized += double(stats.counter("screen triangles"));
      mode.vertices += double(stats.counter("vertices transformed"));
      mode.fragments += double(stats.counter("fragments tested"));
      mode.cullingSeconds += stats.seconds("culling: backface") + stats.seconds("culling: frustum");
      mode.frustumSeconds += stats.seconds("culling: frustum");
    }
    // Every few frames, each mode's image against the exact reference.
    const bool errorFrame = options.errorFrames > 0 && (f * options.errorFrames) % options.frames < options.errorFrames;
    if (errorFrame) {
      Stats referenceStats;
      const ReferenceImage truth = traceReference(prepared, 0, referenceStats);
      for (ModeResult& mode : result.modes) {
        mode.errorSum += surfaceError(mode.visibility.frame, truth).pixelError;
        ++mode.errorFrames;
      }
    }
    progress.update(++done, name);
  }
  return result;
}

// The measured columns of one mode on one scene, shared by the CSV, the JSON and the table.
std::vector<std::pair<std::string, std::string>> fields(const SceneResult& scene, std::size_t m, const StudyOptions& options) {
  const ModeResult& mode = scene.modes[m];
  const double frames = double(mode.seconds.size());
  const FrameTimes times = frameTimes(mode.seconds);
  return {{"scene", scene.name},
          {"mode", modes()[m].name},
          {"culling", modes()[m].cull.empty() ? "none" : culling::describePipeline(culling::parsePipeline(modes()[m].cull))},
          {"depth_test", modes()[m].depthTest ? "on" : "off"},
          {"objects", std::to_string(scene.objects)},
          {"triangles", std::to_string(scene.triangles)},
          {"width", std::to_string(scene.width)},
          {"height", std::to_string(scene.height)},
          {"frames", std::to_string(mode.seconds.size())},
          {"threads", std::to_string(options.threads)},
          {"time_mean_ms", formatted(times.mean, "%.4f")},
          {"time_best5_ms", formatted(times.best, "%.4f")},
          {"time_worst5_ms", formatted(times.worst, "%.4f")},
          {"culling_ms", formatted(1e3 * mode.cullingSeconds / frames, "%.4f")},
          {"triangles_submitted", formatted(mode.trianglesIn / frames, "%.1f")},
          {"triangles_rasterized", formatted(mode.rasterized / frames, "%.1f")},
          {"vertices_transformed", formatted(mode.vertices / frames, "%.1f")},
          {"fragments", formatted(mode.fragments / frames, "%.1f")},
          {"pixel_error", mode.errorFrames ? formatted(mode.errorSum / mode.errorFrames, "%.6f") : ""},
          {"error_frames", std::to_string(mode.errorFrames)}};
}

// One CSV line: the names (header) or the values of the fields.
std::string csvLine(const std::vector<std::pair<std::string, std::string>>& columns, bool header) {
  std::string line;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i > 0) line += ',';
    line += header ? columns[i].first : csvField(columns[i].second);
  }
  return line + "\n";
}

std::string csv(const std::vector<SceneResult>& scenes, const StudyOptions& options) {
  std::string text = csvLine(fields(scenes.front(), 0, options), true);
  for (const SceneResult& scene : scenes)
    for (std::size_t m = 0; m < modes().size(); ++m) text += csvLine(fields(scene, m, options), false);
  return text;
}

std::string json(const std::vector<SceneResult>& scenes, const StudyOptions& options) {
  std::string text = "[\n";
  for (const SceneResult& scene : scenes)
    for (std::size_t m = 0; m < modes().size(); ++m) {
      std::string object;
      for (const auto& [name, value] : fields(scene, m, options)) {
        const bool numeric = name != "scene" && name != "mode" && name != "culling" && name != "depth_test";
        object += (object.empty() ? "" : ", ") + jsonString(name) + ": " + (!numeric ? jsonString(value) : value.empty() ? "null" : value);
      }
      text += std::string(text.size() > 2 ? ",\n" : "") + "  {" + object + "}";
    }
  return text + "\n]\n";
}

std::string table(const SceneResult& scene, const StudyOptions& options) {
  char line[256];
  std::snprintf(line, sizeof line, "\n%s: %zu objects, %zu triangles, %dx%d, %d frames, %d thread(s)\n", scene.name.c_str(),
                scene.objects, scene.triangles, scene.width, scene.height, options.frames, options.threads);
  std::string text = line;
  std::snprintf(line, sizeof line, "  %-42s %9s %9s %9s %8s %12s %11s\n", "mode", "mean ms", "best 5%", "worst 5%", "/ z-buf",
                "rasterized", "pixel error");
  text += line;
  const double zbuffer = scene.meanMs("z-buffer");
  for (std::size_t m = 0; m < modes().size(); ++m) {
    const FrameTimes times = frameTimes(scene.modes[m].seconds);
    const ModeResult& mode = scene.modes[m];
    const std::string error = mode.errorFrames ? formatted(100 * mode.errorSum / mode.errorFrames, "%.3f%%") : "-";
    std::snprintf(line, sizeof line, "  %-42s %9.3f %9.3f %9.3f %8.2f %12.0f %11s\n", modes()[m].name.c_str(), times.mean,
                  times.best, times.worst, times.mean / zbuffer, mode.rasterized / double(mode.seconds.size()), error.c_str());
    text += line;
  }
  return text;
}

// One mode's frame time over another's, frame by frame (the same pose of the same
// scene, measured moments apart), as a median with its confidence interval: the poses
// make frame times vary far more than noise does, their ratios much less.
Interval pairedRatio(const SceneResult& scene, const std::string& mode, const std::string& over) {
  const std::vector<double>& numerator = scene.modes[modeIndex(mode)].seconds;
  const std::vector<double>& denominator = scene.modes[modeIndex(over)].seconds;
  std::vector<double> ratios;
  for (std::size_t f = 0; f < numerator.size(); ++f) ratios.push_back(numerator[f] / denominator[f]);
  return medianWithConfidence(ratios);
}

// "0.62 [0.60-0.64]"
std::string describe(const Interval& ratio) {
  return formatted(ratio.median, "%.2f") + " [" + formatted(ratio.low, "%.2f") + "-" + formatted(ratio.high, "%.2f") + "]";
}

// The published conclusions, each checked on the scenes that were run. A claim that one
// mode is faster holds when the confidence interval of the paired ratio lies on its
// side of 1, and is within noise when the interval straddles 1.
std::string conclusions(const std::vector<SceneResult>& scenes) {
  std::string text = "\nconclusions (frame-time ratios: median of the frames [95% confidence interval]):\n";
  const auto find = [&](const std::string& name) -> const SceneResult* {
    for (const SceneResult& scene : scenes)
      if (scene.name == name) return &scene;
    return nullptr;
  };
  // 1. Backface culling always helps: with and without the z-buffer.
  std::vector<Verdict> verdicts;
  std::string detail;
  for (const SceneResult& scene : scenes) {
    const Interval without = pairedRatio(scene, "backface", "none");
    const Interval with = pairedRatio(scene, "backface + z-buffer", "z-buffer");
    verdicts.push_back(below(without, 1));
    verdicts.push_back(below(with, 1));
    detail += " " + scene.name + " " + describe(without) + " / " + describe(with) + ";";
  }
  detail.pop_back();
  text += std::string("  backface culling always helps: ") + verdictText(allOf(verdicts)) +
          " (time with it / without, no depth test / z-buffer:" + detail + ")\n";
  // 2. Frustum culling costs more than it saves on the single cube, and saves most on dragons.
  const auto frustumRatio = [](const SceneResult& scene, const std::string& variant) {
    return pairedRatio(scene, "backface + z-buffer + frustum (" + variant + ")", "backface + z-buffer");
  };
  if (const SceneResult* cube = find("cube")) {
    // The cube never leaves the view, so a frustum test can only cost: held when it
    // removed no triangle while taking measurable time (the frame times themselves
    // differ by less than their noise here).
    const auto stage = [&](const std::string& variant) {
      const std::size_t with = modeIndex("backface + z-buffer + frustum (" + variant + ")"), without = modeIndex("backface + z-buffer");
      const bool removedNothing = cube->modes[with].trianglesIn == cube->modes[without].trianglesIn;
      return std::pair(removedNothing, 1e6 * cube->modes[with].frustumSeconds / double(cube->modes[with].seconds.size()));
    };
    const auto [sphereNothing, sphereMicroseconds] = stage("sphere");
    const auto [triangleNothing, triangleMicroseconds] = stage("triangle");
    text += std::string("  frustum culling costs more than it saves on the cube: ") +
            verdictText(sphereNothing && triangleNothing ? Verdict::held : Verdict::didNotHold) + " (it removed " +
            (sphereNothing && triangleNothing ? "nothing" : "some triangles") + "; the frustum stage took " +
            formatted(sphereMicroseconds, "%.1f") + " us per frame with the sphere test, " + formatted(triangleMicroseconds, "%.1f") +
            " us with the triangle test; frame time with / without frustum: sphere " + describe(frustumRatio(*cube, "sphere")) +
            ", triangle " + describe(frustumRatio(*cube, "triangle")) + ")\n";
  }
  if (const SceneResult* dragons = find("dragons"); dragons && scenes.size() > 1) {
    // Saves most: dragons' ratio below every other scene's, each pair judged on intervals.
    const Interval most = frustumRatio(*dragons, "sphere");
    verdicts.clear();
    detail.clear();
    for (const SceneResult& scene : scenes) {
      const Interval ratio = frustumRatio(scene, "sphere");
      if (&scene != dragons)
        verdicts.push_back(most.high < ratio.low ? Verdict::held : most.low > ratio.high ? Verdict::didNotHold : Verdict::withinNoise);
      detail += " " + scene.name + " " + describe(ratio) + ";";
    }
    detail.pop_back();
    text += std::string("  frustum culling saves most on dragons: ") + verdictText(allOf(verdicts)) +
            " (time with the sphere test / without:" + detail + ")\n";
  }
  // 3. Per-object spheres beat per-triangle tests wherever there is more than one object.
  verdicts.clear();
  detail.clear();
  for (const SceneResult& scene : scenes) {
    if (scene.objects < 2) continue;
    const Interval ratio = pairedRatio(scene, "backface + z-buffer + frustum (sphere)", "backface + z-buffer + frustum (triangle)");
    verdicts.push_back(below(ratio, 1));
    detail += " " + scene.name + " " + describe(ratio) + ";";
  }
  if (!detail.empty()) {
    detail.pop_back();
    text += std::string("  per-object spheres beat per-triangle tests on scenes of several objects: ") + verdictText(allOf(verdicts)) +
            " (sphere time / triangle time:" + detail + ")\n";
  }
  return text;
}

// Mean frame time per scene (clusters) and mode (bars), log scale, with the best and
// worst 5% as the error bar.
std::string plot(const std::vector<SceneResult>& scenes) {
  std::string data = "$frames << EOD\n";
  for (const SceneResult& scene : scenes) {
    data += scene.name;
    for (const ModeResult& mode : scene.modes) {
      const FrameTimes times = frameTimes(mode.seconds);
      for (const double value : {times.mean, times.best, times.worst}) {
        data += ' ';
        data += formatted(value, "%.6g");
      }
    }
    data += "\n";
  }
  data += "EOD\n";
  std::vector<std::string> titles;
  for (const Mode& mode : modes()) titles.push_back(mode.name);
  std::vector<double> shown;
  for (const SceneResult& scene : scenes)
    for (const ModeResult& mode : scene.modes) {
      const FrameTimes times = frameTimes(mode.seconds);
      shown.insert(shown.end(), {times.best, times.worst});
    }
  return data +
         "set title 'Culling combinations: mean frame time over a full turn (bars: best and worst 5%)'\n"
         "set ylabel 'visibility pass per frame (ms)'\n" + timeAxis('y', shown, true) + "set grid ytics\n"
         "set style data histogram\nset style histogram errorbars gap 1.5 lw 1\nset style fill solid 0.85 border -1\n"
         "set boxwidth 0.9\nset key below horizontal maxcols 2 font ',10'\nset xtics nomirror\nplot " +
         histogramBars("$frames", titles, 3) + "\n";
}

}  // namespace

std::filesystem::path studyFolder(const StudyOptions& options) {
  return options.out.empty() ? std::filesystem::path("out/study") / options.name : std::filesystem::path(options.out);
}

int study(const StudyOptions& options) {
  const std::vector<std::string> occlusionStudies = {"occlusion-walkthrough", "occlusion-queries", "hzb-resolution", "occluder-fraction"};
  const std::vector<std::string> effectsStudies = {"effects", "shadow-map"};
  const auto among = [&](const std::vector<std::string>& names) {
    return std::find(names.begin(), names.end(), options.name) != names.end();
  };
  if (options.name != "culling-combos" && options.name != "indoor" && !among(occlusionStudies) && !among(effectsStudies))
    throw InputError("study " + options.name +
                     ": unknown study; expected culling-combos, occlusion-walkthrough, occlusion-queries, hzb-resolution, occluder-fraction, indoor, "
                     "effects or shadow-map");
  if (!options.size.empty()) parseSize(options.size, "--size");
  if (options.name != "occlusion-queries" && (!options.shard.empty() || !options.merge.empty()))
    throw InputError(std::string(options.shard.empty() ? "--merge" : "--shard") + ": study " + options.name +
                     " is not sharded; expected study occlusion-queries");
  if (options.name == "occlusion-queries") checkOcclusionQueriesOptions(options);
  const std::filesystem::path folder = studyFolder(options);
  if (options.name != "culling-combos") {
    if (!options.scenes.empty()) throw InputError("--scenes: study " + options.name + " has its own scenes; --scenes is for culling-combos");
    makeFolder(folder, "--out");
    if (options.name == "indoor") return indoorStudy(options, folder);
    return among(occlusionStudies) ? occlusionStudy(options, folder) : effectsStudy(options, folder);
  }
  StudyOptions resolved = options;
  resolved.frames = options.frames > 0 ? options.frames : 360;
  const int frames = resolved.frames;
  std::vector<std::string> scenes = kStudyScenes;
  if (!resolved.scenes.empty()) {
    scenes = splitList(resolved.scenes, "--scenes");
    for (const std::string& scene : scenes)
      if (std::find(kStudyScenes.begin(), kStudyScenes.end(), scene) == kStudyScenes.end())
        throw InputError("--scenes " + resolved.scenes + ": '" + scene + "' is not one of the study's scenes; expected some of cube, counters, trees, dragons");
  }
  if (resolved.errorFrames > frames)
    throw InputError("--error-frames " + std::to_string(resolved.errorFrames) + ": more than the " + std::to_string(frames) +
                     " frames; expected at most --frames");
  makeFolder(folder, "--out");

  std::printf("culling combinations: every object turning at %g degrees/s, %d frames over a full turn (one every %.4g ms of "
              "animation)\n",
              kDegreesPerSecond, resolved.frames, 1e3 * 360 / kDegreesPerSecond / resolved.frames);
  Progress progress(scenes.size() * std::size_t(resolved.frames));
  std::size_t done = 0;
  std::vector<SceneResult> results;
  const InterruptibleRun interruptible;  // stops after the scene in progress
  for (const std::string& scene : scenes) {
    if (InterruptibleRun::requested()) break;
    results.push_back(runScene(scene, resolved, progress, done));
    std::printf("%s", table(results.back(), resolved).c_str());
    std::fflush(stdout);
  }
  const bool cutShort = InterruptibleRun::requested();
  if (cutShort) reportInterrupted(results.size(), scenes.size(), "scenes");
  if (results.empty()) return kInterruptedExit;
  if (!cutShort) std::printf("%s", conclusions(results).c_str());

  OutputFiles files;
  files.addText(folder / "culling_combos.csv", csv(results, resolved));
  files.addText(folder / "culling_combos.json", json(results, resolved));
  if (!cutShort) addPlot(files, folder, "culling_combos", plot(results));  // a plot of part of a study misleads
  files.commit();
  std::printf("wrote %s/culling_combos.{csv,json%s}\n", folder.string().c_str(), cutShort ? "" : ",png,svg,gp");
  return cutShort ? kInterruptedExit : 0;
}

}  // namespace hsr::studies
