#include "algorithms/registry.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "algorithms/appel/appel.hpp"
#include "algorithms/floating_horizon/floating_horizon.hpp"
#include "algorithms/painter/painter.hpp"
#include "algorithms/roberts/roberts.hpp"
#include "algorithms/ray_casting/ray_casting.hpp"
#include "algorithms/zbuffer/zbuffer.hpp"
#include "renderer/error.hpp"
#include "algorithms/floating_horizon/curve_comparison.hpp"
#include "renderer/line_drawing.hpp"
#include "renderer/line_reference.hpp"
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

// The number a knob value spells ("12", "0.25", "1e9", and "0.5%" when allowed), or
// nothing when it spells none or lies outside the range.
std::optional<KnobNumber> parseNumber(const KnobSpec::Range& range, std::string text) {
  const bool percent = range.percent && !text.empty() && text.back() == '%';
  if (percent) text.pop_back();
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  if (value < range.minimum || value > range.maximum || (range.integer && value != std::floor(value))) return std::nullopt;
  return KnobNumber{value, percent};
}

std::string describeRange(const KnobSpec::Range& range) {
  const auto number = [](double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return std::string(text);
  };
  std::string text = std::string(range.integer ? "an integer" : "a number") + " in [" + number(range.minimum) + ", " +
                     number(range.maximum) + "]";
  if (range.percent) text += ", or a percentage P% with P in that range";
  return text;
}

// A scene with transparency needs its surfaces blended back to front; an algorithm that
// keeps only the nearest surface per pixel would print a silently wrong image.
std::string transparencyRefusal(const PreparedScene& scene, const std::string& algorithm) {
  if (!scene.scene().effects.transparency) return "";
  return "the scene declares transparency, which needs the surfaces behind a pixel blended back to front; " + algorithm +
         " keeps only the nearest (use --algo painter or zbuffer)";
}

// The index of a value among a knob's choices, as the enum listed in the same order.
template <typename Enum>
Enum choiceOf(const AlgorithmEntry& entry, const KnobValues& values, const std::string& name) {
  return static_cast<Enum>(choiceIndex(*findKnob(entry, name), values.at(name)));
}

// A surface algorithm that can draw a culled set: render (every triangle) and
// renderVisible (the kept ones) from one run, given the set or nullptr for all.
void setCullableRender(
    AlgorithmEntry& entry,
    const std::function<Frame(const PreparedScene&, const KnobValues&, int, Stats&, const VisibleSet*)>& run) {
  entry.render = [run](const PreparedScene& scene, const KnobValues& values, int threads, Stats& stats) {
    return run(scene, values, threads, stats, nullptr);
  };
  entry.renderVisible = [run](const PreparedScene& scene, const KnobValues& values, const VisibleSet& visible, int threads,
                              Stats& stats) { return run(scene, values, threads, stats, &visible); };
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
      {"depth-test", "off: no depth test, every fragment is drawn and the last triangle drawn at a pixel wins (wrong "
       "wherever surfaces overlap; kept to show what the depth buffer buys)", {"on", "off"}},
  };
  entry.keyCounters = {"screen triangles", "fragments tested", "fragments written"};
  entry.studyConfigurations = {{}, {{"variant", "scanline"}}, {{"depth-format", "unorm24"}}, {{"depth-format", "unorm16"}}};
  const auto typed = [entry](const KnobValues& values) {
    zbuffer::Knobs knobs;
    knobs.variant = choiceOf<zbuffer::Variant>(entry, values, "variant");
    knobs.depthFormat = choiceOf<DepthFormat>(entry, values, "depth-format");
    knobs.depthTest = values.at("depth-test") == "on";
    return knobs;
  };
  setCullableRender(entry, [typed](const PreparedScene& scene, const KnobValues& values, int threads, Stats& stats,
                                    const VisibleSet* visible) { return zbuffer::run(scene, typed(values), threads, stats, visible); });
  return entry;
}

