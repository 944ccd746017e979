#include "pipeline/why.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <regex>
#include <span>
#include <string>
#include <vector>

#include "renderer/lines/line_drawing.hpp"
#include "renderer/steps/steps.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/markup.hpp"

namespace hsr::pipeline {
namespace {

std::string triangleOf(const PreparedScene& scene, std::uint32_t id) {
  return id == conventions::kBackgroundId ? "the background" : scene.triangleName(id - 1);
}

// The triangles of a certified tie: "triangle 3 of "a" and triangle 7 of "b"".
std::string tiedOf(const PreparedScene& scene, const std::vector<std::uint32_t>& tied) {
  std::string text;
  for (std::size_t i = 0; i < tied.size(); ++i)
    text += (i == 0 ? "" : i + 1 == tied.size() ? " and " : ", ") + triangleOf(scene, tied[i]);
  return text;
}

// Why the algorithm's answer differs from the reference's, from the history: the
// reference's triangle lost there (the depth test, a tie kept by drawing order), or was
// shown and then replaced, or was culled, or never reached the pixel (the rasterizer's
// coverage rule, or clipping, left it out).
std::string verdictOf(const PreparedScene& scene, const PixelAnswer& answer) {
  const std::string expected = triangleOf(scene, answer.reference.id);
  if (answer.shown == answer.reference.id) return "agrees with the exact reference";
  if (answer.reference.ambiguous)
    return "a certified tie: " + tiedOf(scene, answer.tied) + " are exactly nearest here, so any of them is right (the reference names " +
           expected + ")";
  const std::string differs = "differs: the reference shows " + expected + ", ";
  if (answer.culled) return differs + "which the culling stage " + answer.culledBy + " removed before the algorithm ran";
  const auto& history = answer.history;
  std::size_t met = history.size();  // the reference's triangle's last event here (a window's is no triangle's)
  for (std::size_t i = 0; i < history.size(); ++i)
    if (history[i].subject.empty() && history[i].id == answer.reference.id) met = i;
  if (met == history.size() && answer.reference.id == conventions::kBackgroundId) {
    // Nothing lies along the ray: the event that last gave the pixel a triangle is the one at fault.
    std::size_t filled = history.size();
    for (std::size_t i = 0; i < history.size(); ++i)
      if (history[i].subject.empty() && history[i].shown) filled = i;
    if (filled == history.size()) return differs + "where nothing lies between the near and far planes";
    return differs + "where nothing lies along the ray, but " + triangleOf(scene, history[filled].id) + " was shown (event " +
           std::to_string(filled + 1) + ": " + history[filled].outcome + ": " + history[filled].detail + ")";
  }
  if (met == history.size())
    return differs + "which the algorithm never met at this pixel (the rasterizer did not cover the pixel's center with it, it was clipped, or no ray tested it)";
  const auto event = [](std::size_t i) { return "event " + std::to_string(i + 1); };
  if (!history[met].shown) return differs + "not shown after " + event(met) + ": " + history[met].outcome + ": " + history[met].detail;
  std::size_t replaced = met + 1;
  while (replaced < history.size() && !history[replaced].shown) ++replaced;
  HSR_CHECK(replaced < history.size());  // something replaced it, or the pixel would show it
  return differs + "which was shown (" + event(met) + ") and then replaced by " + triangleOf(scene, history[replaced].id) + " (" +
         event(replaced) + ": " + history[replaced].outcome + ")";
}

// The culling stages' fate for the reference's triangle, one event a stage in order,
// until one removes it: what the stage was given of the triangle's object and kept of
// it, and what the stage's own test found for the object, where it says.
// Empty when there are no stages or the reference shows the background.
std::vector<PixelEvent> cullingEvents(const PreparedScene& scene, const culling::Pipeline& stages, culling::CullingWitness& culled,
                                      std::uint32_t id, std::string& culledBy) {
  std::vector<PixelEvent> events;
  if (id == conventions::kBackgroundId) return events;
  const Instance& object = scene.instanceOf(id - 1);
  const auto instance = std::uint32_t(&object - scene.instances().data());
  const std::vector<VisibleSet>& keptByStage = culled.keptByStage;
  const auto ofObject = [&](const VisibleSet& set) {
    const auto first = std::lower_bound(set.triangles.begin(), set.triangles.end(), object.firstTriangle);
    return std::lower_bound(first, set.triangles.end(), object.firstTriangle + object.triangleCount) - first;
  };
  std::ptrdiff_t given = object.triangleCount;
  for (std::size_t s = 0; s < stages.size(); ++s) {
    const VisibleSet& kept = keptByStage[s];
    const bool keeps = std::binary_search(kept.triangles.begin(), kept.triangles.end(), id - 1);
    const std::ptrdiff_t keptOfObject = ofObject(kept);
    // The variant's own test, in its line of help (hsr list), else the stage's summary.
    const KnobSpec& variants = stages[s].stage->variantKnob();
    const auto variant = std::find(variants.choices.begin(), variants.choices.end(), stages[s].variant());
    const std::size_t which = std::size_t(variant - variants.choices.begin());
    const std::string test = which < variants.choiceHelp.size() ? variants.choiceHelp[which] : stages[s].stage->summary;
    // What the test found: for the triangle, where the stage tests triangles, else for its object.
    const std::string* forTriangle = culled.byStage[s].aboutTriangle(id - 1);
    const std::string* forObject = culled.byStage[s].about(instance);
    const std::string found = forTriangle && !forTriangle->empty() ? "; for the triangle the test found " + *forTriangle
                              : forObject && !forObject->empty()   ? "; the test found " + *forObject
                                                                   : "";
    events.push_back({id, keeps ? "kept the reference's triangle" : "removed the reference's triangle; its test: " + test,
                      "of its object's " + std::to_string(given) + " triangles given to the stage, it kept " + std::to_string(keptOfObject) + found,
                      std::numeric_limits<double>::quiet_NaN(), false, "culling stage " + stages[s].name()});
    if (!keeps) {
      culledBy = stages[s].name();
      break;
    }
    given = keptOfObject;
  }
  return events;
}

std::string jsonTriangle(std::uint32_t id) { return id == conventions::kBackgroundId ? "null" : std::to_string(id - 1); }
// The algorithm's decisions about what is not a triangle (AlgorithmEntry::whyDecisions), as JSON strings.
std::string decisionsJson(const Configuration& configuration) {
  std::string json;
  for (const std::string& decision : configuration.algorithm->whyDecisions) json += (json.empty() ? "" : ", ") + jsonString(decision);
  return json;
}

// The triangles of a certified tie (or the one winner) as JSON objects: each one's index and name.
std::string tiedJson(const PreparedScene& scene, const std::vector<std::uint32_t>& tied) {
  std::string json;
  for (std::size_t i = 0; i < tied.size(); ++i)
    json += std::string(i ? ", " : "") + "{\"triangle\": " + jsonTriangle(tied[i]) + ", \"name\": " + jsonString(triangleOf(scene, tied[i])) + "}";
  return json;
}

}  // namespace

void checkAnswersWhyAlongEdges(const AlgorithmEntry& algorithm) {
  if (algorithm.drawLinesWatchingEdge) return;
  std::string names;
  for (const AlgorithmEntry& entry : algorithms())
    if (entry.drawLinesWatchingEdge) names += (names.empty() ? "" : ", ") + entry.name;
  if (algorithm.kind != AlgorithmKind::line)
    throw InputError("--edge: " + algorithm.name + " draws no edges; expected --pixel X,Y, or --edge with --algo " + names);
  throw InputError("--algo " + algorithm.name + ": hsr why --edge follows the loops of " + names + " so far; expected --algo " + names);
}

void checkAnswersWhy(const AlgorithmEntry& algorithm) {
  if (algorithm.answersWhy) return;
  std::string names;
  for (const AlgorithmEntry& entry : algorithms())
    if (entry.answersWhy) names += (names.empty() ? "" : ", ") + entry.name;
  if (algorithm.drawLinesWatchingEdge)
    throw InputError("--algo " + algorithm.name + ": a line algorithm answers along an edge; expected --edge N or --edge X,Y (--pixel asks " +
                     names + ")");
  throw InputError("--algo " + algorithm.name + ": hsr why follows the loops of " + names + " so far; expected one of those");
}

PixelWitness::Pixel pixelOf(const std::string& text, int width, int height) {
  std::smatch match;
  if (!std::regex_match(text, match, std::regex(R"(\s*(\d{1,9})\s*,\s*(\d{1,9})\s*)")))
    throw InputError("--pixel " + text + ": expected X,Y (a column and a row counted from the top left, e.g. 640,360)");
  const long long x = std::stoll(match[1]), y = std::stoll(match[2]);
  if (x >= width || y >= height)
    throw InputError("--pixel " + text + ": outside the " + std::to_string(width) + "x" + std::to_string(height) + " image; expected X in [0, " +
                     std::to_string(width - 1) + "] and Y in [0, " + std::to_string(height - 1) + "]");
  return {int(x), int(y)};
}

namespace {

// The edge "N" or nearest to pixel "X,Y" names, among the drawing's edges.
std::uint32_t edgeAsked(const std::string& text, const LineSet& lines, double& pixelsAway) {
  std::smatch match;
  const std::string count = std::to_string(lines.edges.size());
  if (std::regex_match(text, match, std::regex(R"(\s*(\d{1,9})\s*)"))) {
    const long long edge = std::stoll(match[1]);
    if (edge >= static_cast<long long>(lines.edges.size()))
      throw InputError("--edge " + text + ": the drawing has " + count + " edges; expected an edge number in [0, " +
                       std::to_string(lines.edges.size() - 1) + "] or a pixel X,Y near one");
    pixelsAway = -1;
    return static_cast<std::uint32_t>(edge);
  }
  if (!std::regex_match(text, match, std::regex(R"(\s*(\d{1,9})\s*,\s*(\d{1,9})\s*)")))
    throw InputError("--edge " + text + ": expected an edge number, or X,Y for the edge passing nearest that pixel");
  const dvec2 center(conventions::pixelCenter(int(std::stoll(match[1]))), conventions::pixelCenter(int(std::stoll(match[2]))));
  constexpr double kNearEnough = 3;  // pixels
  std::uint32_t nearest = 0;
  pixelsAway = std::numeric_limits<double>::infinity();
  for (std::uint32_t e = 0; e < lines.edges.size(); ++e) {
    const FeatureEdge& edge = lines.edges[e];
    const dvec2 along = edge.pixelTo - edge.pixelFrom;
    const double squared = glm::dot(along, along);
    const double u = squared > 0 ? std::clamp(glm::dot(center - edge.pixelFrom, along) / squared, 0.0, 1.0) : 0.0;
    const double away = glm::length(center - edge.pixelAt(u));
    if (away < pixelsAway) nearest = e, pixelsAway = away;
  }
  if (!(pixelsAway <= kNearEnough)) {
    char away[64];
    std::snprintf(away, sizeof away, "%.3g", pixelsAway);
    throw InputError("--edge " + text + ": no edge of the drawing passes within 3 pixels of that pixel's center" +
                     (lines.edges.empty() ? std::string(" (it has none)") : std::string(" (the nearest is ") + away + " pixels away)") +
                     "; expected a pixel on a drawn edge, or an edge number");
  }
  return nearest;
}

// Up to this many pixels of an edge in dispute is the rounding of an algorithm's
// arithmetic and its stated tolerances (docs/robustness.md), not a difference of method:
// the precision hsr writes a drawing to (SVG coordinates to 0.001 pixel).
constexpr double kRoundingPixels = 1e-3;

}  // namespace

EdgeAnswer explainEdge(const PreparedScene& scene, const Configuration& configuration, const std::string& edgeText, int threads,
                       Stats& stats) {
  const AlgorithmEntry& algorithm = *configuration.algorithm;
  checkAnswersWhyAlongEdges(algorithm);
  EdgeAnswer answer;
  Stats findingStats;
  const LineSet found = algorithm.drawLines(scene, configuration.knobs, threads, findingStats, nullptr);
  EdgeWitness witness;
  witness.edge = edgeAsked(edgeText, found, answer.pixelsAway);
  const LineSet lines = algorithm.drawLinesWatchingEdge(scene, configuration.knobs, stats, witness);
  answer.edge = witness.edge;
  answer.drawn = lines.edges[answer.edge];
  answer.walk = std::move(witness.events);
  for (const LineSegment& segment : lines.segments)
    if (segment.edge == answer.edge) answer.pieces.push_back(segment);
  const LineJudgement judged = algorithm.judgeLines(scene, configuration.knobs, lines, threads, stats);
  const EdgeVisibility exact = algorithm.exactAlongEdge ? algorithm.exactAlongEdge(lines, answer.edge, judged.exact)
                                                        : edgeVisibility(judged.exact)[answer.edge];
  const EdgeVisibility mine = edgeVisibility(lines)[answer.edge];
  // Where it sees the edge, leaving out slivers no longer than that rounding (where the
  // edge grazes a face at a corner).
  for (const Interval& visible : exact.visible)
    if ((visible.end - visible.begin) * exact.lengthPixels > kRoundingPixels) answer.referenceVisible.push_back(visible);
  // The line error (renderer/reference/metrics.hpp) of this one edge: drawn but hidden, and hidden but visible.
  const LineError error = lineError(std::span(&mine, 1), std::span(&exact, 1));
  answer.differingPixels = error.wronglyDrawn + error.wronglyHidden;
  char text[160];
  std::snprintf(text, sizeof text, "differs: it and the exact line reference disagree on %.3g of the edge's %.3g pixels",
                answer.differingPixels, exact.lengthPixels);
  answer.agrees = answer.differingPixels <= kRoundingPixels;
  answer.verdict = answer.differingPixels == 0 ? "agrees with the exact line reference"
                   : answer.differingPixels <= kRoundingPixels
                       ? "agrees with the exact line reference within 0.001 pixel, the precision a drawing is written to: they differ on " +
                             whyNumber(answer.differingPixels) + " pixels of its length (the algorithm's tolerances, listed in docs/robustness.md, move the ends of its pieces)"
                       : text;
  return answer;
}

std::vector<PixelAnswer> explainPixels(const PreparedScene& scene, const Configuration& configuration,
                                       const std::vector<PixelWitness::Pixel>& pixels, int threads, Stats& stats,
                                       StepAsked* step) {
  PixelWitness witness(pixels, scene.width());
  // The exact reference first: the objects its triangles belong to are those the culling
  // stages are asked about.
  Stats referenceStats;
  const SurfaceReference reference(scene, referenceStats);
  const CameraTransform& camera = scene.camera();
  std::vector<PixelAnswer> answers(witness.count());
  culling::CullingWitness culled;
  for (std::size_t asked = 0; asked < witness.count(); ++asked) {
    PixelAnswer& answer = answers[asked];
    answer.pixel = witness.pixel(asked);
    SurfaceReference::Counters counters;
    answer.reference = reference.trace(
        camera, camera.rayThroughPixel(conventions::pixelCenter(answer.pixel.x), conventions::pixelCenter(answer.pixel.y)), counters,
        &answer.tied);
    if (answer.reference.id != conventions::kBackgroundId) {
      culled.instances.push_back(std::uint32_t(&scene.instanceOf(answer.reference.id - 1) - scene.instances().data()));
      culled.triangles.push_back(answer.reference.id - 1);
    }
  }
  for (std::vector<std::uint32_t>* asked : {&culled.instances, &culled.triangles}) {
    std::sort(asked->begin(), asked->end());
    asked->erase(std::unique(asked->begin(), asked->end()), asked->end());
  }
  Visibility visibility;
  // With a step asked about: each step's mark, the events each pixel's history held when
  // it was recorded (on one thread, so that no loop adds to a history meanwhile).
  std::vector<std::vector<std::size_t>> marks;
  const auto mark = [&](const std::string& caption) {
    if (marks.size() + 1 == step->number) step->caption = caption;
    std::vector<std::size_t>& counts = marks.emplace_back();
    for (std::size_t asked = 0; asked < witness.count(); ++asked) counts.push_back(witness.history(asked).size());
  };
  std::optional<StepRecorder> steps;
  if (step) {
    steps.emplace(step->every, [&](const Step& recorded) { mark(recorded.caption); });
    threads = 1;
  }
  const VisibleSet kept =
      renderVisibility(scene, configuration, threads, stats, visibility, nullptr, &witness, &culled, steps ? &*steps : nullptr);
  if (step) {
    mark(kFinishedImageStep);  // the last step hsr render --steps records: the finished image, every event behind it
    step->recorded = marks.size();
    if (step->number < 1 || step->number > marks.size())
      throw InputError("--step " + std::to_string(step->number) + ": " + configuration.algorithm->name + " records " +
                       std::to_string(marks.size()) + " steps here (as hsr render --steps numbers them, with the same size, knobs and --every); expected 1 to " +
                       std::to_string(marks.size()));
  }
  for (std::size_t asked = 0; asked < witness.count(); ++asked) {
    PixelAnswer& answer = answers[asked];
    const std::size_t at = std::size_t(answer.pixel.y) * std::size_t(scene.width()) + std::size_t(answer.pixel.x);
    answer.shown = visibility.frame.ids[at];
    answer.distance = visibility.frame.distances(&stats)[at];
    answer.culled = answer.reference.id != conventions::kBackgroundId &&
                    !std::binary_search(kept.triangles.begin(), kept.triangles.end(), answer.reference.id - 1);
    // The culling stages ran first: their fate for the reference's triangle leads the history.
    answer.history = cullingEvents(scene, configuration.culling, culled, answer.reference.id, answer.culledBy);
    const std::vector<PixelEvent>& loop = witness.history(asked);
    answer.eventsByStep = answer.history.size() + (step ? marks[step->number - 1][asked] : loop.size());
    answer.history.insert(answer.history.end(), loop.begin(), loop.end());
    answer.agrees = answer.shown == answer.reference.id || answer.reference.ambiguous;
    answer.verdict = verdictOf(scene, answer);
  }
  return answers;
}

std::string whyText(const PreparedScene& scene, const std::string& sceneName, const Configuration& configuration,
                    const std::vector<PixelAnswer>& answers, const StepAsked* step) {
  std::string text = "hsr why: " + sceneName + " at " + std::to_string(scene.width()) + "x" + std::to_string(scene.height()) +
                     " with " + configuration.algorithm->name + " (" + configuration.knobs.described() + ")" +
                     (configuration.culling.empty() ? "" : " after culling") + "\n";
  const std::string stepName = step ? "step " + std::to_string(step->number) : "";
  if (step) text += "up to " + stepName + " of " + std::to_string(step->recorded) + ": " + step->caption + "\n";
  for (const PixelAnswer& answer : answers) {
    const std::size_t count = step ? answer.eventsByStep : answer.history.size();
    text += "\npixel (" + std::to_string(answer.pixel.x) + ", " + std::to_string(answer.pixel.y) + "): " + std::to_string(count) +
            (count == 1 ? " event" : " events") + (step ? " by " + stepName + " (of " + std::to_string(answer.history.size()) + " in all)" : "") +
            (configuration.culling.empty() ? ", in the order the algorithm's loop met them\n"
                                           : ", in the order they happened: the culling stages', then the algorithm's loop's\n");
    for (std::size_t i = 0; i < count; ++i) {
      const PixelEvent& event = answer.history[i];
      text += "  " + std::to_string(i + 1) + ". " + (event.subject.empty() ? triangleOf(scene, event.id) : event.subject) + ": " + event.outcome +
              "\n     " + event.detail +
              (std::isnan(event.distance) ? "" : "; distance " + whyNumber(event.distance)) + "\n";
    }
    if (step) {
      std::uint32_t then = conventions::kBackgroundId;  // what the pixel showed by the step: the last event that showed one
      for (std::size_t i = 0; i < count; ++i)
        if (answer.history[i].shown) then = answer.history[i].id;
      const std::size_t after = answer.history.size() - count;
      text += "  by " + stepName + " it shows " + triangleOf(scene, then) + "; " + std::to_string(after) +
              (after == 1 ? " event follows\n" : " events follow\n");
    }
    text += std::string(step ? "  in the end it shows " : "  shows ") + triangleOf(scene, answer.shown) +
            (answer.shown == conventions::kBackgroundId ? "" : " at distance " + whyNumber(answer.distance)) + "\n";
    const ReferenceHit& hit = answer.reference;
    text += "  the exact reference: " + triangleOf(scene, hit.id) +
            (hit.id == conventions::kBackgroundId ? "" : " at distance " + whyNumber(hit.distance)) + ", decided " +
            (hit.usedExact ? "with exact arithmetic (floating point could not)" : "in floating point within its error bounds") +
            (hit.ambiguous ? "; a certified tie of " + tiedOf(scene, answer.tied) : "") + "\n";
    text += "  => " + answer.verdict + "\n";
  }
  return text;
}

namespace {

std::string intervalsText(const std::vector<Interval>& intervals) {
  if (intervals.empty()) return "nowhere";
  std::string text;
  for (const Interval& interval : intervals) text += (text.empty() ? "" : ", ") + whyNumber(interval.begin) + " to " + whyNumber(interval.end);
  return text;
}

std::string edgeTitle(const PreparedScene& scene, const EdgeAnswer& answer) {
  const std::string named = edgeNamesOf(scene)(answer.drawn);
  char ends[160];
  std::snprintf(ends, sizeof ends, "from (%.6g, %.6g) to (%.6g, %.6g) in pixels", answer.drawn.pixelFrom.x, answer.drawn.pixelFrom.y,
                answer.drawn.pixelTo.x, answer.drawn.pixelTo.y);
  return "edge " + std::to_string(answer.edge) + (named.empty() ? "" : ", the " + named) + ", " + ends;
}

}  // namespace

std::string edgeText(const PreparedScene& scene, const std::string& sceneName, const Configuration& configuration, const EdgeAnswer& answer) {
  std::string text = "hsr why: " + sceneName + " at " + std::to_string(scene.width()) + "x" + std::to_string(scene.height()) + " with " +
                     configuration.algorithm->name + " (" + configuration.knobs.described() + ")\n\n" + edgeTitle(scene, answer) +
                     (answer.pixelsAway >= 0 ? " (" + whyNumber(answer.pixelsAway) + " pixels from the pixel's center)" : "") + "\n" +
                     "  " + std::to_string(answer.walk.size()) + (answer.walk.size() == 1 ? " event" : " events") +
                     ", in the order the algorithm met them (u: 0 at its start, 1 at its end)\n";
  for (std::size_t i = 0; i < answer.walk.size(); ++i) {
    const EdgeEvent& event = answer.walk[i];
    text += "  " + std::to_string(i + 1) + ". " + (std::isnan(event.u) ? "" : "at u = " + whyNumber(event.u) + ": ") +
            (event.subject.empty() ? "" : event.subject + ": ") + event.outcome + "\n     " + event.detail + "\n";
  }
  text += "  its pieces:";
  for (std::size_t i = 0; i < answer.pieces.size(); ++i) {
    const LineSegment& piece = answer.pieces[i];
    text += std::string(i ? "; " : " ") + whyNumber(piece.begin) + " to " + whyNumber(piece.end) +
            (piece.qi == LineSegment::kHidden ? " hidden" : " QI " + std::to_string(piece.qi) + (piece.visible() ? " (visible)" : ""));
  }
  text += "\n  the exact line reference: visible " + intervalsText(answer.referenceVisible) + "\n  => " + answer.verdict + "\n";
  return text;
}

std::string edgeJson(const PreparedScene& scene, const std::string& sceneName, const Configuration& configuration, const EdgeAnswer& answer) {
  std::string json = "{\"scene\": " + jsonString(sceneName) + ", \"algorithm\": " + jsonString(configuration.algorithm->name) +
                     ", \"knobs\": " + jsonString(configuration.knobs.described()) + ", \"edge\": " + std::to_string(answer.edge) +
                     ", \"name\": " + jsonString(edgeTitle(scene, answer)) + ", \"from\": [" + jsonNumber(answer.drawn.pixelFrom.x) + ", " +
                     jsonNumber(answer.drawn.pixelFrom.y) + "], \"to\": [" + jsonNumber(answer.drawn.pixelTo.x) + ", " +
                     jsonNumber(answer.drawn.pixelTo.y) + "]" +
                     ", \"pixels_away\": " + (answer.pixelsAway >= 0 ? jsonNumber(answer.pixelsAway) : "null") +
                     ", \"decisions\": [" + decisionsJson(configuration) + "], \"walk\": [";
  for (std::size_t i = 0; i < answer.walk.size(); ++i)
    json += std::string(i ? ", " : "") + "\n  {\"u\": " + jsonNumber(answer.walk[i].u) + ", \"change\": " +
            std::to_string(answer.walk[i].change) + ", \"subject\": " + jsonString(answer.walk[i].subject) +
            ", \"outcome\": " + jsonString(answer.walk[i].outcome) + ", \"detail\": " + jsonString(answer.walk[i].detail) + "}";
  json += "],\n \"pieces\": [";
  for (std::size_t i = 0; i < answer.pieces.size(); ++i)
    json += std::string(i ? ", " : "") + "{\"begin\": " + jsonNumber(answer.pieces[i].begin) + ", \"end\": " + jsonNumber(answer.pieces[i].end) +
            ", \"qi\": " + std::to_string(answer.pieces[i].qi) + "}";
  json += "],\n \"reference_visible\": [";
  for (std::size_t i = 0; i < answer.referenceVisible.size(); ++i)
    json += std::string(i ? ", " : "") + "[" + jsonNumber(answer.referenceVisible[i].begin) + ", " + jsonNumber(answer.referenceVisible[i].end) + "]";
  return json + "],\n \"differing_pixels\": " + jsonNumber(answer.differingPixels) + ", \"agrees\": " +
         (answer.agrees ? "true" : "false") + ", \"verdict\": " + jsonString(answer.verdict) + "}\n";
}

std::string whyJson(const PreparedScene& scene, const std::string& sceneName, const Configuration& configuration,
                    const std::vector<PixelAnswer>& answers, const StepAsked* step) {
  std::string json = "{\"scene\": " + jsonString(sceneName) + ", \"algorithm\": " + jsonString(configuration.algorithm->name) +
                     ", \"knobs\": " + jsonString(configuration.knobs.described()) + ", \"width\": " + std::to_string(scene.width()) +
                     ", \"height\": " + std::to_string(scene.height()) + ", \"decisions\": [" + decisionsJson(configuration) + "], \"paints_in_order\": " +
                     (configuration.algorithm->order ? "true" : "false") + ", \"step\": " +
                     (step ? "{\"number\": " + std::to_string(step->number) + ", \"of\": " + std::to_string(step->recorded) +
                                 ", \"caption\": " + jsonString(step->caption) + "}"
                           : "null") +
                     ", \"pixels\": [";
  for (std::size_t p = 0; p < answers.size(); ++p) {
    const PixelAnswer& answer = answers[p];
    json += std::string(p ? ", " : "") + "\n  {\"x\": " + std::to_string(answer.pixel.x) + ", \"y\": " + std::to_string(answer.pixel.y) +
            ", \"events_by_step\": " + std::to_string(answer.eventsByStep) + ", \"history\": [";
    for (std::size_t i = 0; i < answer.history.size(); ++i) {
      const PixelEvent& event = answer.history[i];
      const bool aboutTriangle = event.subject.empty();
      json += std::string(i ? ", " : "") + "\n    {\"triangle\": " + (aboutTriangle ? jsonTriangle(event.id) : "null") +
              ", \"name\": " + jsonString(aboutTriangle ? triangleOf(scene, event.id) : event.subject) +
              ", \"outcome\": " + jsonString(event.outcome) + ", \"detail\": " + jsonString(event.detail) +
              ", \"distance\": " + jsonNumber(event.distance) + ", \"shown\": " + (event.shown ? "true" : "false") + "}";
    }
    const ReferenceHit& hit = answer.reference;
    json += "],\n   \"shows\": {\"triangle\": " + jsonTriangle(answer.shown) + ", \"name\": " + jsonString(triangleOf(scene, answer.shown)) +
            ", \"distance\": " + jsonNumber(answer.distance) + "},\n   \"reference\": {\"triangle\": " + jsonTriangle(hit.id) +
            ", \"name\": " + jsonString(triangleOf(scene, hit.id)) + ", \"distance\": " + jsonNumber(hit.distance) +
            ", \"ambiguous\": " + (hit.ambiguous ? "true" : "false") + ", \"tied\": [" + tiedJson(scene, answer.tied) +
            "], \"exact_fallback\": " + (hit.usedExact ? "true" : "false") + "},\n   \"culled\": " + (answer.culled ? "true" : "false") + ", \"agrees\": " + (answer.agrees ? "true" : "false") +
            ", \"verdict\": " + jsonString(answer.verdict) + "}";
  }
  return json + "\n]}\n";
}

}  // namespace hsr::pipeline
