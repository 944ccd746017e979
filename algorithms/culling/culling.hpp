// Culling stages: cheap tests that remove triangles before a surface algorithm draws
// them. A correct stage is conservative: it may keep a triangle nobody will see, never
// drop one somebody would. The textbooks' wrong versions are kept as variants, so the
// suite can show where they drop visible triangles.
//
//   backface (backface.cpp)  a triangle facing away from the eye is hidden by the front
//                            of its own closed surface
//   frustum  (frustum.cpp)   an object or triangle wholly outside the view volume
//   occlusion (occlusion/)   an object behind what nearer objects drew into a small
//                            depth map (or what the previous frame left in its depth)
//   portals (cells/)         in a level divided into cells, a cell no chain of portals
//                            from the eye's cell reaches within the view
//   pvs (cells/)             in such a level, an object outside the set precomputed for
//                            the eye's cell
//
// A pipeline runs stages in the order given, each on what the previous one kept, and
// hands the surviving VisibleSet (renderer/scene/visible_set.hpp) to a surface algorithm.
#pragma once

#include <algorithm>
#include <functional>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "algorithms/culling/occlusion/simulated_gpu.hpp"
#include "algorithms/knobs.hpp"
#include "renderer/geometry/camera.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/scene/visible_set.hpp"
#include "renderer/steps/steps.hpp"
#include "renderer/util/parallel.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::culling {

// What a stage carries from one frame of a walk to the next (occlusion:queries keeps
// its hierarchy's visibility and its answers still in flight); each such stage derives
// its own.
struct StageMemory {
  virtual ~StageMemory() = default;
};

// What earlier frames of a walk left behind, for the stages that use them: the previous
// frame's camera and image, whose depth occlusion:previous-frame reads (null on the
// first frame); a memory slot per stage of the pipeline, kept by the caller from frame
// to frame; and the simulated GPU the walk is drawn on (algorithms/culling/occlusion/simulated_gpu.hpp),
// for occlusion:queries, which draws and queries as it goes (the caller begins and ends
// its frames). Null memory or GPU: the stage starts from nothing, on a GPU of its own.
struct PreviousFrame {
  Camera camera;
  const Frame* frame = nullptr;
  std::vector<std::unique_ptr<StageMemory>>* memory = nullptr;
  SimulatedGpu* gpu = nullptr;
};

// hsr why: what a stage's own test found for the objects and triangles asked about (the
// reference's, at the pixels asked about), in its terms ("outside the left plane",
// "behind every texel of its footprint", "the eye lies behind its plane"). Handed to a
// stage only when asked (StageInput::why), as PixelWitness is to an algorithm: a stage
// that tests objects fills `found`, one that tests triangles `foundForTriangle`.
struct StageWitness {
  std::vector<std::uint32_t> instances;  // the objects asked about, ascending
  std::vector<std::string> found;        // what the test found for each ("": nothing said)
  std::vector<std::uint32_t> triangles;  // the triangles asked about, ascending
  std::vector<std::string> foundForTriangle;
  // The slot of an object asked about, or null for any other.
  std::string* about(std::uint32_t instance) { return slotOf(instances, found, instance); }
  // The slot of a triangle asked about, or null for any other.
  std::string* aboutTriangle(std::uint32_t triangle) { return slotOf(triangles, foundForTriangle, triangle); }

 private:
  static std::string* slotOf(const std::vector<std::uint32_t>& asked, std::vector<std::string>& slots, std::uint32_t which) {
    const auto at = std::lower_bound(asked.begin(), asked.end(), which);
    return at != asked.end() && *at == which ? &slots[std::size_t(at - asked.begin())] : nullptr;
  }
};

// hsr why's view of a pipeline: each stage's kept set and its witness, in order.
struct CullingWitness {
  std::vector<std::uint32_t> instances;  // the objects asked about, ascending
  std::vector<std::uint32_t> triangles;  // the triangles asked about, ascending
  std::vector<VisibleSet> keptByStage;
  std::vector<StageWitness> byStage;
};

// What a stage works on: the scene seen from its camera, and what earlier stages kept.
struct StageInput {
  const PreparedScene& scene;
  const CameraTransform& camera;
  const VisibleSet& in;
  int threads;
  Stats& stats;
  const PreviousFrame* previous;  // nullptr: none (the first frame, or a single image)
  StepRecorder* steps = nullptr;  // where the stage records its steps; null: not asked (renderer/steps/steps.hpp)
  std::unique_ptr<StageMemory>* memory = nullptr;  // this stage's slot in previous->memory, or null
  StageWitness* why = nullptr;  // hsr why's objects, where the stage says what its test found; null: not asked
};