AlgorithmEntry rayCastingEntry() {
  AlgorithmEntry entry;
  entry.name = "ray_casting";
  entry.kind = "surface";
  entry.summary = "a ray per pixel center, nearest surface wins (Appel 1968): through a BVH, naive, or marched in steps";
  entry.knobs = {
      {"variant",
       "bvh: nearest hit through the BVH; naive: every ray against every triangle; march: fixed steps with inside tests",
       {"bvh", "naive", "march"}},
      {"budget", "naive and march refuse a run of more ray-triangle tests (naive) or samples (march) than this",
       {"1e9", "1e10", "1e11"}, KnobSpec::Range{1, 1e15}, {"naive", "march"}},
      {"step", "march: the distance between samples, in world units, or P% of the scene's bounding-box diagonal",
       {"0.5%", "2%", "1%", "0.25%", "0.1%"}, KnobSpec::Range{1e-6, 1e6, false, true}, {"march"}},
      {"grid", "march: occupancy-grid voxels along each mesh's longest side",
       {"64", "16", "32", "128", "256"}, KnobSpec::Range{1, ray_casting::kMaxGrid, true}, {"march"}},
      {"refine", "march: bisection steps back to the surface once a sample is inside",
       {"0", "2", "4", "8"}, KnobSpec::Range{0, 52, true}, {"march"}},
  };
  entry.keyCounters = {"primary rays", "bvh nodes visited", "ray-triangle tests", "march samples", "inside tests",
                       "nearest-triangle voxels searched"};
  entry.studyConfigurations = {{}, {{"variant", "naive"}}, {{"variant", "march"}}, {{"variant", "march"}, {"refine", "6"}}};
  // The variant's choices are listed in the order of ray_casting::Variant.
  const auto typed = [entry](const KnobValues& values) {
    ray_casting::Knobs knobs;
    knobs.variant = choiceOf<ray_casting::Variant>(entry, values, "variant");
    knobs.budget = knobNumber(values, "budget").value;
    const KnobNumber step = knobNumber(values, "step");
    knobs.step = {step.value, step.percent};
    knobs.grid = int(knobNumber(values, "grid").value);
    knobs.refine = int(knobNumber(values, "refine").value);
    return knobs;
  };
  entry.refusal = [typed](const PreparedScene& scene, const KnobValues& values) {
    if (std::string transparency = transparencyRefusal(scene, "ray casting"); !transparency.empty()) return transparency;
    return ray_casting::refusal(scene, typed(values));
  };
  entry.render = [typed](const PreparedScene& scene, const KnobValues& values, int threads, Stats& stats) {
    return ray_casting::run(scene, typed(values), threads, stats);
  };
  return entry;
}

