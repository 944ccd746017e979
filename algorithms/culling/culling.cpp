// The culling stages by name, and the pipeline that runs them in order.
#include "algorithms/culling/culling.hpp"

#include "algorithms/culling/backface.hpp"
#include "algorithms/culling/cells/portals.hpp"
#include "algorithms/culling/cells/pvs.hpp"
#include "algorithms/culling/frustum.hpp"
#include "algorithms/culling/occlusion/occlusion.hpp"
#include "renderer/util/error.hpp"

namespace hsr::culling {
namespace {

// "a, b or c".
std::string choiceList(const std::vector<std::string>& choices) {
  std::string text;
  for (std::size_t i = 0; i < choices.size(); ++i) text += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
  return text;
}

// The knob of `stage` that may be given bare after `variant`, or nullptr.
const KnobSpec* bareKnob(const StageEntry& stage, const std::string& variant) {
  for (const KnobSpec& knob : stage.knobs)
    if (knob.bare && knob.appliesTo(variant)) return &knob;
  return nullptr;
}

}  // namespace

const std::vector<StageEntry>& stages() {
  static const std::vector<StageEntry> entries = {backface::stage(), frustum::stage(), occlusion::stage(), portals::stage(),
                                                 pvs::stage()};
  return entries;
}

std::string StageChoice::name() const {
  std::string text = stage->name + ":" + variant();
  const KnobSpec* bare = bareKnob(*stage, variant());
  if (bare) text += ":" + knobs.at(bare->name);
  for (const KnobSpec& knob : stage->knobs)
    if (knob.name != "variant" && &knob != bare && knobs.at(knob.name) != knob.defaultValue)
      text += ":" + knob.name + "=" + knobs.at(knob.name);
  return text;
}

Pipeline parsePipeline(const std::string& text, const std::string& where) {
  std::vector<std::string> stageNames;
  for (const StageEntry& stage : stages()) stageNames.push_back(stage.name);
  const std::string names = choiceList(stageNames);
  Pipeline pipeline;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, comma - begin);
    std::vector<std::string> parts;
    for (std::size_t from = 0;;) {
      const std::size_t colon = std::min(item.find(':', from), item.size());
      parts.push_back(item.substr(from, colon - from));
      if (colon == item.size()) break;
      from = colon + 1;
    }
    const std::string& name = parts.front();
    const auto stage = std::find_if(stages().begin(), stages().end(), [&](const StageEntry& s) { return s.name == name; });
    if (stage == stages().end())
      throw InputError(where + ": unknown culling stage '" + name + "' in '" + text + "'; expected a comma-separated list of " +
                       names + ", each optionally :VARIANT and :KNOB=VALUE");
    const bool variantGiven = parts.size() > 1 && parts[1].find('=') == std::string::npos;
    KnobSettings settings;
    if (variantGiven) {
      const std::vector<std::string>& variants = stage->variantKnob().choices;
      if (std::find(variants.begin(), variants.end(), parts[1]) == variants.end())
        throw InputError(where + ": culling stage " + name + " has no variant '" + parts[1] + "'; expected " + choiceList(stage->variantKnob().choices));
      settings.emplace_back("variant", parts[1]);
    }
    std::size_t next = variantGiven ? 2 : 1;
    // A bare value right after the variant sets the knob that takes one (occlusion:queries:chc).
    const std::string variant = variantGiven ? parts[1] : stage->variantKnob().defaultValue;
    if (const KnobSpec* bare = bareKnob(*stage, variant); bare && variantGiven && next < parts.size() && parts[next].find('=') == std::string::npos) {
      if (std::find(bare->choices.begin(), bare->choices.end(), parts[next]) == bare->choices.end())
        throw InputError(where + ": " + name + ":" + variant + " has no " + bare->name + " '" + parts[next] + "'; expected " +
                         choiceList(bare->choices));
      settings.emplace_back(bare->name, parts[next++]);
    }
    for (std::size_t i = next; i < parts.size(); ++i) {
      if (parts[i].find('=') == std::string::npos)
        throw InputError(where + ": '" + parts[i] + "' in '" + item + "' is not a setting; expected " + name +
                         "[:VARIANT] followed by :KNOB=VALUE settings");
      settings.push_back(parseKnobSetting(parts[i], where));
    }
    KnobValues values = stage->resolve(settings, where);
    if (const std::string conflict = stage->conflict(values); !conflict.empty()) throw InputError(where + ": " + item + ": " + conflict);
    pipeline.push_back({&*stage, std::move(values)});
    if (comma == text.size()) return pipeline;
    begin = comma + 1;
  }
}

