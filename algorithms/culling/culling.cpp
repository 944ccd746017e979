// The culling stages by name, and the pipeline that runs them in order.
#include "algorithms/culling/culling.hpp"

#include "algorithms/culling/backface.hpp"
#include "algorithms/culling/frustum.hpp"
#include "algorithms/culling/occlusion/occlusion.hpp"
#include "renderer/error.hpp"

namespace hsr::culling {
namespace {

// The index of a variant among the stage's, as the stage's enum lists them in the same order.
template <typename Variant>
Variant variantOf(const StageEntry& stage, const std::string& name) {
  for (std::size_t i = 0; i < stage.variants.size(); ++i)
    if (stage.variants[i].first == name) return static_cast<Variant>(i);
  HSR_CHECK(false && "variant validated by parsePipeline");
  return Variant{};
}

std::string variantList(const StageEntry& stage) {
  std::string text;
  for (std::size_t i = 0; i < stage.variants.size(); ++i)
    text += (i == 0 ? "" : i + 1 == stage.variants.size() ? " or " : ", ") + stage.variants[i].first;
  return text;
}

// A stage whose variants are named in the order of its enum, run by `cull`.
template <typename Variant, typename Cull>
StageEntry stageEntry(std::string name, std::string summary, std::vector<std::pair<std::string, std::string>> variants,
                      std::vector<std::string> wrongVariants, Cull cull) {
  StageEntry stage{std::move(name), std::move(summary), std::move(variants), std::move(wrongVariants), nullptr};
  stage.run = [stage, cull](const StageChoice& choice, const StageInput& input) {
    return cull(input.scene, input.camera, variantOf<Variant>(stage, choice.variant), input.in, input.threads, input.stats);
  };
  return stage;
}

}  // namespace

const std::vector<StageEntry>& stages() {
  static const std::vector<StageEntry> entries = {
      stageEntry<backface::Variant>(
          "backface", "drop triangles facing away from the eye (right for closed surfaces only)",
          {{"object", "the eye against the triangle's plane, an exact sign"},
           {"screen", "the sign of the projected area, after clipping at the near plane"},
           {"view-direction", "the normal against the view direction only: wrong under perspective, kept to show why"}},
          {"view-direction"}, backface::cull),
      stageEntry<frustum::Variant>(
          "frustum", "drop objects or triangles wholly outside the view volume",
          {{"sphere", "per object: its bounding sphere against the six planes"},
           {"aabb", "per object: its box, by center and extent, against the six planes"},
           {"bvh", "per object, hierarchically: boxes down the object BVH, with plane masking"},
           {"triangle", "per triangle: outside when all three corners are outside one plane"},
           {"any-vertex", "per triangle: kept only if a corner is inside; wrong for big triangles, kept to show why"}},
          {"any-vertex"}, frustum::cull),
      occlusion::stage(),
  };
  return entries;
}

bool StageChoice::wrong() const {
  return std::find(stage->wrongVariants.begin(), stage->wrongVariants.end(), variant) != stage->wrongVariants.end() ||
         stage->knobsMayDropVisible(knobs);
}

std::string StageChoice::name() const {
  std::string text = stage->name + ":" + variant;
  for (const KnobSpec& knob : stage->knobs)
    if (knobs.at(knob.name) != knob.choices.front()) text += ":" + knob.name + "=" + knobs.at(knob.name);
  return text;
}

Pipeline parsePipeline(const std::string& text, const std::string& where) {
  std::string names;
  for (const StageEntry& stage : stages()) names += (names.empty() ? "" : " or ") + stage.name;
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
    const std::string variant = variantGiven ? parts[1] : stage->variants.front().first;
    if (std::none_of(stage->variants.begin(), stage->variants.end(), [&](const auto& v) { return v.first == variant; }))
      throw InputError(where + ": culling stage " + name + " has no variant '" + variant + "'; expected " + variantList(*stage));
    // The variant is a knob like the others to the checks: some knobs belong to one variant.
    std::vector<KnobSpec> knobs = stage->knobs;
    KnobSpec variantKnob{"variant", "", {}};
    for (const auto& v : stage->variants) variantKnob.choices.push_back(v.first);
    knobs.push_back(variantKnob);
    KnobSettings settings = {{"variant", variant}};
    for (std::size_t i = variantGiven ? 2 : 1; i < parts.size(); ++i) {
      if (parts[i].find('=') == std::string::npos)
        throw InputError(where + ": '" + parts[i] + "' in '" + item + "' is not a setting; expected " + name +
                         "[:VARIANT] followed by :KNOB=VALUE settings");
      settings.push_back(parseKnobSetting(parts[i], where));
    }
    KnobValues values = resolveKnobs("culling stage " + name, knobs, settings, where);
    values.erase("variant");
    if (const std::string conflict = stage->conflict(variant, values); !conflict.empty())
      throw InputError(where + ": " + item + ": " + conflict);
    pipeline.push_back({&*stage, variant, std::move(values)});
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

VisibleSet runPipeline(const PreparedScene& scene, const Pipeline& pipeline, int threads, Stats& stats,
                       const PreviousFrame* previous) {
  const CameraTransform& camera = scene.camera();
  VisibleSet set = VisibleSet::everything(scene);
  for (const StageChoice& choice : pipeline) set = choice.stage->run(choice, {scene, camera, set, threads, stats, previous});
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

std::vector<std::uint32_t> instancesIn(const PreparedScene& scene, const VisibleSet& in) {
  std::vector<std::uint32_t> instances;
  forEachInstanceIn(scene, in, [&](std::uint32_t instance, auto, auto) { instances.push_back(instance); });
  return instances;
}

}  // namespace hsr::culling