AlgorithmEntry painterEntry() {
  AlgorithmEntry entry;
  entry.name = "painter";
  entry.kind = "surface";
  entry.summary = "far to near with no depth buffer: depth sort, Newell-Newell-Sancha with splitting, or a BSP tree";
  entry.knobs = {
      {"variant",
       "bsp: BSP tree built once, walked far side first; newell: sort, then prove or repair each overlapping pair, "
       "splitting cycles; sort: one depth key per triangle (wrong where triangles overlap in depth)",
       {"bsp", "newell", "sort"}},
      {"key", "sort: the depth that orders a triangle: its centroid's, its nearest corner's or its farthest corner's",
       {"centroid", "nearest", "farthest"}, std::nullopt, {"sort"}},
      {"split-cap", "newell: the most splits; past it, conflicts are painted unresolved and the image is labelled partial",
       {"100000", "0", "10", "1000"}, KnobSpec::Range{0, 1e9, true}, {"newell"}},
      {"split-limit", "bsp: the most splits the build may make (each keeps a polygon, about 100 bytes); past it, it stops "
       "with an error", {"1e7", "1e5", "1e6", "1e8"}, KnobSpec::Range{0, 1e9, true}, {"bsp"}},
      {"budget", "newell: refuses scenes with more triangle pairs n(n-1)/2 than this", {"1e9", "1e10", "1e11"},
       KnobSpec::Range{1, 1e15}, {"newell"}},
      {"build-budget", "bsp: refuses scenes whose tree build is estimated (n log2(n)^2) above this many plane-side tests",
       {"1e8", "1e9", "1e10"}, KnobSpec::Range{1, 1e15}, {"bsp"}},
      {"splitter", "bsp: each node's plane: the first triangle's, a random one's, or the fewest splits among candidates",
       {"least-splits", "first", "random"}, std::nullopt, {"bsp"}},
      {"seed", "bsp: seed of the random choices of random and least-splits", {"1", "2", "3"},
       KnobSpec::Range{0, 9007199254740992.0, true}, {"bsp"}},
      {"candidates", "bsp least-splits: planes tried per node", {"8", "1", "2", "4", "16", "32"},
       KnobSpec::Range{1, 1024, true}, {"bsp"}},
  };
  entry.keyCounters = {"pieces painted", "fragments written", "newell pairs tested", "newell reorders", "newell splits",
                       "bsp nodes", "bsp depth", "bsp splits"};
  entry.studyConfigurations = {{}, {{"variant", "newell"}}, {{"variant", "sort"}}, {{"variant", "sort"}, {"key", "nearest"}}};
  const auto typed = [entry](const KnobValues& values) {
    painter::Knobs knobs;
    knobs.variant = choiceOf<painter::Variant>(entry, values, "variant");
    knobs.key = choiceOf<painter::SortKey>(entry, values, "key");
    knobs.splitCap = knobNumber(values, "split-cap").value;
    knobs.splitLimit = knobNumber(values, "split-limit").value;
    knobs.budget = knobNumber(values, "budget").value;
    knobs.buildBudget = knobNumber(values, "build-budget").value;
    knobs.splitter = choiceOf<painter::Splitter>(entry, values, "splitter");
    knobs.seed = static_cast<std::uint64_t>(knobNumber(values, "seed").value);
    knobs.candidates = static_cast<int>(knobNumber(values, "candidates").value);
    return knobs;
  };
  entry.refusal = [typed](const PreparedScene& scene, const KnobValues& values) { return painter::refusal(scene, typed(values)); };
  setCullableRender(entry, [typed](const PreparedScene& scene, const KnobValues& values, int threads, Stats& stats,
                                    const VisibleSet* visible) { return painter::run(scene, typed(values), threads, stats, visible); });
  return entry;
}

// The knob every line algorithm has: which mesh edges are drawn besides contours and boundaries.
KnobSpec creaseKnob() {
  return {"crease", "feature edges: draw the edges whose two faces' normals differ by more than this many degrees",
          {"30", "0", "10", "60"}, KnobSpec::Range{0, 180}};
}

// A line algorithm's entry draws with `draw`; its image is the drawing rasterized,
// visible lines only.
void setDrawing(AlgorithmEntry& entry, std::function<LineSet(const PreparedScene&, const KnobValues&, int, Stats&)> draw) {
  entry.kind = "line";
  entry.drawLines = draw;
  entry.render = [draw](const PreparedScene& scene, const KnobValues& values, int threads, Stats& stats) {
    return lineSetFrame(draw(scene, values, threads, stats), LineStyle::visible);
  };
  entry.judgeLines = [](const PreparedScene& scene, const KnobValues&, const LineSet& lines, int threads, Stats& stats) {
    const std::vector<EdgeVisibility> exact = traceLineReference(scene, lines.edges, threads, stats);
    return LineJudgement{lineError(edgeVisibility(lines), exact), lineErrorMap(lines, exact)};
  };
}

