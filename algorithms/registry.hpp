// The registry: every algorithm by name, with its knobs and their allowed values, so
// the CLI, the tests and (later) sweeps discover algorithms instead of hard-coding them.
#pragma once

#include <algorithm>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "renderer/frame.hpp"
#include "renderer/line_set.hpp"
#include "renderer/line_errors.hpp"
#include "renderer/prepare.hpp"
#include "renderer/stats.hpp"
#include "renderer/visible_set.hpp"

namespace hsr {

struct KnobSpec {
  std::string name;
  std::string help;
  // Allowed values; the first is the default. A numeric knob (below) accepts any number
  // in its range, and its choices are the default followed by values worth sweeping.
  std::vector<std::string> choices;
  struct Range {
    double minimum, maximum;
    bool integer = false;
    bool percent = false;  // also "P%": a percentage of some scene size the help names
  };
  std::optional<Range> range = std::nullopt;
  // The values of the algorithm's "variant" knob this knob applies to; empty: all.
  std::vector<std::string> variants = {};

  bool appliesTo(const std::string& variant) const {
    return variants.empty() || std::find(variants.begin(), variants.end(), variant) != variants.end();
  }
};

using KnobValues = std::map<std::string, std::string>;  // every knob of the algorithm, validated

using KnobSettings = std::vector<std::pair<std::string, std::string>>;  // NAME=VALUE as the user gave them

// A line drawing judged against the exact one: its line error, and where it is wrong
// (renderer/line_errors: lineErrorMap's colours).
struct LineJudgement {
  LineError error;
  std::vector<std::uint8_t> errorMap;
};

struct AlgorithmEntry {
  std::string name;
  // "surface"; "line" for a hidden-line algorithm, judged by the line reference; or
  // "reference" for the exact reference every surface algorithm is judged by.
  std::string kind;
  std::string summary;
  std::vector<KnobSpec> knobs;
  // The counters hsr compare prints for this algorithm, in this order.
  std::vector<std::string> keyCounters;
  // The configurations hsr compare's default study runs (the defaults first), chosen
  // to show what the knobs trade.
  std::vector<KnobSettings> studyConfigurations = {{}};
  // Why the algorithm cannot render the scene at its size with these knobs, or "" when
  // it can; the message names the knob to change when there is one.
  std::function<std::string(const PreparedScene&, const KnobValues&)> refusal = [](const PreparedScene&, const KnobValues&) {
    return std::string();
  };
  // threads: 0 = all cores. A line algorithm's frame is its drawing rasterized.
  std::function<Frame(const PreparedScene&, const KnobValues&, int threads, Stats&)> render;
  // Surface algorithms that can draw just what culling stages kept (algorithms/culling,
  // hsr render --cull): render, on those triangles only. Unset for the others.
  std::function<Frame(const PreparedScene&, const KnobValues&, const VisibleSet&, int threads, Stats&)> renderVisible;
  // Line algorithms: the drawing itself, and how it is judged (by default, the line
  // reference on the drawing's own edges; a drawing of curves, against the exact drawing
  // of the same curves).
  std::function<LineSet(const PreparedScene&, const KnobValues&, int threads, Stats&)> drawLines;
  std::function<LineJudgement(const PreparedScene&, const KnobValues&, const LineSet&, int threads, Stats&)> judgeLines;
};

const std::vector<AlgorithmEntry>& algorithms();

// Throws InputError naming the unknown algorithm (after `where`, the option that gave
// it) and listing the known ones.
const AlgorithmEntry& findAlgorithm(const std::string& name, const std::string& where = "--algo");

// The algorithm's knob of that name, or nullptr.
const KnobSpec* findKnob(const AlgorithmEntry& algorithm, const std::string& name);
const KnobSpec* findKnob(const std::vector<KnobSpec>& knobs, const std::string& name);

// Fills in defaults and checks every setting; throws InputError for an unknown knob, a
// value outside its choices or range, or a knob the chosen variant does not have,
// naming the algorithm, the knob and what is allowed.
KnobValues resolveKnobs(const AlgorithmEntry& algorithm, const KnobSettings& settings, const std::string& where = "--knob");
// The same for any owner of knobs (a culling stage): `owner` names it in the messages.
KnobValues resolveKnobs(const std::string& owner, const std::vector<KnobSpec>& knobs, const KnobSettings& settings,
                        const std::string& where);

// "NAME=VALUE" split at the first '='; throws InputError naming `where` otherwise.
std::pair<std::string, std::string> parseKnobSetting(const std::string& text, const std::string& where);

// A numeric knob's value (checked by resolveKnobs); a percentage is returned as given
// (e.g. 0.5 for "0.5%"), with `percent` set.
struct KnobNumber {
  double value;
  bool percent;
};
KnobNumber knobNumber(const KnobValues& values, const std::string& name);

// The settings that differ from the defaults, as "name=value name=value" ("defaults" if none).
std::string describeKnobs(const AlgorithmEntry& algorithm, const KnobValues& values);

}  // namespace hsr
