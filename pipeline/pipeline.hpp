// The pipeline: one place that runs a configuration on a scene, pass by pass,
//   culling -> visibility -> shadow maps -> shading -> transparency -> fog -> outline,
// each pass only when the scene's effects (renderer/scene/scene.hpp: Effects) and the
// configuration call for it. The algorithm answers visibility alone (algorithms/
// algorithm.hpp); everything after it is the same for every algorithm. `hsr render
// --explain` prints plan(), which asks the same passes the same question render() asks
// them, so the plan cannot drift from what runs. Each pass times itself ("pass: NAME"
// phases, read back by passTimes).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "algorithms/algorithm.hpp"
#include "algorithms/culling/culling.hpp"
#include "algorithms/registry.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/source_location.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::pipeline {

// What to run: an algorithm with its knobs, after culling stages (none when empty).
struct Configuration {
  const AlgorithmEntry* algorithm = nullptr;
  KnobValues knobs;
  culling::Pipeline culling = {};
};

// A configuration of an algorithm's settings, checked (InputError naming `where`).
Configuration configurationOf(const AlgorithmEntry& algorithm, const KnobSettings& settings, const std::string& where = "--knob");
// The same in the algorithm's own types: the function that makes its entry and its Knobs
// struct (configurationOf(zbuffer::entry, zbuffer::knobTable(), {.depthTest = false})),
// so that code names no algorithm or knob by a string.
template <typename Knobs>
Configuration configurationOf(MakeEntry make, const KnobTable<Knobs>& table, const Knobs& knobs = {}) {
  return {&entryOf(make), table.valuesOf(knobs)};
}

// Why the configuration cannot render the scene, or "" when it can: the algorithm's own
// refusal (a budget, a shape it cannot handle), or transparency an algorithm cannot blend
// (it answers only the nearest surface and cannot leave the transparent ones out).
std::string refusal(const PreparedScene& scene, const Configuration& configuration);
// The algorithms that can draw a culled set of triangles: "zbuffer or painter".
std::string cullableAlgorithms();
// The culling stages --cull asks for (empty: none), checked against what the algorithm
// can take: InputError for a stage it cannot, naming the algorithms that can.
culling::Pipeline cullingOf(const std::string& text, const AlgorithmEntry& algorithm);
// Throws InputError ("SCENE: ALGORITHM cannot render it: why") when refusal() names a reason.
void checkRenders(const Configuration& configuration, const std::string& sceneName, const PreparedScene& scene);
// What to say when a render runs out of memory: a size within the limits can still be
// more than the machine (or a browser's page) has. Names the memory the frame alone needs.
std::string outOfMemory(int width, int height, const std::string& algorithm);
// The same where the size is not known (loading a scene, preparing it).
inline constexpr const char* kOutOfMemory = "out of memory; expected a smaller --size or scene";

// One pass as the plan shows it: whether it runs, and the scene fact that decides it.
struct PlannedPass {
  std::string pass;
  bool runs;
  std::string reason;
  std::vector<PlannedPass> work = {};  // choices inside the pass (the shading's normals, highlights, shadow lookups)
};
std::vector<PlannedPass> plan(const PreparedScene& scene, const Configuration& configuration);

// The result of a render: the image (surfaces shaded, or a line drawing's visible lines
// rasterized), for a line algorithm the drawing itself, for an algorithm that draws
// polygons (AlgorithmEntry::drawsPolygons) the visible ones, and for one that shares
// pixels among surfaces (the A-buffer) each pixel's shares.
struct Rendered {
  Frame frame;
  LineSet drawing;
  std::vector<VisiblePolygon> polygons = {};
  std::optional<PixelCoverage> coverage = {};
};

// Renders the scene at its size. threads: 0 = all cores; the image is the same bits for
// every count. `previous`: the previous frame, for a culling stage that reuses it
// (occlusion:previous-frame). `steps`: where the culling stages and the algorithm record
// their steps (renderer/steps/steps.hpp), or null. The configuration must not be refused
// (refusal()).
Rendered render(const PreparedScene& scene, const Configuration& configuration, int threads, Stats& stats,
                const culling::PreviousFrame* previous = nullptr, StepRecorder* steps = nullptr);

// The culling and visibility passes alone, into `visibility` (its frame reused when it
// has the scene's size): what the studies time when they compare visibility methods,
// which the shading passes would only add the same cost to. Returns what the culling
// stages kept (every triangle when there are none). `why`: the pixels hsr why asks about,
// whose histories an algorithm that answers why (AlgorithmEntry::answersWhy) records, and
// the counter "why: events recorded"; null: none asked, and no provenance work done.
// culled: where the culling stages' kept sets and what each found for culled->instances
// go, one per stage in order (culling.hpp), or null.
// `steps`: where their steps go, as render()'s (hsr why --step).
VisibleSet renderVisibility(const PreparedScene& scene, const Configuration& configuration, int threads, Stats& stats,
                            Visibility& visibility, const culling::PreviousFrame* previous = nullptr, PixelWitness* why = nullptr,
                            culling::CullingWitness* culled = nullptr, StepRecorder* steps = nullptr);

// The caption of the last step hsr render --steps records for a surface algorithm, after
// the algorithm's own: the finished image.
inline constexpr const char* kFinishedImageStep = "the finished image, after the passes that follow visibility (hsr render --explain)";
// That last step recorded: `shown` is the finished image, or for a line algorithm the
// drawing as it is shown (in its --line-style); the steps page shows the caller's lines.
void recordFinishedStep(StepRecorder& steps, const Frame& shown, bool lines, SourceLocation where = SourceLocation::current());

// The time of each pass that ran, in pipeline order, from a render's Stats.
struct PassTime {
  std::string pass;
  double seconds;
  bool visibility;  // culling or visibility: the algorithm's own cost (renderVisibility's passes)
};
std::vector<PassTime> passTimes(const Stats& stats);

// What the render decided on the way, read from its counters: the work each piece of
// expensive machinery did, or that it did none because the scene did not need it.
std::vector<std::string> decisionsTaken(const Stats& stats);

}  // namespace hsr::pipeline