AlgorithmEntry floatingHorizonEntry() {
  AlgorithmEntry entry;
  entry.name = "floating_horizon";
  entry.summary = "curves of a height field front to back against upper and lower horizons (Williamson 1972, Wright 1973)";
  entry.knobs = {
      {"columns", "horizon resolution: screen columns the horizons are kept for (P%: of the image width)",
       {"100%", "25%", "50%", "200%"}, KnobSpec::Range{1, 65536, true, true}},
      {"samples", "points sampled along each curve (P%: of the image width)", {"100%", "5%", "25%", "200%"},
       KnobSpec::Range{2, 1048576, true, true}},
      {"interpolate", "on: compute where a segment crosses a horizon; off: drop segments whose samples disagree",
       {"on", "off"}},
      {"lower", "on: keep the lower horizon too, so curves seen below everything drawn are visible; off: upper only",
       {"on", "off"}},
      {"mesh", "on: draw the curves of constant x as well as of constant z", {"off", "on"}},
  };
  entry.keyCounters = {"curves", "samples", "horizon crossings", "breaks", "segments dropped"};
  entry.studyConfigurations = {{}, {{"interpolate", "off"}, {"samples", "5%"}}, {{"samples", "5%"}}, {{"lower", "off"}},
                               {{"columns", "25%"}}};
  const auto typed = [](const PreparedScene& scene, const KnobValues& values) {
    const auto widthShare = [&](const std::string& name, int minimum) {
      const KnobNumber number = knobNumber(values, name);
      return std::max(minimum, static_cast<int>(std::lround(number.percent ? number.value / 100 * scene.width() : number.value)));
    };
    floating_horizon::Knobs knobs;
    knobs.columns = widthShare("columns", 1);
    knobs.samples = widthShare("samples", 2);
    knobs.interpolate = values.at("interpolate") == "on";
    knobs.lowerHorizon = values.at("lower") == "on";
    knobs.mesh = values.at("mesh") == "on";
    return knobs;
  };
  entry.refusal = [](const PreparedScene& scene, const KnobValues&) { return floating_horizon::refusal(scene); };
  setDrawing(entry, [typed](const PreparedScene& scene, const KnobValues& values, int, Stats& stats) {
    return floating_horizon::run(scene, typed(scene, values), stats);
  });
  entry.judgeLines = [](const PreparedScene& scene, const KnobValues& values, const LineSet& lines, int threads, Stats& stats) {
    const floating_horizon::ExactDrawing exact = floating_horizon::exactDrawing(scene, values.at("mesh") == "on", threads, stats);
    CurveComparison comparison = compareCurveDrawings(lines, exact.lines, exact.visibility);
    return LineJudgement{comparison.error, std::move(comparison.errorMap)};
  };
  return entry;
}

AlgorithmEntry appelEntry() {
  AlgorithmEntry entry;
  entry.name = "appel";
  entry.summary = "quantitative invisibility: walk the edges of closed meshes, counting the faces in front (Appel 1967)";
  entry.knobs = {
      {"surfaces",
       "closed: count front faces (Appel's QI; needs closed, consistently oriented meshes); any: count every face, "
       "so open, non-manifold and double-sided meshes are drawn too (wrong where surfaces pass through or lie on "
       "each other)",
       {"closed", "any"}},
      {"cell", "side in pixels of the image-plane grid that lists the contour edges each edge may cross",
       {"16", "4", "64", "256"}, KnobSpec::Range{1, 65536}},
      creaseKnob(),
  };
  entry.keyCounters = {"feature edges", "contour edges", "crossings tested", "QI changes", "start-vertex ray casts",
                       "QI mismatches"};
  const auto typed = [entry](const KnobValues& values) {
    appel::Knobs knobs;
    knobs.surfaces = choiceOf<appel::Surfaces>(entry, values, "surfaces");
    knobs.cellPixels = knobNumber(values, "cell").value;
    knobs.creaseDegrees = knobNumber(values, "crease").value;
    return knobs;
  };
  entry.refusal = [typed](const PreparedScene& scene, const KnobValues& values) { return appel::refusal(scene, typed(values)); };
  setDrawing(entry, [typed](const PreparedScene& scene, const KnobValues& values, int, Stats& stats) {
    return appel::run(scene, typed(values), stats);
  });
  return entry;
}

