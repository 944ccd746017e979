// What the walkthrough studies share (gpu_walk.hpp).
#include "studies/gpu_walk.hpp"

#include <algorithm>

#include "algorithms/registry.hpp"
#include "algorithms/zbuffer/zbuffer.hpp"
#include "pipeline/pipeline.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "studies/plot.hpp"

namespace hsr::studies {

FrameRow walkFrame(const PreparedScene& scene, const std::vector<std::uint8_t>& seen,
                   const std::vector<std::uint8_t>& seenBefore, MethodWalk& walk, int threads) {
  walk.gpu.beginFrame(scene.camera());
  const culling::PreviousFrame previous{walk.lastCamera, walk.hasLast ? &walk.last.frame : nullptr, &walk.memory, &walk.gpu};
  Stats stats;
  const VisibleSet kept = culling::runPipeline(scene, walk.pipeline, threads, stats, &previous);
  const std::vector<culling::TriangleRun> runs = culling::trianglesByInstance(scene, kept);
  if (!walk.lastStageIs("queries"))  // the query strategies drew as they went
    for (std::uint32_t object = 0; object < runs.size(); ++object)
      if (runs[object].end > runs[object].first)
        walk.gpu.draw(scene, object, {kept.triangles.data() + runs[object].first, runs[object].end - runs[object].first});
  const GpuFrameTimes times = walk.gpu.endFrame();
  if (walk.lastStageIs("previous-frame")) {
    // Untimed: the depth the next frame reprojects.
    Stats untimed;
    const pipeline::Configuration zbuffer = pipeline::configurationOf(zbuffer::entry, zbuffer::knobTable());
    walk.last.frame = Frame(scene.width(), scene.height());
    zbuffer.algorithm->visibility({scene, scene.camera(), &kept, threads, untimed}, zbuffer.knobs, walk.last);
    walk.last.frame.distances();  // what reprojecting reads, decoded here, untimed too
  }
  walk.lastCamera = scene.camera().camera(), walk.hasLast = true;

  FrameRow row;
  row.ms = 1e3 * times.frame, row.waitingMs = 1e3 * times.waiting;
  row.triangles = std::int64_t(kept.triangles.size());
  row.objects = std::count_if(runs.begin(), runs.end(), [](const culling::TriangleRun& run) { return run.end > run.first; });
  row.queries = stats.counter("queries: issued"), row.wasted = stats.counter("queries: answered visible");
  row.multiqueries = stats.counter("queries: multiqueries");
  walk.drawnInSpell.resize(seen.size(), 0);
  for (std::size_t object = 0; object < seen.size(); ++object) {
    const bool drawn = runs[object].end > runs[object].first;
    if (seen[object] && !seenBefore[object]) walk.drawnInSpell[object] = 0;  // a new spell in view
    if (seen[object] && !drawn) (walk.drawnInSpell[object] ? row.falseCulls : row.late) += 1;
    walk.drawnInSpell[object] = walk.drawnInSpell[object] || (seen[object] && drawn);
  }
  return row;
}

std::vector<FrameRow> walkPosition(const PreparedScene& scene, const std::string& level, const std::vector<Method>& methods,
                                   std::vector<MethodWalk>& walks, std::vector<std::uint8_t>& seenBefore, int position, int threads) {
  Stats referenceStats;
  const std::vector<std::uint8_t> seen =
      objectsWithAny(scene, visibleTriangles(traceReference(scene, threads, referenceStats), scene.triangleCount()));
  std::vector<FrameRow> rows;
  for (std::size_t k = 0; k < methods.size(); ++k) {
    const std::size_t m = (k + std::size_t(position)) % methods.size();
    FrameRow row = walkFrame(scene, seen, seenBefore, walks[m], threads);
    row.level = level, row.method = methods[m].name, row.frame = position;
    rows.push_back(row);
  }
  seenBefore = seen;
  return rows;
}

Spread spreadOf(std::vector<double> values) {
  const double n = double(values.size());
  Spread spread{0, 0, 0, 0};
  for (const double v : values) spread.mean += v / n;
  for (const double v : values) spread.variance += (v - spread.mean) * (v - spread.mean) / n;
  std::sort(values.begin(), values.end());
  spread.p5 = values[std::size_t(0.05 * (n - 1))], spread.p95 = values[std::size_t(0.95 * (n - 1))];
  return spread;
}

std::string levelTimesPlot(const std::string& study, const std::string& table, const std::vector<std::string>& methods,
                           const std::vector<double>& shown) {
  return table + "EOD\nset title '" + study + ": frame time per level (mean; bars: 5% to 95%)'\nset ylabel 'ms'\n" +
         timeAxis('y', shown, true) +
         "set style data histogram\nset style histogram errorbars gap 1.5 lw 1\nset style fill solid 0.85 border -1\n"
         "set boxwidth 0.9\nset grid ytics\nset key below horizontal maxcols 5 font ',9'\n"
         "set linetype 9 lc rgb '#8c564b'\nplot " +  // gnuplot's colors repeat after eight
         histogramBars("$table", methods, 3) + "\n";
}

std::string jsonObjectOf(const CsvRow& row, std::size_t textFields) {
  std::string json = "{";
  for (std::size_t i = 0; i < row.size(); ++i)
    json += (i ? ", " : "") + jsonString(row[i].first) + ": " + (i < textFields ? jsonString(row[i].second) : row[i].second);
  return json + "}";
}

}  // namespace hsr::studies
