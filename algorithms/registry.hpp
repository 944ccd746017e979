// The registry: every algorithm by name, so the command line, the studies, the tests
// and the benchmarks discover algorithms instead of hard-coding them. The entries come
// from the algorithm folders themselves (algorithms/algorithm.hpp): the build lists the
// folders (algorithms/CMakeLists.txt), the exact reference first.
#pragma once

#include <string>
#include <vector>

#include "algorithms/algorithm.hpp"
#include "algorithms/knobs.hpp"

namespace hsr {

const std::vector<AlgorithmEntry>& algorithms();

// Throws InputError naming the unknown algorithm (after `where`, the option that gave
// it) and listing the known ones: for names a user typed.
const AlgorithmEntry& findAlgorithm(const std::string& name, const std::string& where = "--algo");

// The registered entry that `make` made: how code names an algorithm, typed, so that a
// renamed or removed one is a compile error rather than an unknown name at run time
// (entryOf(zbuffer::entry)).
using MakeEntry = AlgorithmEntry (*)();
const AlgorithmEntry& entryOf(MakeEntry make);
// The exact reference's entry.
const AlgorithmEntry& referenceEntry();

// The algorithm's knob of that name, or nullptr.
const KnobSpec* findKnob(const AlgorithmEntry& algorithm, const std::string& name);

// The settings checked and typed by the algorithm's knob table: throws InputError for an
// unknown knob, a value outside its choices or range, or a knob the chosen variant does
// not have, naming `where`, the algorithm, the knob and what is allowed.
KnobValues resolveKnobs(const AlgorithmEntry& algorithm, const KnobSettings& settings, const std::string& where = "--knob");

// The algorithm's name as prose ("ray casting" for ray_casting), for messages.
std::string displayName(const AlgorithmEntry& algorithm);

// The functions that make the entries of the algorithms the build registered, in the
// order of algorithms/CMakeLists.txt (defined in the generated registered_algorithms.cpp).
std::vector<MakeEntry> registeredAlgorithms();

}  // namespace hsr