AlgorithmEntry robertsEntry() {
  AlgorithmEntry entry;
  entry.name = "roberts";
  entry.summary = "every edge against every convex body by linear inequalities along the sight lines (Roberts 1963)";
  entry.knobs = {
      {"grid", "on: only the bodies listed in the screen-grid cells an edge crosses are tested; off: every body",
       {"on", "off"}},
      {"cell", "side in pixels of the screen grid's cells", {"32", "8", "128", "512"}, KnobSpec::Range{1, 65536}},
      creaseKnob(),
  };
  entry.keyCounters = {"feature edges", "junction lines", "back-face edges", "edge-body pairs", "body tests", "hidden intervals"};
  const auto typed = [](const KnobValues& values) {
    roberts::Knobs knobs;
    knobs.grid = values.at("grid") == "on";
    knobs.cellPixels = knobNumber(values, "cell").value;
    knobs.creaseDegrees = knobNumber(values, "crease").value;
    return knobs;
  };
  entry.refusal = [](const PreparedScene& scene, const KnobValues&) { return roberts::refusal(scene); };
  setDrawing(entry, [typed](const PreparedScene& scene, const KnobValues& values, int, Stats& stats) {
    return roberts::run(scene, typed(values), stats);
  });
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
  static const std::vector<AlgorithmEntry> all = {referenceEntry(), zbufferEntry(), rayCastingEntry(), painterEntry(), robertsEntry(), appelEntry(),
                                                 floatingHorizonEntry()};
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

const KnobSpec* findKnob(const AlgorithmEntry& algorithm, const std::string& name) { return findKnob(algorithm.knobs, name); }

const KnobSpec* findKnob(const std::vector<KnobSpec>& knobs, const std::string& name) {
  for (const KnobSpec& knob : knobs)
    if (knob.name == name) return &knob;
  return nullptr;
}

KnobValues resolveKnobs(const AlgorithmEntry& algorithm, const KnobSettings& settings, const std::string& where) {
  return resolveKnobs(algorithm.name, algorithm.knobs, settings, where);
}

KnobValues resolveKnobs(const std::string& owner, const std::vector<KnobSpec>& knobs, const KnobSettings& settings,
                        const std::string& where) {
  KnobValues values;
  for (const auto& knob : knobs) values[knob.name] = knob.choices.front();
  for (const auto& [name, value] : settings) {
    const KnobSpec* knob = findKnob(knobs, name);
    if (!knob) {
      std::vector<std::string> names;
      for (const auto& k : knobs) names.push_back(k.name);
      throw InputError(where + " " + name + "=" + value + ": " + owner + " has no knob '" + name + "'; expected one of " +
                       joined(names));
    }
    if (knob->range ? !parseNumber(*knob->range, value) : choiceIndex(*knob, value) == knob->choices.size())
      throw InputError(where + " " + name + "=" + value + ": " + owner + " " + name + " must be " +
                       (knob->range ? describeRange(*knob->range) : "one of " + joined(knob->choices)));
    values[name] = value;
  }
  // A knob of one variant given with another is a mistake, not something to ignore.
  for (const auto& [name, value] : settings) {
    const KnobSpec& knob = *findKnob(knobs, name);
    if (!knob.variants.empty() && !knob.appliesTo(values.at("variant")))
      throw InputError(where + " " + name + "=" + value + ": " + owner + " " + name + " applies only to variant " +
                       joined(knob.variants) + ", not to variant " + values.at("variant"));
  }
  return values;
}

KnobNumber knobNumber(const KnobValues& values, const std::string& name) {
  const std::string& text = values.at(name);
  const bool percent = !text.empty() && text.back() == '%';
  return {std::stod(percent ? text.substr(0, text.size() - 1) : text), percent};
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
