// The registry: every algorithm by name, with its knobs and their allowed values, so
// the CLI, the tests and (later) sweeps discover algorithms instead of hard-coding them.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "renderer/frame.hpp"
#include "renderer/prepare.hpp"
#include "renderer/stats.hpp"

namespace hsr {

struct KnobSpec {
  std::string name;
  std::string help;
  std::vector<std::string> choices;  // allowed values; the first is the default
};

using KnobValues = std::map<std::string, std::string>;  // every knob of the algorithm, validated

struct AlgorithmEntry {
  std::string name;
  std::string kind;  // "surface" for now; line algorithms and culling stages come later
  std::string summary;
  std::vector<KnobSpec> knobs;
  // threads: 0 = all cores.
  std::function<Frame(const PreparedScene&, const KnobValues&, int threads, Stats&)> render;
};

const std::vector<AlgorithmEntry>& algorithms();

// Throws InputError naming the unknown algorithm and listing the known ones.
const AlgorithmEntry& findAlgorithm(const std::string& name);

// Fills in defaults and checks every setting; throws InputError for an unknown knob or
// a value outside its choices, naming the algorithm, the knob and what is allowed.
KnobValues resolveKnobs(const AlgorithmEntry& algorithm, const std::vector<std::pair<std::string, std::string>>& settings);

}  // namespace hsr