// A stage as the pipeline and `hsr list` see it. Each stage file declares its own
// (backface::stage(), frustum::stage(), occlusion::stage()) with its knob table: the
// "variant" knob first, each variant with a line of help, then the knobs given as
// :KNOB=VALUE after it.
struct StageEntry {
  std::string name;
  std::string summary;
  std::vector<KnobSpec> knobs;
  std::function<KnobValues(const KnobSettings&, const std::string& where)> resolve;
  // Whether these settings can drop visible triangles (a variant kept to show why, or a
  // knob traded for speed).
  std::function<bool(const KnobValues&)> mayDropVisible = nullptr;
  // Why these settings do not go together, or "" when they do.
  std::function<std::string(const KnobValues&)> conflict = [](const KnobValues&) { return std::string(); };
  std::function<VisibleSet(const KnobValues&, const StageInput&)> run = nullptr;
  // Runs only on a level divided into [[cells]] (portals, pvs), and refuses others.
  bool needsCells = false;

  const KnobSpec& variantKnob() const { return knobs.front(); }
};

// A stage's entry with its knob table hooked up.
template <typename Knobs>
StageEntry stageEntry(std::string name, std::string summary, const KnobTable<Knobs>& table) {
  StageEntry stage{std::move(name), std::move(summary), table.specs(), nullptr};
  stage.resolve = [table, owner = "culling stage " + stage.name](const KnobSettings& settings, const std::string& where) {
    return table.resolve(owner, settings, where);
  };
  return stage;
}

const std::vector<StageEntry>& stages();

// One stage of a pipeline with its variant and knobs chosen.
struct StageChoice {
  const StageEntry* stage;
  KnobValues knobs;  // every knob of the stage, the variant's among them, validated
  bool wrong() const { return stage->mayDropVisible(knobs); }
  const std::string& variant() const { return knobs.at("variant"); }
  // "occlusion:depth-map:raster=center": the variant, and the knobs that differ from
  // their defaults.
  std::string name() const;
};
using Pipeline = std::vector<StageChoice>;

// "backface,frustum:sphere,occlusion:depth-map:raster=center": stages separated by
// commas, each NAME, NAME:VARIANT or either followed by :KNOB=VALUE settings. Throws
// InputError naming `where` and what was expected.
Pipeline parsePipeline(const std::string& text, const std::string& where = "--cull");
std::string describePipeline(const Pipeline& pipeline);  // "backface:object,frustum:sphere"

// Runs the stages in order on the scene's camera and size. threads: 0 = all cores; the
// result is the same for every thread count. Counts "culling: triangles kept". With
// steps, records after each stage what it kept and what it removed; with why, keeps
// there what each stage kept and found for why->instances, in order (hsr why names the
// stage that removed a triangle, and what its test found).
VisibleSet runPipeline(const PreparedScene& scene, const Pipeline& pipeline, int threads, Stats& stats,
                       const PreviousFrame* previous = nullptr, StepRecorder* steps = nullptr, CullingWitness* why = nullptr);

// The machinery the stages share. The triangles of `in` for which a test holds, in
// order, tested in parallel chunks: makeTest() gives each chunk its own test (a callable
// bool(std::uint32_t triangle)), so a test may keep state without sharing it.
template <typename MakeTest>
VisibleSet keepTriangles(const VisibleSet& in, int threads, MakeTest&& makeTest);
// The triangles of `in` whose instance passes keep(instance index); keep is asked once
// for each instance that has triangles in `in`, in order, and never for the others.
VisibleSet keepObjects(const PreparedScene& scene, const VisibleSet& in, const std::function<bool(std::uint32_t)>& keep);
// The instances that have triangles in `in`, ascending.
std::vector<std::uint32_t> instancesIn(const PreparedScene& scene, const VisibleSet& in);
// For each instance, its triangles in `in`: the part [first, end) of in.triangles (empty
// when it has none).
struct TriangleRun {
  std::uint32_t first = 0, end = 0;
};
std::vector<TriangleRun> trianglesByInstance(const PreparedScene& scene, const VisibleSet& in);

// keepTriangles: each chunk writes its own list, and the lists are joined in chunk
// order, so the output is the same for any thread count.
template <typename MakeTest>
VisibleSet keepTriangles(const VisibleSet& in, int threads, MakeTest&& makeTest) {
  constexpr std::size_t kChunk = 8192;
  const std::size_t chunks = (in.triangles.size() + kChunk - 1) / kChunk;
  std::vector<std::vector<std::uint32_t>> kept(chunks);
  parallelFor(chunks, threads, [&](std::size_t chunk, int) {
    auto test = makeTest();
    const auto begin = in.triangles.begin() + std::ptrdiff_t(chunk * kChunk);
    const auto end = in.triangles.begin() + std::ptrdiff_t(std::min(in.triangles.size(), (chunk + 1) * kChunk));
    std::copy_if(begin, end, std::back_inserter(kept[chunk]), test);
  });
  VisibleSet out;
  std::size_t total = 0;
  for (const auto& part : kept) total += part.size();
  out.triangles.reserve(total);
  for (const auto& part : kept) out.triangles.insert(out.triangles.end(), part.begin(), part.end());
  return out;
}

}  // namespace hsr::culling
