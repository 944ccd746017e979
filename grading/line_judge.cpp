#include "grading/line_judge.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "grading/judge.hpp"
#include "renderer/lines/feature_edges.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/reference/line_reference.hpp"
#include "renderer/scene/intersections.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::grading {
namespace {

constexpr std::array<CauseText, kLineCauses> kLineCauseTexts = {{
    {"drawn though hidden",
     "a stretch of a line of the view that a face hides: its QI is too low there. Does the count go up by one where the "
     "edge passes behind a contour, and is the QI at the walk's starting vertex counted over every front face its "
     "eye ray crosses?"},
    {"hidden though visible",
     "a visible stretch left out: its QI is too high there, or the edge is not drawn at all. Does the count go down "
     "where the edge comes out from behind a contour, and are the corrections at a vertex on a contour applied once?"},
    {"not a line of the view",
     "a segment on none of the view's lines: only contours (between a front and a back face), creases sharper than 30 "
     "degrees, boundaries and the lines where surfaces pass through each other are drawn, not the diagonals of a "
     "flat face or a back face's edges"},
}};

struct Piece {
  dvec2 from, to;
  std::uint32_t edge;
};

// Whether both ends of `piece` lie within kOnLine of the line through `from` whose unit
// normal is `across`.
bool liesOnLine(const Piece& piece, const dvec2& from, const dvec2& across) {
  return std::abs(glm::dot(piece.from - from, across)) <= kOnLine && std::abs(glm::dot(piece.to - from, across)) <= kOnLine;
}

// The stretches of segment from..to (as distances from `from`, in pixels) that no piece
// lying on its line covers.
std::vector<Interval> uncovered(const dvec2& from, const dvec2& to, std::span<const Piece> pieces) {
  const double length = glm::length(to - from);
  if (!(length > 0)) return {};
  const dvec2 along = (to - from) / length, across(-along.y, along.x);
  std::vector<Interval> covered;
  for (const Piece& piece : pieces) {
    if (!liesOnLine(piece, from, across)) continue;
    const double a = glm::dot(piece.from - from, along), b = glm::dot(piece.to - from, along);
    const double begin = std::max(std::min(a, b), 0.0), end = std::min(std::max(a, b), length);
    if (end > begin) covered.push_back({begin, end});
  }
  std::sort(covered.begin(), covered.end(), [](const Interval& p, const Interval& q) { return p.begin < q.begin; });
  std::vector<Interval> gaps;
  double reached = 0;
  for (const Interval& c : covered) {
    if (c.begin > reached) gaps.push_back({reached, c.begin});
    reached = std::max(reached, c.end);
  }
  if (reached < length) gaps.push_back({reached, length});
  return gaps;
}

// The piece under point p, if one lies on the line from..to there; nullptr otherwise.
const Piece* pieceUnder(const dvec2& p, const dvec2& from, const dvec2& to, std::span<const Piece> pieces) {
  const dvec2 along = glm::normalize(to - from), across(-along.y, along.x);
  for (const Piece& piece : pieces) {
    if (!liesOnLine(piece, from, across)) continue;
    const double a = glm::dot(piece.from - p, along), b = glm::dot(piece.to - p, along);
    if (std::min(a, b) <= 0 && std::max(a, b) >= 0) return &piece;
  }
  return nullptr;
}

// Marks the pixels segment from..to passes through, sampled every quarter pixel.
void drawInto(std::vector<std::uint8_t>& rgba, int width, int height, const dvec2& from, const dvec2& to, std::array<std::uint8_t, 4> color) {
  const int samples = 1 + int(std::ceil(4 * glm::length(to - from)));
  for (int k = 0; k <= samples; ++k) {
    const dvec2 p = from + (to - from) * (double(k) / samples);
    const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
    if (x < 0 || y < 0 || x >= width || y >= height) continue;
    std::copy(color.begin(), color.end(), rgba.begin() + (std::ptrdiff_t(y) * width + x) * 4);
  }
}

}  // namespace

const char* lineCauseName(LineCause cause) { return kLineCauseTexts[std::size_t(cause)].name; }
const char* lineCauseAdvice(LineCause cause) { return kLineCauseTexts[std::size_t(cause)].advice; }

std::string readSegments(const std::filesystem::path& file, std::vector<DrawnSegment>& segments) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) return "wrote no drawing at " + file.filename().string();
  std::ifstream in(file);
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    std::istringstream split(line);
    std::vector<std::string> words;
    for (std::string word; split >> word;) words.push_back(word);
    if (words.empty() || words[0][0] == '#') continue;
    const std::string where = file.filename().string() + ":" + std::to_string(number) + ": ";
    std::array<double, 4> v{};
    bool numbers = words.size() == 4;
    for (std::size_t k = 0; numbers && k < 4; ++k) {
      char* end = nullptr;
      v[k] = std::strtod(words[k].c_str(), &end);
      numbers = *end == '\0';
    }
    if (!numbers) return where + "'" + line.substr(0, 60) + "'; expected four numbers, x0 y0 x1 y1 (a visible segment in pixels)";
    if (!std::all_of(v.begin(), v.end(), [](double c) { return std::isfinite(c); }))
      return where + "'" + line.substr(0, 60) + "': a coordinate is not a finite number";
    if (segments.size() == kMostSegments)
      return where + "more than 100,000 segments; expected the visible parts of the view's lines (a few hundred segments on the "
             "shipped scenes)";
    segments.push_back({{v[0], v[1]}, {v[2], v[3]}});
  }
  return "";
}

