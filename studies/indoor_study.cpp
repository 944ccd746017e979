// indoor (README "Cells, portals and potentially visible sets"): indoor visibility as
// the classic engines did it, against the methods that need no cells. Three levels
// divided into cells (scenes/study/indoor.toml, a hall with twelve rooms; corridors.toml,
// a grid of corridors; castle.toml, walked inside its walls), each along a closed path
// at eye height; at every position nine
// methods draw on a simulated GPU (gpu_walk.hpp), as occlusion-queries times them, and
// the exact reference says which objects are seen:
//   frustum                      the baseline: no cells
//   portals rect, polygon        Luebke and Georges' traversal, each frame
//   pvs sampled 1, 8, 64         sets built once from 1, 8 or 64 eye points a cell
//   pvs conservative             sets built once from portal chains
//   depth-map, chc               occlusion culling without cells
// Per frame: time, objects and triangles drawn, objects seen and not drawn. Per PVS
// method: the build's time and the sets' mean size (built before the walk, untimed in
// its frames). And a top-down map of the indoor level from one eye: its cells, its
// portals, and what each method keeps.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "algorithms/culling/cells/portals.hpp"
#include "algorithms/culling/cells/pvs.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "studies/common.hpp"
#include "studies/gpu_walk.hpp"
#include "studies/interrupt.hpp"
#include "studies/plot.hpp"
#include "studies/studies.hpp"

