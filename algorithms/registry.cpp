#include "algorithms/registry.hpp"

#include <algorithm>
#include <variant>

#include "renderer/reference.hpp"

namespace hsr {
namespace {

// The exact reference every surface algorithm is judged by (renderer/reference), listed
// so that `--algo reference` renders it and `hsr list` names it.
AlgorithmEntry referenceEntry() {
  AlgorithmEntry entry;
  entry.name = "reference";
  entry.kind = AlgorithmKind::reference;
  entry.summary = "exact visibility per pixel center: BVH, watertight ray test, exact fall-back (renderer/reference)";
  entry.resolve = [](const KnobSettings& settings, const std::string& where) {
    return KnobTable<std::monostate>().resolve("reference", settings, where);
  };
  entry.keyCounters = {"reference exact fall-backs", "reference ambiguous pixels", "bvh nodes visited", "ray-triangle tests"};
  entry.renderExactly = [](const PreparedScene& scene, int threads, Stats& stats) { return renderReference(scene, threads, stats).frame; };
  return entry;
}

}  // namespace

const std::vector<AlgorithmEntry>& algorithms() {
  static const std::vector<AlgorithmEntry> all = [] {
    std::vector<AlgorithmEntry> entries = {referenceEntry()};
    for (AlgorithmEntry& entry : registeredAlgorithms()) entries.push_back(std::move(entry));
    return entries;
  }();
  return all;
}

const AlgorithmEntry& findAlgorithm(const std::string& name, const std::string& where) {
  std::string names;
  for (const auto& entry : algorithms()) {
    if (entry.name == name) return entry;
    names += (names.empty() ? "" : ", ") + entry.name;
  }
  throw InputError(where + " " + name + ": unknown algorithm; expected one of " + names);
}

const KnobSpec* findKnob(const AlgorithmEntry& algorithm, const std::string& name) { return findKnob(algorithm.knobs, name); }

KnobValues resolveKnobs(const AlgorithmEntry& algorithm, const KnobSettings& settings, const std::string& where) {
  return algorithm.resolve(settings, where);
}

std::string displayName(const AlgorithmEntry& algorithm) {
  std::string name = algorithm.name;
  std::replace(name.begin(), name.end(), '_', ' ');
  return name;
}

}  // namespace hsr
