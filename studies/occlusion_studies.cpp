// The occlusion studies (README "Occlusion culling"):
//   occlusion-walkthrough  a city walked along its streets: per-frame time of four
//                          pipelines, and the frames where a visible object was culled
//   hzb-resolution         walls with doors just behind them: depth-map size, rule and
//                          pyramid against doors wrongly culled and time; and the time
//                          per occludee query from 10 to 1,000,000 queries
//   occluder-fraction      three kinds of level, each with all, or 5, 10, 20% of the
//                          objects as occluders: triangles drawn, culling and render time
// A frame is timed as culling study times it (study.cpp): the culling stages, the
// geometry stage and the z-buffer's float depth raster.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "algorithms/culling/occlusion/occlusion.hpp"
#include "algorithms/registry.hpp"
#include "algorithms/zbuffer/zbuffer.hpp"
#include "pipeline/pipeline.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "studies/common.hpp"
#include "studies/interrupt.hpp"
#include "studies/plot.hpp"
#include "studies/results.hpp"
#include "studies/studies.hpp"

namespace hsr::studies {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The z-buffer (float32, full frame) after the culling stages of `cull`.
pipeline::Configuration zbufferAfter(const std::string& cull) {
  pipeline::Configuration configuration = pipeline::configurationOf(zbuffer::entry, zbuffer::knobTable());
  if (!cull.empty()) configuration.culling = culling::parsePipeline(cull);
  return configuration;
}

// One frame of one configuration: the pipeline's culling and visibility passes, timed apart.
struct FrameResult {
  double cullSeconds = 0, renderSeconds = 0;
  VisibleSet kept;
};
FrameResult renderFrame(const PreparedScene& scene, const pipeline::Configuration& configuration, const culling::PreviousFrame* previous,
                        int threads, Visibility& visibility) {
  FrameResult result;
  Stats stats;
  result.kept = pipeline::renderVisibility(scene, configuration, threads, stats, visibility, previous);
  for (const pipeline::PassTime& pass : pipeline::passTimes(stats)) (pass.pass == "culling" ? result.cullSeconds : result.renderSeconds) += pass.seconds;
  return result;
}

// The objects the reference shows of which `kept` has no triangle.
std::int64_t objectsFalselyCulled(const PreparedScene& scene, const ReferenceImage& truth, const VisibleSet& kept) {
  std::vector<std::uint8_t> keptTriangles(scene.triangleCount(), 0);
  for (const std::uint32_t t : kept.triangles) keptTriangles[t] = 1;
  return cullingError(objectsWithAny(scene, keptTriangles), objectsWithAny(scene, visibleTriangles(truth, scene.triangleCount())))
      .falseCulls;
}

// ---------------------------------------------------------------------------------
// occlusion-walkthrough

struct WalkMode {
  std::string name, cull;
};

// Around the middle block of streets: a square loop along x, z = +-40, the eye 1.7 up and
// looking along the street ahead, turning at each corner within a few frames.
Camera walkCamera(const Camera& base, int frame, int frames) {
  const dvec2 corners[4] = {{-40, 40}, {-40, -40}, {40, -40}, {40, 40}};
  const double along = 4.0 * frame / frames;
  const int leg = std::min(3, int(along));
  const double t = along - leg;
  const dvec2 from = corners[leg], to = corners[(leg + 1) % 4], next = corners[(leg + 2) % 4];
  const dvec2 position = from + t * (to - from);
  // The heading swings to the next street over the last 5% of a leg.
  const double swing = std::clamp((t - 0.95) / 0.05, 0.0, 1.0);
  const dvec2 heading = glm::normalize((1 - swing) * glm::normalize(to - from) + swing * glm::normalize(next - to));
  Camera camera = base;
  camera.eye = dvec3(position.x, 1.7, position.y);
  camera.target = camera.eye + dvec3(heading.x, 0, heading.y);
  return camera;
}

int walkthrough(const StudyOptions& options, const std::filesystem::path& folder) {
  const int frames = options.frames > 0 ? options.frames : 500;
  LoadedScene loaded = loadPrepared((std::filesystem::path(HSR_SCENES_DIR) / "study" / "city_walk.toml").string(), options.size);
  PreparedScene& scene = *loaded.prepared;
  Scene& world = *loaded.scene;
  const Camera base = world.camera;
  const std::vector<WalkMode> modes = {{"none", ""}, {"frustum", "frustum"}, {"frustum + occlusion", "frustum,occlusion"},
                                       {"frustum + previous frame", "frustum,occlusion:previous-frame"}};
  struct Result {
    std::vector<double> ms;
    int falseCullFrames = 0;
    std::int64_t falselyCulled = 0;
    double drawn = 0;
    Visibility visibility;
    Frame last;
    Camera lastCamera;
    bool hasLast = false;
  };
  std::vector<Result> results(modes.size());
  std::vector<pipeline::Configuration> configurations;
  for (const WalkMode& mode : modes) configurations.push_back(zbufferAfter(mode.cull));
  for (Result& result : results) result.visibility.frame = result.last = Frame(scene.width(), scene.height());
  std::printf("occlusion walkthrough: %zu objects, %zu triangles, %dx%d, %d frames around the streets, %d thread(s); "
              "every frame checked against the exact reference\n",
              scene.instances().size(), scene.triangleCount(), scene.width(), scene.height(), frames, options.threads);
  Progress progress{std::size_t(frames)};
  for (int f = 0; f < frames; ++f) {
    world.camera = walkCamera(base, f, frames);
    Stats referenceStats;
    const ReferenceImage truth = traceReference(scene, 0, referenceStats);
    for (std::size_t k = 0; k < modes.size(); ++k) {
      const std::size_t m = (k + std::size_t(f)) % modes.size();
      Result& result = results[m];
      const culling::PreviousFrame previous{result.lastCamera, &result.last};
      const FrameResult frame = renderFrame(scene, configurations[m], result.hasLast ? &previous : nullptr, options.threads, result.visibility);
      result.ms.push_back(1e3 * (frame.cullSeconds + frame.renderSeconds));
      result.drawn += double(frame.kept.triangles.size());
      const std::int64_t wrong = objectsFalselyCulled(scene, truth, frame.kept);
      result.falselyCulled += wrong;
      result.falseCullFrames += wrong > 0;
      std::swap(result.visibility.frame, result.last);
      result.last.distances();  // decoded untimed, as every mode once decoded in its pass: only the previous frame reads them
      result.lastCamera = world.camera, result.hasLast = true;
    }
    progress.update(std::size_t(f + 1), "walkthrough");
  }
  std::vector<CsvRow> rows;
  std::printf("\n  %-26s %9s %10s %9s %13s %16s %14s\n", "mode", "mean ms", "std dev ms", "/ none", "triangles", "false-cull frames",
              "objects late");
  const double noneMean = std::accumulate(results[0].ms.begin(), results[0].ms.end(), 0.0) / frames;
  for (std::size_t m = 0; m < modes.size(); ++m) {
    const Result& r = results[m];
    const double mean = std::accumulate(r.ms.begin(), r.ms.end(), 0.0) / frames;
    double variance = 0;
    for (const double ms : r.ms) variance += (ms - mean) * (ms - mean) / frames;
    std::printf("  %-26s %9.3f %10.3f %9.2f %13.0f %16d %14lld\n", modes[m].name.c_str(), mean, std::sqrt(variance), mean / noneMean,
                r.drawn / frames, r.falseCullFrames, static_cast<long long>(r.falselyCulled));
    rows.push_back({{"mode", modes[m].name}, {"culling", modes[m].cull.empty() ? "none" : modes[m].cull},
                    {"frames", std::to_string(frames)}, {"time_mean_ms", formatted(mean, "%.4f")},
                    {"time_stddev_ms", formatted(std::sqrt(variance), "%.4f")}, {"triangles_drawn", formatted(r.drawn / frames, "%.1f")},
                    {"false_cull_frames", std::to_string(r.falseCullFrames)},
                    {"objects_falsely_culled", std::to_string(r.falselyCulled)}});
  }
  // Per-frame time, one line per mode.
  std::string data = "$frames << EOD\n";
  for (int f = 0; f < frames; ++f) {
    data += std::to_string(f);
    for (const Result& r : results) {
      data += ' ';
      data += formatted(r.ms[std::size_t(f)], "%.5g");
    }
    data += "\n";
  }
  std::vector<double> shown;
  for (const Result& r : results) shown.insert(shown.end(), r.ms.begin(), r.ms.end());
  data += "EOD\nset title 'Occlusion walkthrough: visibility pass per frame'\nset xlabel 'frame'\nset ylabel 'ms'\n" +
          timeAxis('y', shown, false) + "set grid\nset key below horizontal\nplot ";
  for (std::size_t m = 0; m < modes.size(); ++m) {
    if (m > 0) data += ", ";
    data += "$frames using 1:" + std::to_string(m + 2) + " with lines title '" + modes[m].name + "'";
  }
  writeStudy(folder, "occlusion_walkthrough", csvOf(rows), data + "\n");
  return 0;
}

// ---------------------------------------------------------------------------------
// hzb-resolution

int hzbResolution(const StudyOptions& options, const std::filesystem::path& folder) {
  LoadedScene loaded = loadPrepared((std::filesystem::path(HSR_SCENES_DIR) / "study" / "walls_doors.toml").string(), options.size);
  const PreparedScene& scene = *loaded.prepared;
  Stats referenceStats;
  const ReferenceImage truth = traceReference(scene, 0, referenceStats);
  const int repeats = std::max(3, options.frames > 0 ? options.frames : 30);
  std::printf("hierarchical-Z resolution: walls with doors just behind them, %dx%d, %zu objects; each setting timed over %d "
              "runs, %d thread(s)\n\n  %-9s %-13s %-8s %12s %14s %14s\n",
              scene.width(), scene.height(), scene.instances().size(), repeats, options.threads, "map", "rule", "pyramid",
              "culled", "doors lost", "culling ms: median [min-max]");
  std::vector<CsvRow> rows;
  std::vector<std::pair<std::string, Timing>> measured;  // for the busy-machine warning
  std::string data = "$sizes << EOD\n";
  const std::vector<std::string> sizes = {"64x64", "128x128", "256x128", "256x256", "512x256"};
  const InterruptibleRun interruptible;
  for (const std::string& size : sizes) {
    if (InterruptibleRun::requested()) break;
    const std::string width = size.substr(0, size.find('x')), height = size.substr(size.find('x') + 1);
    data += size;
    for (const std::string rule : {"conservative", "center"})
      for (const std::string pyramid : {"off", "on"}) {
        if (InterruptibleRun::requested()) break;
        const culling::Pipeline pipeline = culling::parsePipeline("occlusion:map-width=" + width + ":map-height=" + height +
                                                                  ":raster=" + rule + ":pyramid=" + pyramid);
        std::vector<double> seconds;
        std::int64_t culled = 0;
        VisibleSet kept;
        for (int r = -1; r < repeats; ++r) {  // r = -1: a warm-up, untimed
          Stats stats;
          const auto start = Clock::now();
          kept = culling::runPipeline(scene, pipeline, options.threads, stats);
          if (r >= 0) seconds.push_back(since(start));
          culled = stats.counter("occlusion: occludees culled");
        }
        const Timing time = summarize(seconds);
        measured.emplace_back(size + " " + rule + " pyramid " + pyramid, time);
        const std::int64_t lost = objectsFalselyCulled(scene, truth, kept);
        std::printf("  %-9s %-13s %-8s %12lld %14lld %22s\n", size.c_str(), rule.c_str(), pyramid.c_str(),
                    static_cast<long long>(culled), static_cast<long long>(lost), formattedRange(time, 1e3, "%.3f").c_str());
        std::fflush(stdout);
        rows.push_back({{"map", size}, {"rule", rule}, {"pyramid", pyramid}, {"objects_culled", std::to_string(culled)},
                        {"visible_objects_culled", std::to_string(lost)}, {"culling_ms_median", formatted(time.median * 1e3, "%.4f")},
                        {"culling_ms_min", formatted(time.min * 1e3, "%.4f")}, {"culling_ms_max", formatted(time.max * 1e3, "%.4f")}});
        data += timingColumns(time, 1e3);
        data += ' ';
        data += std::to_string(lost);
      }
    data += "\n";
  }
  // Time per query, against the conservative 256x128 map of this view, for 10 to 10^6
  // random rectangles (each 1 to 40 texels a side).
  const CameraTransform& camera = scene.camera();
  const culling::occlusion::Knobs settings;
  const culling::occlusion::MapView view(camera, 256, 128);
  Stats stats;
  const culling::occlusion::DepthMap map = culling::occlusion::occluderDepthMap(
      scene, view, settings, culling::occlusion::chooseOccluders(scene, camera, settings, VisibleSet::everything(scene)), stats);
  const culling::occlusion::Pyramid pyramid(map);
  std::mt19937_64 random(1);
  constexpr int kQueryRuns = 5;
  std::printf("\n  %-10s %22s %22s   (ns per query: median [min-max] of %d runs)\n", "queries", "flat", "pyramid", kQueryRuns);
  data += "EOD\n$queries << EOD\n";
  for (std::int64_t count = 10; count <= 1000000; count *= 10) {
    if (InterruptibleRun::requested()) break;
    std::vector<culling::occlusion::BoxFootprint> boxes(static_cast<std::size_t>(count));
    for (auto& box : boxes) {
      box.x0 = int(random() % 256), box.y0 = int(random() % 128);
      box.x1 = std::min(256, box.x0 + 1 + int(random() % 40)), box.y1 = std::min(128, box.y0 + 1 + int(random() % 40));
      box.nearest = std::uniform_real_distribution<float>(-0.2f, 0)(random);
    }
    Timing perQuery[2];  // seconds per query
    std::int64_t hidden[2] = {0, 0};
    for (int usePyramid = 0; usePyramid < 2; ++usePyramid) {
      std::vector<double> seconds;
      for (int run = -1; run < kQueryRuns; ++run) {  // run = -1: a warm-up, untimed
        std::int64_t read = 0;
        hidden[usePyramid] = 0;
        const auto start = Clock::now();
        for (const auto& box : boxes) hidden[usePyramid] += usePyramid ? pyramid.hidden(box, read) : hiddenOnMap(map, box, read);
        if (run >= 0) seconds.push_back(since(start) / double(count));
      }
      perQuery[usePyramid] = summarize(seconds);
      measured.emplace_back(std::to_string(count) + (usePyramid ? " pyramid" : " flat") + " queries", perQuery[usePyramid]);
    }
    std::printf("  %-10lld %22s %22s   (hidden: %lld flat, %lld pyramid)\n", static_cast<long long>(count),
                formattedRange(perQuery[0], 1e9, "%.1f").c_str(), formattedRange(perQuery[1], 1e9, "%.1f").c_str(),
                static_cast<long long>(hidden[0]), static_cast<long long>(hidden[1]));
    std::fflush(stdout);
    // These rows time one query, in ns: "flat/pyramid".
    const auto both = [&](double Timing::*field) {
      return formatted(perQuery[0].*field * 1e9, "%.2f") + "/" + formatted(perQuery[1].*field * 1e9, "%.2f") + " ns";
    };
    rows.push_back({{"map", "256x128"}, {"rule", "conservative"}, {"pyramid", "queries=" + std::to_string(count)},
                    {"objects_culled", ""}, {"visible_objects_culled", ""}, {"culling_ms_median", both(&Timing::median)},
                    {"culling_ms_min", both(&Timing::min)}, {"culling_ms_max", both(&Timing::max)}});
    data += std::to_string(count);
    for (const Timing& time : perQuery)
      data += timingColumns(time, 1e9);
    data += "\n";
  }
  data += "EOD\nset multiplot layout 1,2\nset title 'Culling time by map size (median, bars: fastest to slowest)'\nset xlabel 'map (texels)'\nset ylabel 'ms'\n"
          "set style data yerrorlines\nset grid\nset key top left font ',9'\n"
          "plot $sizes using 0:2:3:4:xtic(1) title 'conservative', '' using 0:6:7:8 title 'conservative + pyramid', "
          "'' using 0:10:11:12 title 'center', '' using 0:14:15:16 title 'center + pyramid'\n"
          "set title 'Time per occludee query (256x128)'\nset logscale x\nset xlabel 'queries'\nset ylabel 'ns'\n"
          "plot $queries using 1:2:3:4 title 'flat', '' using 1:5:6:7 title 'pyramid'\nunset multiplot\n";
  if (!InterruptibleRun::requested()) warnIfBusy(measured, "--frames " + std::to_string(std::max(90, 3 * repeats)));
  return finishStudy(folder, "hzb_resolution", rows, sizes.size() * 4 + 6, data);
}

// ---------------------------------------------------------------------------------
// occluder-fraction

int occluderFraction(const StudyOptions& options, const std::filesystem::path& folder) {
  const std::vector<std::pair<std::string, std::string>> levels = {
      {"corridors", "a corridor level at eye height"}, {"castle", "a castle seen from a third-person camera"},
      {"strategy_map", "a strategy map seen from above"}};
  const std::vector<std::pair<std::string, std::string>> choices = {
      {"frustum only", "frustum"}, {"all", "frustum,occlusion"},
      {"volume 5%", "frustum,occlusion:occluders=volume:fraction=5%"}, {"volume 10%", "frustum,occlusion:occluders=volume"},
      {"volume 20%", "frustum,occlusion:occluders=volume:fraction=20%"},
      {"solid angle 5%", "frustum,occlusion:occluders=solid-angle:fraction=5%"},
      {"solid angle 10%", "frustum,occlusion:occluders=solid-angle"},
      {"solid angle 20%", "frustum,occlusion:occluders=solid-angle:fraction=20%"}};
  const int repeats = options.frames > 0 ? options.frames : 20;
  std::vector<CsvRow> rows;
  std::vector<std::pair<std::string, Timing>> measured;  // for the busy-machine warning
  std::string data = "$levels << EOD\n";
  const InterruptibleRun interruptible;
  for (const auto& [level, description] : levels) {
    if (InterruptibleRun::requested()) break;
    LoadedScene loaded = loadPrepared((std::filesystem::path(HSR_SCENES_DIR) / "study" / (level + ".toml")).string(), options.size);
    const PreparedScene& scene = *loaded.prepared;
    Stats referenceStats;
    const ReferenceImage truth = traceReference(scene, 0, referenceStats);
    std::printf("\n%s (%s): %zu objects, %zu triangles, %dx%d, %d frames, ms: median [min-max]\n  %-18s %10s %20s %20s %20s %12s\n",
                level.c_str(), description.c_str(), scene.instances().size(), scene.triangleCount(), scene.width(), scene.height(),
                repeats, "occluders", "drawn", "culling", "render", "total", "lost objects");
    data += level;
    Visibility visibility;
    for (const auto& [name, cull] : choices) {
      if (InterruptibleRun::requested()) break;
      const pipeline::Configuration configuration = zbufferAfter(cull);
      std::vector<double> cullSeconds, renderSeconds, totalSeconds;
      FrameResult result;
      for (int r = -1; r < repeats; ++r) {  // r = -1: a warm-up, untimed
        result = renderFrame(scene, configuration, nullptr, options.threads, visibility);
        if (r < 0) continue;
        cullSeconds.push_back(result.cullSeconds), renderSeconds.push_back(result.renderSeconds);
        totalSeconds.push_back(result.cullSeconds + result.renderSeconds);
      }
      const Timing culling = summarize(cullSeconds), render = summarize(renderSeconds), total = summarize(totalSeconds);
      measured.emplace_back(level + ", " + name, total);
      const std::int64_t lost = objectsFalselyCulled(scene, truth, result.kept);
      std::printf("  %-18s %10zu %20s %20s %20s %12lld\n", name.c_str(), result.kept.triangles.size(),
                  formattedRange(culling, 1e3, "%.3f").c_str(), formattedRange(render, 1e3, "%.3f").c_str(),
                  formattedRange(total, 1e3, "%.3f").c_str(), static_cast<long long>(lost));
      std::fflush(stdout);
      rows.push_back({{"level", level}, {"occluders", name}, {"culling", cull},
                      {"triangles_drawn", std::to_string(result.kept.triangles.size())},
                      {"culling_ms_median", formatted(culling.median * 1e3, "%.4f")},
                      {"render_ms_median", formatted(render.median * 1e3, "%.4f")},
                      {"total_ms_median", formatted(total.median * 1e3, "%.4f")}, {"total_ms_min", formatted(total.min * 1e3, "%.4f")},
                      {"total_ms_max", formatted(total.max * 1e3, "%.4f")}, {"visible_objects_culled", std::to_string(lost)}});
      data += timingColumns(total, 1e3);
    }
    data += "\n";
  }
  data += "EOD\nset title 'Occluder fraction: frame time (culling + depth pass, median; bars: fastest to slowest)'\nset xlabel 'level'\nset ylabel 'ms'\n"
          "set yrange [0:*]\nset style data histogram\nset style histogram errorbars gap 1.5 lw 1\nset style fill solid 0.85 border -1\nset boxwidth 0.9\n"
          "set grid ytics\nset key below horizontal maxcols 4 font ',9'\nplot ";
  std::vector<std::string> titles;
  for (const auto& choice : choices) titles.push_back(choice.first);
  data += histogramBars("$levels", titles, 3);
  if (!InterruptibleRun::requested()) warnIfBusy(measured, "--frames " + std::to_string(std::max(60, 3 * repeats)));
  return finishStudy(folder, "occluder_fraction", rows, levels.size() * choices.size(), data + "\n");
}

}  // namespace

int occlusionStudy(const StudyOptions& options, const std::filesystem::path& folder) {
  if (options.name == "occlusion-walkthrough") return walkthrough(options, folder);
  if (options.name == "occlusion-queries") return occlusionQueriesStudy(options, folder);
  if (options.name == "hzb-resolution") return hzbResolution(options, folder);
  return occluderFraction(options, folder);
}

}  // namespace hsr::studies
