// occlusion-queries (README "Occlusion queries"): the survey's walkthrough experiment.
// Four levels of different depth complexity, each walked along a camera path; nine
// culling methods draw every position on a simulated GPU (algorithms/culling/occlusion/simulated_gpu.hpp),
// so that the methods that cull on the CPU (depth map, HZB, previous frame) and those
// that ask the GPU (the query strategies) are timed on one timeline: the frame ends when
// both the CPU and the GPU have finished. A method without queries culls on the CPU,
// then issues a draw per object it kept.
//
// The path is cut into segments of kSegmentFrames positions, each walked from a cold
// start (no memory, a fresh GPU), so that segments are independent: --shard K/N walks
// segments K, K + N, ... and writes their per-frame rows; --merge joins the rows of
// several shard folders and writes the table and plots a single run would have.
//
// Per frame and method: the frame's time and the CPU's wait, triangles drawn, queries
// issued and wasted (answered visible), and against the exact reference: objects late
// (seen, not drawn, and not drawn since they came into view) and false culls (seen, not
// drawn, though drawn earlier in the same spell of being seen: popping out).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "algorithms/culling/culling.hpp"
#include "algorithms/culling/occlusion/simulated_gpu.hpp"
#include "algorithms/registry.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/util/error.hpp"
#include "studies/common.hpp"
#include "studies/gpu_walk.hpp"
#include "studies/interrupt.hpp"
#include "studies/plot.hpp"
#include "studies/results.hpp"
#include "studies/studies.hpp"