DrawingJudgement judgeDrawing(const PreparedScene& scene, std::span<const DrawnSegment> drawn, int threads) {
  // The view's lines: feature edges, then the lines where surfaces pass through each other.
  Stats stats;
  const CameraTransform camera = scene.camera();
  std::vector<FeatureEdge> edges = featureEdges(scene, camera, viewFacing(scene, camera, stats), kDefaultCreaseDegrees, stats);
  for (const Junction& junction : surfaceIntersectionsOf(scene, stats).junctions)
    edges.push_back(projectEdge(camera, junction.from, junction.to, EdgeKind::junction));
  const std::vector<EdgeVisibility> truth = traceLineReference(scene, edges, threads, stats);

  // Each edge cut into the reference's visible pieces and the hidden ones between them.
  std::vector<Piece> visible, hidden;
  DrawingJudgement judgement;
  for (std::uint32_t e = 0; e < edges.size(); ++e) {
    double reached = 0;
    for (const Interval& v : truth[e].visible) {
      if (v.begin > reached) hidden.push_back({edges[e].pixelAt(reached), edges[e].pixelAt(v.begin), e});
      visible.push_back({edges[e].pixelAt(v.begin), edges[e].pixelAt(v.end), e});
      judgement.visibleLength += (v.end - v.begin) * truth[e].lengthPixels;
      reached = v.end;
    }
    if (reached < 1) hidden.push_back({edges[e].pixelAt(reached), edges[e].pixelAt(1), e});
  }
  std::vector<Piece> submitted;
  for (const DrawnSegment& segment : drawn) submitted.push_back({segment.from, segment.to, 0});

  const int width = scene.width(), height = scene.height();
  judgement.heatMap.assign(std::size_t(width) * std::size_t(height) * 4, 0);
  for (const Piece& piece : hidden) drawInto(judgement.heatMap, width, height, piece.from, piece.to, {225, 225, 225, 255});
  for (const Piece& piece : visible) drawInto(judgement.heatMap, width, height, piece.from, piece.to, {128, 128, 128, 255});

  std::array<LineCauseLength, kLineCauses> causes{};
  std::array<double, kLineCauses> longest{};
  const auto wrongStretch = [&](LineCause cause, const dvec2& from, const dvec2& to, std::string where) {
    const double length = glm::length(to - from);
    if (length <= kExcusedLength) {
      judgement.excused += length;
      return;
    }
    judgement.wrong += length;
    LineCauseLength& c = causes[std::size_t(cause)];
    c.pixels += length;
    if (length > longest[std::size_t(cause)]) {
      longest[std::size_t(cause)] = length;
      c.at = (from + to) / 2.0;
      char text[96];
      std::snprintf(text, sizeof text, "at (%.1f, %.1f), %.1f px long", c.at.x, c.at.y, length);
      c.first = text + where;
    }
    drawInto(judgement.heatMap, width, height, from, to, {230, 30, 30, 255});
  };
  const auto onEdge = [&](std::uint32_t e) {
    return ", on edge " + std::to_string(e) + " (a " + edgeKindName(edges[e].kind) + ")";
  };

  // Visible in the reference, not drawn.
  for (const Piece& piece : visible)
    for (const Interval& gap : uncovered(piece.from, piece.to, submitted)) {
      const dvec2 along = glm::normalize(piece.to - piece.from);
      wrongStretch(LineCause::hiddenThoughVisible, piece.from + along * gap.begin, piece.from + along * gap.end, onEdge(piece.edge));
    }
  // Drawn, not visible in the reference: on a hidden piece, or on no line at all.
  for (const Piece& segment : submitted)
    for (const Interval& gap : uncovered(segment.from, segment.to, visible)) {
      const dvec2 along = glm::normalize(segment.to - segment.from);
      const dvec2 from = segment.from + along * gap.begin, to = segment.from + along * gap.end;
      const Piece* under = pieceUnder((from + to) / 2.0, segment.from, segment.to, hidden);
      if (under) wrongStretch(LineCause::drawnThoughHidden, from, to, onEdge(under->edge));
      else wrongStretch(LineCause::notALine, from, to, "");
    }

  for (int c = 0; c < kLineCauses; ++c)
    if (causes[std::size_t(c)].pixels > 0) {
      causes[std::size_t(c)].cause = LineCause(c);
      judgement.causes.push_back(causes[std::size_t(c)]);
    }
  std::stable_sort(judgement.causes.begin(), judgement.causes.end(),
                   [](const LineCauseLength& a, const LineCauseLength& b) { return a.pixels > b.pixels; });
  return judgement;
}

}  // namespace hsr::grading