std::string describePipeline(const Pipeline& pipeline) {
  std::string text;
  for (const StageChoice& choice : pipeline) {
    if (!text.empty()) text += ',';
    text += choice.name();
  }
  return text;
}

namespace {

// A stage's step: what it kept (grey) and what it removed (red), as wireframes.
void recordStage(const PreparedScene& scene, const CameraTransform& camera, const StageChoice& choice, const VisibleSet& in,
                 const VisibleSet& kept, StepRecorder& steps, SourceLocation where = SourceLocation::current()) {
  std::vector<std::uint32_t> removed;
  std::set_difference(in.triangles.begin(), in.triangles.end(), kept.triangles.begin(), kept.triangles.end(), std::back_inserter(removed));
  Image picture = blankPicture(scene.width(), scene.height());
  drawWireframe(picture, scene, camera, kept.triangles, {150, 150, 150});
  drawWireframe(picture, scene, camera, removed, kHighlight);
  drawLegend(picture, {{{150, 150, 150}, "kept: " + std::to_string(kept.triangles.size())},
                       {kHighlight, "removed: " + std::to_string(removed.size())}});
  steps.record("culling stage " + choice.name() + ": kept " + std::to_string(kept.triangles.size()) + " of " +
                   std::to_string(in.triangles.size()) + " triangles, removed " + std::to_string(removed.size()),
               std::move(picture), where);
}

}  // namespace

VisibleSet runPipeline(const PreparedScene& scene, const Pipeline& pipeline, int threads, Stats& stats,
                       const PreviousFrame* previous, StepRecorder* steps, CullingWitness* why) {
  const CameraTransform& camera = scene.camera();
  VisibleSet set = VisibleSet::everything(scene);
  if (previous && previous->memory) previous->memory->resize(std::max(previous->memory->size(), pipeline.size()));
  for (std::size_t s = 0; s < pipeline.size(); ++s) {
    const StageChoice& choice = pipeline[s];
    std::unique_ptr<StageMemory>* memory = previous && previous->memory ? &(*previous->memory)[s] : nullptr;
    StageWitness* const witness =
        why ? &why->byStage.emplace_back(StageWitness{why->instances, std::vector<std::string>(why->instances.size()), why->triangles,
                                                      std::vector<std::string>(why->triangles.size())})
            : nullptr;
    VisibleSet kept = choice.stage->run(choice.knobs, {scene, camera, set, threads, stats, previous, steps, memory, witness});
    if (steps) recordStage(scene, camera, choice, set, kept, *steps);
    if (why) why->keptByStage.push_back(kept);
    set = std::move(kept);
  }
  stats.add("culling: triangles kept", static_cast<std::int64_t>(set.triangles.size()));
  return set;
}

namespace {

// Calls run(instance, begin, end) for each instance with triangles in `in`, in order,
// [begin, end) being its part of in.triangles. `in` is sorted and each instance owns one
// run of ids: each part is found by binary search from where the previous one ended.
template <typename Run>
void forEachInstanceIn(const PreparedScene& scene, const VisibleSet& in, Run&& run) {
  auto begin = in.triangles.begin();
  for (std::uint32_t instance = 0; instance < scene.instances().size() && begin != in.triangles.end(); ++instance) {
    const Instance& object = scene.instances()[instance];
    const auto end = std::lower_bound(begin, in.triangles.end(), object.firstTriangle + object.triangleCount);
    if (begin != end) run(instance, begin, end);
    begin = end;
  }
}

}  // namespace

VisibleSet keepObjects(const PreparedScene& scene, const VisibleSet& in, const std::function<bool(std::uint32_t)>& keep) {
  VisibleSet out;
  forEachInstanceIn(scene, in, [&](std::uint32_t instance, auto begin, auto end) {
    if (keep(instance)) out.triangles.insert(out.triangles.end(), begin, end);
  });
  return out;
}

std::vector<TriangleRun> trianglesByInstance(const PreparedScene& scene, const VisibleSet& in) {
  std::vector<TriangleRun> runs(scene.instances().size());
  forEachInstanceIn(scene, in, [&](std::uint32_t instance, auto begin, auto end) {
    runs[instance] = {static_cast<std::uint32_t>(begin - in.triangles.begin()), static_cast<std::uint32_t>(end - in.triangles.begin())};
  });
  return runs;
}

std::vector<std::uint32_t> instancesIn(const PreparedScene& scene, const VisibleSet& in) {
  std::vector<std::uint32_t> instances;
  forEachInstanceIn(scene, in, [&](std::uint32_t instance, auto, auto) { instances.push_back(instance); });
  return instances;
}

}  // namespace hsr::culling