namespace hsr::studies {
namespace {

constexpr int kSegmentFrames = 50;
constexpr int kDefaultPositions = 2000;  // the survey walked 2,216
const char* const kFramesFile = "occlusion_queries_frames.csv";

struct Level {
  std::string name, file, description;
};
const std::vector<Level> kLevels = {{"city", "city_walk", "city streets at eye height"},
                                    {"corridors", "corridors", "a corridor level at eye height"},
                                    {"castle", "castle", "a castle from a third-person camera"},
                                    {"map", "strategy_map", "a strategy map from above"}};

const std::vector<Method> kMethods = {{"none", ""},
                                      {"frustum", "frustum"},
                                      {"depth-map", "frustum,occlusion"},
                                      {"hzb", "frustum,occlusion:pyramid=on"},
                                      {"previous-frame", "frustum,occlusion:previous-frame"},
                                      {"stop-and-wait", "frustum,occlusion:queries:stop-and-wait"},
                                      {"delayed", "frustum,occlusion:queries:delayed"},
                                      {"chc", "frustum,occlusion:queries:chc"},
                                      {"chcpp", "frustum,occlusion:queries:chcpp"}};

// Position `f` of `frames` on a level's path. The city walks its streets (the square
// loop of occlusion-walkthrough); the other levels orbit their camera's target once.
Camera pathCamera(const Level& level, const Camera& base, int f, int frames) {
  if (level.file == "city_walk") {
    const dvec2 corners[4] = {{-40, 40}, {-40, -40}, {40, -40}, {40, 40}};
    const double along = 4.0 * f / frames;
    const int leg = std::min(3, int(along));
    const dvec2 from = corners[leg], to = corners[(leg + 1) % 4];
    const dvec2 position = from + (along - leg) * (to - from), heading = glm::normalize(to - from);
    Camera camera = base;
    camera.eye = dvec3(position.x, 1.7, position.y);
    camera.target = camera.eye + dvec3(heading.x, 0, heading.y);
    return camera;
  }
  Camera camera = base;
  const dmat4 turn = rotate(dmat4(1), 2 * glm::pi<double>() * f / frames, dvec3(0, 1, 0));
  camera.eye = base.target + dvec3(turn * dvec4(base.eye - base.target, 0));
  return camera;
}

// The segments of the walk, in order: (level, first position).
std::vector<std::pair<std::size_t, int>> segmentsOf(int positionsPerLevel) {
  std::vector<std::pair<std::size_t, int>> segments;
  for (std::size_t level = 0; level < kLevels.size(); ++level)
    for (int first = 0; first < positionsPerLevel; first += kSegmentFrames) segments.emplace_back(level, first);
  return segments;
}

std::vector<CsvRow> csvRows(const std::vector<FrameRow>& rows) {
  std::vector<CsvRow> csv;
  for (const FrameRow& r : rows)
    csv.push_back({{"level", r.level}, {"segment", std::to_string(r.segment)}, {"frame", std::to_string(r.frame)}, {"method", r.method},
                   {"frame_ms", formatted(r.ms, "%.6g")}, {"waiting_ms", formatted(r.waitingMs, "%.6g")},
                   {"triangles", std::to_string(r.triangles)}, {"queries", std::to_string(r.queries)},
                   {"multiqueries", std::to_string(r.multiqueries)}, {"wasted_queries", std::to_string(r.wasted)}, {"objects_late", std::to_string(r.late)},
                   {"false_culls", std::to_string(r.falseCulls)}});
  return csv;
}

// The per-frame rows of a shard folder, as its CSV has them.
std::vector<FrameRow> readFrames(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / kFramesFile;
  std::ifstream in(file);
  if (!in) throw InputError("--merge " + folder.string() + ": no " + kFramesFile + " in it; expected a folder a --shard run wrote");
  std::string line;
  std::getline(in, line);
  const std::string written = csvOf(csvRows({FrameRow{}}));  // the header as this study writes it
  const std::string header = written.substr(0, written.find('\n'));
  if (line != header) throw InputError("--merge " + file.string() + ": line 1 is not the header this study writes; expected " + header);
  std::vector<FrameRow> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    std::vector<std::string> fields;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    FrameRow row;
    try {
      if (fields.size() != 12) throw std::invalid_argument("fields");
      row.level = fields[0], row.segment = std::stoi(fields[1]), row.frame = std::stoi(fields[2]), row.method = fields[3];
      row.ms = std::stod(fields[4]), row.waitingMs = std::stod(fields[5]);
      row.triangles = std::stoll(fields[6]), row.queries = std::stoll(fields[7]), row.multiqueries = std::stoll(fields[8]);
      row.wasted = std::stoll(fields[9]), row.late = std::stoll(fields[10]), row.falseCulls = std::stoll(fields[11]);
    } catch (const std::exception&) {
      throw InputError("--merge " + file.string() + ":" + std::to_string(number) + ": not a row of 12 numbers and names; expected " + header);
    }
    rows.push_back(row);
  }
  return rows;
}

// The frame time along each level's walk, a panel per level and a line per method.
// `frames` are in the walk's order: position by position, the methods in kMethods' order.
std::string perFramePlot(const std::vector<FrameRow>& frames, const std::vector<double>& shown) {
  std::string data, plots;
  for (std::size_t l = 0; l < kLevels.size(); ++l) {
    data += "$level" + std::to_string(l) + " << EOD\n";
    for (std::size_t r = 0; r < frames.size(); ++r) {
      if (frames[r].level != kLevels[l].name) continue;
      if (frames[r].method == kMethods.front().name) {  // a new position: a new row
        if (data.back() != '\n') data += '\n';
        data += std::to_string(frames[r].frame);
      }
      data += ' ';
      data += formatted(frames[r].ms, "%.5g");
    }
    data += "\nEOD\n";
    plots += "set title '" + kLevels[l].name + " (" + kLevels[l].description + ")'\nplot ";
    for (std::size_t m = 0; m < kMethods.size(); ++m)
      plots += std::string(m ? ", " : "") + "$level" + std::to_string(l) + " using 1:" + std::to_string(m + 2) + " with lines lw 0.8 title '" +
               kMethods[m].name + "'";
    plots += "\n";
  }
  return data + "set multiplot layout 2,2 title 'Occlusion queries: frame time along each walk'\nset xlabel 'position'\nset ylabel 'ms'\n" +
         timeAxis('y', shown, false) + "set grid\nset key top left font ',7' maxrows 3\nset linetype 9 lc rgb '#8c564b'\n" + plots +
         "unset multiplot\n";
}

// The table (level x method): frame time's mean, variance and 5% extremes (the 5th and
// 95th percentiles), and the means and totals of the rest; then the files: the frames in
// the order of the walk (segment, position, method), whatever order they were measured
// or merged in, the table, and with `plot` its plot.
void writeResults(std::vector<FrameRow> frames, const std::filesystem::path& folder, bool plot) {
  const auto methodIndex = [](const std::string& name) {
    return std::find_if(kMethods.begin(), kMethods.end(), [&](const Method& m) { return m.name == name; }) - kMethods.begin();
  };
  std::stable_sort(frames.begin(), frames.end(), [&](const FrameRow& a, const FrameRow& b) {
    return std::tuple(a.segment, a.frame, methodIndex(a.method)) < std::tuple(b.segment, b.frame, methodIndex(b.method));
  });
  std::vector<CsvRow> summary;
  std::string json = "{\n  \"study\": \"occlusion-queries\",\n  \"rows\": [\n";
  std::string table = "$table << EOD\n";
  std::printf("\n  %-10s %-15s %9s %11s %8s %8s %11s %9s %8s %11s %7s %7s\n", "level", "method", "mean ms", "variance", "p5 ms",
              "p95 ms", "waiting ms", "triangles", "queries", "late frames", "late", "false");
  for (const Level& level : kLevels) {
    table += level.name;
    for (const Method& method : kMethods) {
      std::vector<double> ms;
      double waiting = 0, triangles = 0, queries = 0, wasted = 0;
      std::int64_t lateFrames = 0, late = 0, falseCulls = 0;
      for (const FrameRow& r : frames)
        if (r.level == level.name && r.method == method.name) {
          ms.push_back(r.ms), waiting += r.waitingMs, triangles += double(r.triangles), queries += double(r.queries);
          wasted += double(r.wasted), lateFrames += r.late > 0, late += r.late, falseCulls += r.falseCulls;
        }
      if (ms.empty()) {
        table += " ?";
        continue;
      }
      const double n = double(ms.size());
      const auto [mean, variance, p5, p95] = spreadOf(ms);
      std::printf("  %-10s %-15s %9.3f %11.4g %8.3f %8.3f %11.3f %9.0f %8.1f %11lld %7lld %7lld\n", level.name.c_str(), method.name.c_str(),
                  mean, variance, p5, p95, waiting / n, triangles / n, queries / n, static_cast<long long>(lateFrames),
                  static_cast<long long>(late), static_cast<long long>(falseCulls));
      const CsvRow row = {{"level", level.name}, {"method", method.name}, {"frames", std::to_string(ms.size())},
                          {"frame_ms_mean", formatted(mean, "%.5g")}, {"frame_ms_variance", formatted(variance, "%.5g")},
                          {"frame_ms_p5", formatted(p5, "%.5g")}, {"frame_ms_p95", formatted(p95, "%.5g")},
                          {"waiting_ms_mean", formatted(waiting / n, "%.5g")}, {"triangles_mean", formatted(triangles / n, "%.1f")},
                          {"queries_mean", formatted(queries / n, "%.2f")}, {"wasted_queries_mean", formatted(wasted / n, "%.2f")},
                          {"late_frames", std::to_string(lateFrames)}, {"objects_late", std::to_string(late)},
                          {"false_culls", std::to_string(falseCulls)}};
      summary.push_back(row);
      json += std::string(summary.size() > 1 ? ",\n" : "") + "    " + jsonObjectOf(row, 2);
      for (const double value : {mean, p5, p95}) {
        table += ' ';
        table += formatted(value, "%.5g");
      }
    }
    table += "\n";
  }
  json += "\n  ]\n}\n";
  OutputFiles files;
  files.addText(folder / kFramesFile, csvOf(csvRows(frames)));
  files.addText(folder / "occlusion_queries.csv", csvOf(summary));
  files.addText(folder / "occlusion_queries.json", json);
  if (plot) {
    std::vector<std::string> titles;
    for (const Method& method : kMethods) titles.push_back(method.name);
    std::vector<double> shown;
    for (const FrameRow& r : frames) shown.push_back(r.ms);
    addPlot(files, folder, "occlusion_queries", levelTimesPlot("Occlusion queries", table, titles, shown));
    addPlot(files, folder, "occlusion_queries_frames", perFramePlot(frames, shown));
  }
  files.commit();
  std::printf("wrote %s/{%s,occlusion_queries.csv,occlusion_queries.json%s}\n", folder.string().c_str(), kFramesFile,
              plot ? ",occlusion_queries{,_frames}.{png,svg,gp}" : "");
}

// "K/N" with 1 <= K <= N <= 10000.
std::pair<int, int> parseShard(const std::string& text) {
  int k = 0, n = 0;
  char slash = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &k, &slash, &n, &extra) != 3 || slash != '/' || n < 1 || n > 10000 || k < 1 || k > n)
    throw InputError("--shard " + text + ": expected K/N, this run's share K of N shards, 1 <= K <= N <= 10000");
  return {k, n};
}

}  // namespace

