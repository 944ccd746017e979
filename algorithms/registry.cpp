#include "algorithms/registry.hpp"

#include <algorithm>

#include "algorithms/zbuffer/zbuffer.hpp"
#include "renderer/error.hpp"
#include "renderer/reference.hpp"

namespace hsr {
namespace {

std::string joined(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& word : words) text += (text.empty() ? "" : ", ") + word;
  return text;
}

std::size_t choiceIndex(const KnobSpec& knob, const std::string& value) {
  return static_cast<std::size_t>(std::find(knob.choices.begin(), knob.choices.end(), value) - knob.choices.begin());
}

AlgorithmEntry zbufferEntry() {
  AlgorithmEntry entry;
  entry.name = "zbuffer";
  entry.kind = "surface";
  entry.summary = "per-pixel depth test (Catmull 1974): full-frame or one-scanline buffer";
  entry.knobs = {
      {"variant", "full: whole-image depth buffer, tile-parallel; scanline: one row of depth, active-triangle list",
       {"full", "scanline"}},
      {"depth-format", "what the depth buffer stores (conventions.hpp)", depthFormatNames()},
  };
  entry.keyCounters = {"screen triangles", "fragments tested", "fragments written"};
  entry.studyConfigurations = {{}, {{"variant", "scanline"}}, {{"depth-format", "unorm24"}}, {{"depth-format", "unorm16"}}};
  entry.render = [knobs = entry.knobs](const PreparedScene& scene, const KnobValues& values, int threads, Stats& stats) {
    zbuffer::Knobs typed;
    typed.variant = static_cast<zbuffer::Variant>(choiceIndex(knobs[0], values.at("variant")));
    typed.depthFormat = static_cast<DepthFormat>(choiceIndex(knobs[1], values.at("depth-format")));
    return zbuffer::run(scene, typed, threads, stats);
  };
  return entry;
}

AlgorithmEntry referenceEntry() {
  AlgorithmEntry entry;
  entry.name = "reference";
  entry.kind = "reference";
  entry.summary = "exact visibility per pixel center: BVH, watertight ray test, exact fall-back (renderer/reference)";
  entry.keyCounters = {"reference exact fall-backs", "reference ambiguous pixels", "bvh nodes visited", "ray-triangle tests"};
  entry.render = [](const PreparedScene& scene, const KnobValues&, int threads, Stats& stats) {
    return renderReference(scene, threads, stats).frame;
  };
  return entry;
}

}  // namespace

const std::vector<AlgorithmEntry>& algorithms() {
  static const std::vector<AlgorithmEntry> all = {referenceEntry(), zbufferEntry()};
  return all;
}

const AlgorithmEntry& findAlgorithm(const std::string& name, const std::string& where) {
  std::vector<std::string> names;
  for (const auto& entry : algorithms()) {
    if (entry.name == name) return entry;
    names.push_back(entry.name);
  }
  throw InputError(where + " " + name + ": unknown algorithm; expected one of " + joined(names));
}

KnobValues resolveKnobs(const AlgorithmEntry& algorithm, const KnobSettings& settings, const std::string& where) {
  KnobValues values;
  for (const auto& knob : algorithm.knobs) values[knob.name] = knob.choices.front();
  for (const auto& [name, value] : settings) {
    const auto knob = std::find_if(algorithm.knobs.begin(), algorithm.knobs.end(), [&](const KnobSpec& k) { return k.name == name; });
    if (knob == algorithm.knobs.end()) {
      std::vector<std::string> names;
      for (const auto& k : algorithm.knobs) names.push_back(k.name);
      throw InputError(where + " " + name + "=" + value + ": " + algorithm.name + " has no knob '" + name +
                       "'; expected one of " + joined(names));
    }
    if (choiceIndex(*knob, value) == knob->choices.size())
      throw InputError(where + " " + name + "=" + value + ": " + algorithm.name + " " + name + " must be one of " +
                       joined(knob->choices));
    values[name] = value;
  }
  return values;
}

std::pair<std::string, std::string> parseKnobSetting(const std::string& text, const std::string& where) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0) throw InputError(where + " " + text + ": expected NAME=VALUE");
  return {text.substr(0, equals), text.substr(equals + 1)};
}

std::string describeKnobs(const AlgorithmEntry& algorithm, const KnobValues& values) {
  std::string text;
  for (const auto& knob : algorithm.knobs) {
    const std::string& value = values.at(knob.name);
    if (value != knob.choices.front()) text += (text.empty() ? "" : " ") + knob.name + "=" + value;
  }
  return text.empty() ? "defaults" : text;
}

}  // namespace hsr
