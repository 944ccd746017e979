#include "algorithms/registry.hpp"

#include <algorithm>
#include <variant>

#include "renderer/reference/reference.hpp"

namespace hsr {
namespace {

// The exact reference every surface algorithm is judged by (renderer/reference/reference), listed
// so that `--algo reference` renders it and `hsr list` names it.
AlgorithmEntry makeReferenceEntry() {
  AlgorithmEntry entry;
  entry.name = "reference";
  entry.kind = AlgorithmKind::reference;
  entry.summary = "exact visibility per pixel center: BVH, watertight ray test, exact fall-back (renderer/reference/reference)";
  entry.resolve = [](const KnobSettings& settings, const std::string& where) {
    return KnobTable<std::monostate>().resolve("reference", settings, where);
  };
  entry.keyCounters = {"reference exact fall-backs", "reference ambiguous pixels", "bvh nodes visited", "ray-triangle tests"};
  entry.renderExactly = [](const PreparedScene& scene, int threads, Stats& stats) { return renderReference(scene, threads, stats).frame; };
  return entry;
}

// Every entry with the function that made it, the reference first.
struct Registered {
  MakeEntry make;
  AlgorithmEntry entry;
};
const std::vector<Registered>& registered() {
  static const std::vector<Registered> all = [] {
    std::vector<Registered> entries = {{makeReferenceEntry, makeReferenceEntry()}};
    for (const MakeEntry make : registeredAlgorithms()) entries.push_back({make, make()});
    return entries;
  }();
  return all;
}

}  // namespace

const std::vector<AlgorithmEntry>& algorithms() {
  static const std::vector<AlgorithmEntry> all = [] {
    std::vector<AlgorithmEntry> entries;
    for (const Registered& each : registered()) entries.push_back(each.entry);
    return entries;
  }();
  return all;
}

const AlgorithmEntry& entryOf(MakeEntry make) {
  for (std::size_t i = 0; i < registered().size(); ++i)
    if (registered()[i].make == make) return algorithms()[i];
  HSR_CHECK(false && "an algorithm the build did not register (algorithms/CMakeLists.txt)");
  return algorithms().front();
}

const AlgorithmEntry& referenceEntry() { return entryOf(makeReferenceEntry); }

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