void checkOcclusionQueriesOptions(const StudyOptions& options) {
  if (!options.merge.empty() && !options.shard.empty()) throw InputError("--merge: a merge walks nothing; --shard is for the runs it joins");
  if (!options.shard.empty()) parseShard(options.shard);
  for (const std::string& shard : options.merge) readFrames(shard);
}

int occlusionQueriesStudy(const StudyOptions& options, const std::filesystem::path& folder) {
  if (!options.merge.empty()) {
    std::vector<FrameRow> frames;
    for (const std::string& shard : options.merge) {
      const std::vector<FrameRow> part = readFrames(shard);
      frames.insert(frames.end(), part.begin(), part.end());
    }
    std::printf("occlusion queries: %zu frame rows merged from %zu shard folders\n", frames.size(), options.merge.size());
    writeResults(std::move(frames), folder, true);
    return 0;
  }
  const auto [shard, shards] = options.shard.empty() ? std::pair(1, 1) : parseShard(options.shard);
  const int positions = options.frames > 0 ? options.frames : kDefaultPositions;
  const int perLevel = std::max(1, positions / int(kLevels.size()));
  const std::vector<std::pair<std::size_t, int>> segments = segmentsOf(perLevel);
  std::vector<std::size_t> mine;
  for (std::size_t s = std::size_t(shard - 1); s < segments.size(); s += std::size_t(shards)) mine.push_back(s);

  std::vector<LoadedScene> scenes;
  for (const Level& level : kLevels)
    scenes.push_back(loadPrepared((std::filesystem::path(HSR_SCENES_DIR) / "study" / (level.file + ".toml")).string(), options.size));
  std::printf("occlusion queries: %d positions per level in segments of %d from a cold start, shard %d of %d (%zu of %zu segments), "
              "%zu methods, %d thread(s); every position checked against the exact reference\n",
              perLevel, kSegmentFrames, shard, shards, mine.size(), segments.size(), kMethods.size(), options.threads);

  std::vector<FrameRow> frames;
  Progress progress(mine.size());
  const InterruptibleRun interruptible;  // stops after the segment in progress
  std::size_t done = 0;
  for (const std::size_t s : mine) {
    if (InterruptibleRun::requested()) break;
    const auto [levelIndex, first] = segments[s];
    const Level& level = kLevels[levelIndex];
    Scene& world = *scenes[levelIndex].scene;
    const PreparedScene& scene = *scenes[levelIndex].prepared;
    const Camera base = world.camera;
    std::vector<MethodWalk> walks(kMethods.size());
    for (std::size_t m = 0; m < kMethods.size(); ++m) {
      if (!kMethods[m].cull.empty()) walks[m].pipeline = culling::parsePipeline(kMethods[m].cull, "study");
    }
    std::vector<std::uint8_t> seenBefore(scene.instances().size(), 0);
    for (int f = first; f < std::min(perLevel, first + kSegmentFrames); ++f) {
      world.camera = pathCamera(level, base, f, perLevel);
      for (FrameRow& row : walkPosition(scene, level.name, kMethods, walks, seenBefore, f, options.threads)) {
        row.segment = int(s);
        frames.push_back(row);
      }
    }
    world.camera = base;
    std::printf("  %s, positions %d-%d: walked\n", level.name.c_str(), first, std::min(perLevel, first + kSegmentFrames) - 1);
    std::fflush(stdout);
    progress.update(++done, level.name);
  }
  const bool complete = !InterruptibleRun::requested();
  if (!complete) reportInterrupted(done, mine.size(), "segments");
  // A shard's plot would show part of the walk: the merge draws it.
  writeResults(std::move(frames), folder, complete && shards == 1);
  return complete ? 0 : kInterruptedExit;
}

}  // namespace hsr::studies
