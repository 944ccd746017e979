#include "algorithms/registry.hpp"

#include <algorithm>

#include "algorithms/zbuffer/zbuffer.hpp"
#include "renderer/error.hpp"

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
  entry.render = [knobs = entry.knobs](const PreparedScene& scene, const KnobValues& values, int threads, Stats& stats) {
    zbuffer::Knobs typed;
    typed.variant = static_cast<zbuffer::Variant>(choiceIndex(knobs[0], values.at("variant")));
    typed.depthFormat = static_cast<DepthFormat>(choiceIndex(knobs[1], values.at("depth-format")));
    return zbuffer::run(scene, typed, threads, stats);
  };
  return entry;
}

}  // namespace

const std::vector<AlgorithmEntry>& algorithms() {
  static const std::vector<AlgorithmEntry> all = {zbufferEntry()};
  return all;
}

const AlgorithmEntry& findAlgorithm(const std::string& name) {
  std::vector<std::string> names;
  for (const auto& entry : algorithms()) {
    if (entry.name == name) return entry;
    names.push_back(entry.name);
  }
  throw InputError("--algo " + name + ": unknown algorithm; expected one of " + joined(names));
}

KnobValues resolveKnobs(const AlgorithmEntry& algorithm, const std::vector<std::pair<std::string, std::string>>& settings) {
  KnobValues values;
  for (const auto& knob : algorithm.knobs) values[knob.name] = knob.choices.front();
  for (const auto& [name, value] : settings) {
    const auto knob = std::find_if(algorithm.knobs.begin(), algorithm.knobs.end(), [&](const KnobSpec& k) { return k.name == name; });
    if (knob == algorithm.knobs.end()) {
      std::vector<std::string> names;
      for (const auto& k : algorithm.knobs) names.push_back(k.name);
      throw InputError("--knob " + name + "=" + value + ": " + algorithm.name + " has no knob '" + name +
                       "'; expected one of " + joined(names));
    }
    if (choiceIndex(*knob, value) == knob->choices.size())
      throw InputError("--knob " + name + "=" + value + ": " + algorithm.name + " " + name + " must be one of " +
                       joined(knob->choices));
    values[name] = value;
  }
  return values;
}

}  // namespace hsr
