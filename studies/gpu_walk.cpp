// What the walkthrough studies share (gpu_walk.hpp).
#include "studies/gpu_walk.hpp"

#include <algorithm>

#include "algorithms/registry.hpp"
#include "pipeline/pipeline.hpp"

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
    const pipeline::Configuration zbuffer = pipeline::configurationOf(findAlgorithm("zbuffer"), {});
    walk.last.frame = Frame(scene.width(), scene.height());
    zbuffer.algorithm->visibility({scene, scene.camera(), &kept, threads, untimed}, zbuffer.knobs, walk.last);
  }
  walk.lastCamera = scene.camera().camera(), walk.hasLast = true;

  FrameRow row;
  row.ms = 1e3 * times.frame, row.waitingMs = 1e3 * times.waiting;
  row.triangles = std::int64_t(kept.triangles.size());
  row.objects = std::count_if(runs.begin(), runs.end(), [](const culling::TriangleRun& run) { return run.end > run.first; });
  row.queries = stats.counter("queries: issued"), row.wasted = stats.counter("queries: answered visible");
  walk.drawnInSpell.resize(seen.size(), 0);
  for (std::size_t object = 0; object < seen.size(); ++object) {
    const bool drawn = runs[object].end > runs[object].first;
    if (seen[object] && !seenBefore[object]) walk.drawnInSpell[object] = 0;  // a new spell in view
    if (seen[object] && !drawn) (walk.drawnInSpell[object] ? row.falseCulls : row.late) += 1;
    walk.drawnInSpell[object] = walk.drawnInSpell[object] || (seen[object] && drawn);
  }
  return row;
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

std::string jsonObjectOf(const CsvRow& row, std::size_t textFields) {
  std::string json = "{";
  for (std::size_t i = 0; i < row.size(); ++i)
    json += (i ? ", " : "") + jsonString(row[i].first) + ": " + (i < textFields ? jsonString(row[i].second) : row[i].second);
  return json + "}";
}

}  // namespace hsr::studies