namespace hsr::studies {
namespace {

constexpr int kDefaultFrames = 300;  // per level

struct Level {
  std::string name, file, description;
  std::vector<dvec2> path;  // (x, z) corners of a closed walk
  double eyeHeight;
};
const std::vector<Level> kLevels = {
    // Down the hall, up through a door, west through the five doors of the north rooms,
    // back to the hall, across to the south rooms, east through theirs, and back.
    {"indoor", "indoor", "a hall with twelve rooms", {{-28, 0}, {25, 0}, {25, 6}, {-25, 6}, {-25, 0}, {-25, -6}, {25, -6}, {25, 0}}, 1.6},
    // East along a corridor through the gaps in its cross walls, round the wall's end,
    // west along the next one.
    {"corridors", "corridors", "a grid of corridors", {{-42, 4}, {42, 4}, {42, 12}, {-42, 12}}, 1.6},
    // Round the inside of the castle: along the north wall through the gaps at the
    // inner walls' ends, down the east courtyard, back through the southern gaps, up
    // the west courtyard.
    {"castle", "castle", "the courtyards of a castle", {{-20, 28.5}, {20, 28.5}, {20, -28.5}, {-20, -28.5}}, 1.7}};

const std::vector<Method> kMethods = {{"frustum", "frustum"},
                                      {"portals rect", "frustum,portals"},
                                      {"portals polygon", "frustum,portals:narrowing=polygon"},
                                      {"pvs sampled 1", "frustum,pvs:build=sampled:samples=1:resolution=32"},
                                      {"pvs sampled 8", "frustum,pvs:build=sampled:samples=8:resolution=32"},
                                      {"pvs sampled 64", "frustum,pvs:build=sampled:samples=64:resolution=32"},
                                      {"pvs conservative", "frustum,pvs"},
                                      {"depth-map", "frustum,occlusion"},
                                      {"chc", "frustum,occlusion:queries:chc"}};

// Position f of `frames` on a level's closed path, at even steps along it, the eye at
// the level's eye height and looking along the path; over the last 1.5 units of a leg
// the heading swings to the next.
Camera alongPath(const Camera& base, const Level& level, int f, int frames) {
  const std::vector<dvec2>& corners = level.path;
  std::vector<double> lengths;
  double total = 0;
  for (std::size_t i = 0; i < corners.size(); ++i) total += lengths.emplace_back(glm::distance(corners[i], corners[(i + 1) % corners.size()]));
  double along = total * f / frames;
  std::size_t leg = 0;
  while (leg + 1 < corners.size() && along > lengths[leg]) along -= lengths[leg++];
  const dvec2 from = corners[leg], to = corners[(leg + 1) % corners.size()], next = corners[(leg + 2) % corners.size()];
  const double swing = std::clamp((along - (lengths[leg] - 1.5)) / 1.5, 0.0, 1.0);
  const dvec2 heading = glm::normalize((1 - swing) * glm::normalize(to - from) + swing * glm::normalize(next - to));
  const dvec2 position = from + std::min(along, lengths[leg]) / lengths[leg] * (to - from);
  Camera camera = base;
  camera.eye = dvec3(position.x, level.eyeHeight, position.y);
  camera.target = camera.eye + dvec3(heading.x, 0, heading.y);
  return camera;
}

// What a PVS method's sets cost and hold, from the untimed frame that built them.
struct BuildRow {
  double seconds = 0, meanSet = 0;
};

// The top-down map of a level from its camera: cells outlined, portals drawn thick,
// every object's footprint coloured by what keeps it, the eye and its view.
std::string mapPlot(const PreparedScene& scene, const std::vector<std::uint8_t>& keptByPortals, const std::vector<std::uint8_t>& inPvs,
                    const std::vector<std::uint8_t>& seen) {
  const Scene& level = scene.scene();
  std::string objects;
  Aabb bounds;
  for (const Cell& cell : level.cells) bounds.grow(cell.from), bounds.grow(cell.to);
  int index = 1;
  const auto rectangle = [&](double x0, double z0, double x1, double z1, const std::string& style) {
    objects += "set object " + std::to_string(index++) + " rect from " + formatted(x0, "%.4g") + "," + formatted(z0, "%.4g") + " to " +
               formatted(x1, "%.4g") + "," + formatted(z1, "%.4g") + " " + style + "\n";
  };
  for (std::size_t i = 0; i < scene.instances().size(); ++i) {
    const Aabb& box = scene.instances()[i].box;
    // The floor and the ceiling span the whole map: left out, so it shows what stands on it.
    if (box.hi.x - box.lo.x > 0.9 * (bounds.hi.x - bounds.lo.x) && box.hi.z - box.lo.z > 0.9 * (bounds.hi.z - bounds.lo.z)) continue;
    const std::string colour = seen[i] ? "'#d62728'" : keptByPortals[i] ? "'#1f77b4'" : inPvs[i] ? "'#9ecae1'" : "'#d9d9d9'";
    rectangle(box.lo.x, box.lo.z, box.hi.x, box.hi.z, "fc rgb " + colour + " fs solid 1.0 noborder front");
  }
  for (const Cell& cell : level.cells) rectangle(cell.from.x, cell.from.z, cell.to.x, cell.to.z, "fs empty border rgb '#555555' back");
  std::string lines;
  for (const Portal& portal : level.portals) {
    Aabb extent;
    for (const dvec3& corner : portal.polygon) extent.grow(corner);
    if (portal.axis == 1) continue;  // a floor or ceiling opening: no line on a map from above
    lines += "set arrow from " + formatted(extent.lo.x, "%.4g") + "," + formatted(extent.lo.z, "%.4g") + " to " +
             formatted(extent.hi.x, "%.4g") + "," + formatted(extent.hi.z, "%.4g") + " nohead lw 3 lc rgb '#2ca02c' front\n";
  }
  const CameraTransform camera = scene.camera();
  const dvec3 eye = camera.camera().eye;
  for (const double x : {0.0, double(scene.width())}) {
    const dvec3 direction = glm::normalize(camera.rayThroughPixel(x, scene.height() / 2.0).direction);
    const dvec3 reach = eye + 14.0 * direction;
    lines += "set arrow from " + formatted(eye.x, "%.4g") + "," + formatted(eye.z, "%.4g") + " to " + formatted(reach.x, "%.4g") + "," +
             formatted(reach.z, "%.4g") + " nohead dt 2 lc rgb 'black' front\n";
  }
  return "$eye << EOD\n" + formatted(eye.x, "%.4g") + " " + formatted(eye.z, "%.4g") + "\nEOD\n" + objects + lines + "set size ratio -1\nset xrange [" + formatted(bounds.lo.x - 1, "%.4g") + ":" + formatted(bounds.hi.x + 1, "%.4g") +
         "]\nset yrange [" + formatted(bounds.hi.z + 1, "%.4g") + ":" + formatted(bounds.lo.z - 1, "%.4g") +
         "]\nset xlabel 'x'\nset ylabel 'z'\nset key below horizontal\n"
         "set title \"Cells (grey outlines) and portals (green) from above. Objects seen by the eye (red); not seen, but kept by\\n"
         "portals:polygon (blue); kept only by the eye cell's conservative PVS (light blue); culled by both (grey)\" font ',10'\n"
         "plot $eye using 1:2 with points pt 7 ps 1.5 lc rgb 'black' title 'eye'\n";
}

// The map of the indoor level from one eye (in the hall, looking across it into the
// doors of the north rooms), with what the reference sees and what portals and the PVS keep.
void writeMap(const std::filesystem::path& folder, OutputFiles& files, Scene& world, const PreparedScene& scene) {
  const Camera base = world.camera;
  world.camera.eye = dvec3(-12, 1.6, -1.2), world.camera.target = dvec3(-2, 1.6, 4);
  Stats stats;
  const culling::cells::CellMap map(scene, "study indoor");
  const VisibleSet all = VisibleSet::everything(scene);
  const VisibleSet byPortals = culling::portals::cull(scene, map, scene.camera(), {0, culling::portals::Narrowing::polygon}, all, stats);
  const culling::pvs::VisibleSets sets = culling::pvs::build(scene, map, {}, 0, stats);
  const VisibleSet byPvs = culling::pvs::cull(scene, map, sets, scene.camera(), all, stats);
  const auto objectsOf = [&](const VisibleSet& set) {
    std::vector<std::uint8_t> flags(scene.triangleCount(), 0);
    for (const std::uint32_t t : set.triangles) flags[t] = 1;
    return objectsWithAny(scene, flags);
  };
  const std::vector<std::uint8_t> seen = objectsWithAny(scene, visibleTriangles(traceReference(scene, 0, stats), scene.triangleCount()));
  addPlot(files, folder, "indoor_map", mapPlot(scene, objectsOf(byPortals), objectsOf(byPvs), seen));
  world.camera = base;
}

}  // namespace

int indoorStudy(const StudyOptions& options, const std::filesystem::path& folder) {
  const int frames = options.frames > 0 ? options.frames : kDefaultFrames;
  std::vector<LoadedScene> scenes;
  for (const Level& level : kLevels)
    scenes.push_back(loadPrepared((std::filesystem::path(HSR_SCENES_DIR) / "study" / (level.file + ".toml")).string(), options.size));
  std::printf("indoor: %d positions per level along a closed walk, %zu methods on a simulated GPU, %d thread(s); every position "
              "checked against the exact reference\n",
              frames, kMethods.size(), options.threads);
  std::vector<FrameRow> rows;
  std::vector<std::vector<BuildRow>> builds(kLevels.size(), std::vector<BuildRow>(kMethods.size()));
  const InterruptibleRun interruptible;  // stops after the level in progress
  std::size_t levelsWalked = 0;
  for (std::size_t l = 0; l < kLevels.size() && !InterruptibleRun::requested(); ++l) {
    const Level& level = kLevels[l];
    Scene& world = *scenes[l].scene;
    const PreparedScene& scene = *scenes[l].prepared;
    const Camera base = world.camera;
    std::vector<MethodWalk> walks(kMethods.size());
    for (std::size_t m = 0; m < kMethods.size(); ++m) {
      walks[m].pipeline = culling::parsePipeline(kMethods[m].cull, "study indoor");
      // A PVS is built before the walk (its frames look it up): built here, untimed,
      // into the walk's memory, at the first position (or read from its cache).
      if (kMethods[m].cull.find("pvs") == std::string::npos) continue;
      // The table's figures from a build of its own, so that a cache beside the scene
      // does not stand in for the build it measures.
      Stats stats;
      const culling::pvs::VisibleSets sets =
          culling::pvs::build(scene, culling::cells::CellMap(scene, "study indoor"), walks[m].pipeline.back().knobs.as<culling::pvs::Knobs>(),
                              options.threads, stats);
      builds[l][m] = {sets.seconds, double(stats.counter("pvs: objects in all sets")) / double(world.cells.size())};
      world.camera = alongPath(base, level, 0, frames);
      const culling::PreviousFrame previous{world.camera, nullptr, &walks[m].memory, nullptr};
      culling::runPipeline(scene, walks[m].pipeline, options.threads, stats, &previous);
      std::printf("  %s, %s: sets built in %.3f s, %.1f objects a cell on average of %zu\n", level.name.c_str(), kMethods[m].name.c_str(),
                  builds[l][m].seconds, builds[l][m].meanSet, scene.instances().size());
    }
    std::vector<std::uint8_t> seenBefore(scene.instances().size(), 0);
    Progress progress{std::size_t(frames)};
    for (int f = 0; f < frames; ++f) {
      world.camera = alongPath(base, level, f, frames);
      const std::vector<FrameRow> position = walkPosition(scene, level.name, kMethods, walks, seenBefore, f, options.threads);
      rows.insert(rows.end(), position.begin(), position.end());
      progress.update(std::size_t(f + 1), level.name);
    }
    world.camera = base;
    ++levelsWalked;
  }

  // The table: per level and method, the frame time's spread and the means and totals.
  std::vector<CsvRow> summary;
  std::string json = "{\n  \"study\": \"indoor\",\n  \"rows\": [\n";
  std::string table = "$table << EOD\n";
  std::printf("\n  %-10s %-17s %8s %8s %8s %8s %10s %14s %9s %9s %9s\n", "level", "method", "mean ms", "p5 ms", "p95 ms", "objects",
              "triangles", "missing frames", "missing", "build s", "set size");
  for (std::size_t l = 0; l < levelsWalked; ++l) {
    table += kLevels[l].name;
    for (std::size_t m = 0; m < kMethods.size(); ++m) {
      std::vector<double> ms;
      double objects = 0, triangles = 0;
      std::int64_t missingFrames = 0, missing = 0;
      for (const FrameRow& r : rows)
        if (r.level == kLevels[l].name && r.method == kMethods[m].name) {
          ms.push_back(r.ms), objects += double(r.objects), triangles += double(r.triangles);
          missingFrames += r.late + r.falseCulls > 0, missing += r.late + r.falseCulls;
        }
      const double n = double(ms.size());
      const Spread time = spreadOf(ms);
      const BuildRow& build = builds[l][m];
      std::printf("  %-10s %-17s %8.3f %8.3f %8.3f %8.1f %10.0f %14lld %9lld %9.3f %9.1f\n", kLevels[l].name.c_str(), kMethods[m].name.c_str(),
                  time.mean, time.p5, time.p95, objects / n, triangles / n, static_cast<long long>(missingFrames),
                  static_cast<long long>(missing), build.seconds, build.meanSet);
      const CsvRow row = {{"level", kLevels[l].name}, {"method", kMethods[m].name}, {"culling", kMethods[m].cull},
                          {"frames", std::to_string(ms.size())}, {"frame_ms_mean", formatted(time.mean, "%.5g")},
                          {"frame_ms_p5", formatted(time.p5, "%.5g")}, {"frame_ms_p95", formatted(time.p95, "%.5g")},
                          {"objects_drawn_mean", formatted(objects / n, "%.2f")}, {"triangles_drawn_mean", formatted(triangles / n, "%.1f")},
                          {"frames_missing_an_object", std::to_string(missingFrames)}, {"objects_missing", std::to_string(missing)},
                          {"pvs_build_s", formatted(build.seconds, "%.5g")}, {"pvs_mean_set_objects", formatted(build.meanSet, "%.2f")}};
      summary.push_back(row);
      json += std::string(summary.size() > 1 ? ",\n" : "") + "    " + jsonObjectOf(row, 3);
      table += ' ' + formatted(time.mean, "%.5g") + ' ' + formatted(time.p5, "%.5g") + ' ' + formatted(time.p95, "%.5g");
    }
    table += "\n";
  }
  json += "\n  ]\n}\n";
  std::vector<CsvRow> frameRows;
  for (const FrameRow& r : rows)
    frameRows.push_back({{"level", r.level}, {"frame", std::to_string(r.frame)}, {"method", r.method}, {"frame_ms", formatted(r.ms, "%.6g")},
                         {"objects_drawn", std::to_string(r.objects)}, {"triangles_drawn", std::to_string(r.triangles)},
                         {"objects_missing", std::to_string(r.late + r.falseCulls)}});
  OutputFiles files;
  files.addText(folder / "indoor_frames.csv", csvOf(frameRows));
  files.addText(folder / "indoor.csv", csvOf(summary));
  files.addText(folder / "indoor.json", json);
  const bool complete = levelsWalked == kLevels.size();
  if (complete) {
    std::vector<std::string> titles;
    for (const Method& method : kMethods) titles.push_back(method.name);
    std::vector<double> shown;
    for (const FrameRow& r : rows) shown.push_back(r.ms);
    addPlot(files, folder, "indoor", levelTimesPlot("Indoor", table, titles, shown));
    // Objects drawn along each walk, a panel per level.
    std::string data, plots;
    for (std::size_t l = 0; l < kLevels.size(); ++l) {
      data += "$level" + std::to_string(l) + " << EOD\n";
      for (int f = 0; f < frames; ++f) {
        data += std::to_string(f);
        for (const Method& method : kMethods)
          for (const FrameRow& r : rows)
            if (r.level == kLevels[l].name && r.frame == f && r.method == method.name) data += ' ' + std::to_string(r.objects);
        data += "\n";
      }
      data += "EOD\n";
      plots += "set title '" + kLevels[l].name + " (" + kLevels[l].description + ")'\nplot ";
      for (std::size_t m = 0; m < kMethods.size(); ++m)
        plots += std::string(m ? ", " : "") + "$level" + std::to_string(l) + " using 1:" + std::to_string(m + 2) + " with lines lw 0.8 title '" +
                 kMethods[m].name + "'";
      plots += "\n";
    }
    addPlot(files, folder, "indoor_frames",
            data + "set multiplot layout 3,1 title 'Indoor: objects drawn along each walk'\nset xlabel 'position'\nset ylabel 'objects'\n"
                   "set logscale y\nset grid\nset key top left font ',7' maxrows 3\nset linetype 9 lc rgb '#8c564b'\n" +
                plots + "unset multiplot\n");
    writeMap(folder, files, *scenes.front().scene, *scenes.front().prepared);
  }
  files.commit();
  std::printf("wrote %s/{indoor_frames.csv,indoor.csv,indoor.json%s}\n", folder.string().c_str(),
              complete ? ",indoor{,_frames,_map}.{png,svg,gp}" : "");
  if (!complete) reportInterrupted(levelsWalked, kLevels.size(), "levels");
  return complete ? 0 : kInterruptedExit;
}

}  // namespace hsr::studies
