#include "algorithms/floating_horizon/curve_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "renderer/lines/line_drawing.hpp"
#include "renderer/lines/line_errors.hpp"
#include "renderer/util/error.hpp"

namespace hsr {
namespace {

bool contains(const std::vector<Interval>& sorted, double u) {
  const auto after = std::upper_bound(sorted.begin(), sorted.end(), u, [](double x, const Interval& i) { return x < i.begin; });
  return after != sorted.begin() && u <= std::prev(after)->end;
}

// A drawing of curves looked up by curve and running coordinate.
class CurveLookup {
 public:
  CurveLookup(const LineSet& lines, std::vector<EdgeVisibility> visibility, std::size_t curves)
      : lines_(lines), visibility_(std::move(visibility)), byCurve_(curves) {
    HSR_CHECK(lines.curvePlaces.size() == lines.edges.size());
    for (std::uint32_t e = 0; e < lines.edges.size(); ++e) byCurve_.at(lines.curvePlaces[e].curve).push_back(e);
    for (auto& edges : byCurve_)
      std::sort(edges.begin(), edges.end(), [&](auto a, auto b) { return lines.curvePlaces[a].from < lines.curvePlaces[b].from; });
  }

  const LineSet& lines() const { return lines_; }
  const EdgeVisibility& visibility(std::size_t edge) const { return visibility_[edge]; }

  // The point of the curve at that coordinate, if the drawing has it, and whether it is drawn visible.
  struct Point {
    bool visible = false;
    dvec2 pixel{0};
  };
  std::optional<Point> at(std::uint32_t curve, double coordinate) const {
    const std::vector<std::uint32_t>& edges = byCurve_[curve];
    const auto after = std::upper_bound(edges.begin(), edges.end(), coordinate,
                                        [&](double c, std::uint32_t e) { return c < lines_.curvePlaces[e].from; });
    if (after == edges.begin()) return std::nullopt;
    const std::uint32_t e = *std::prev(after);
    const CurvePlace& place = lines_.curvePlaces[e];
    if (coordinate > place.to) return std::nullopt;
    const double u = lines_.edges[e].projectedParameter((coordinate - place.from) / (place.to - place.from));
    return Point{contains(visibility_[e].visible, u), lines_.edges[e].pixelAt(u)};
  }

 private:
  const LineSet& lines_;
  std::vector<EdgeVisibility> visibility_;
  std::vector<std::vector<std::uint32_t>> byCurve_;
};

// Walks edge e of `walked` in steps of at most a quarter pixel. For each step: its ends
// in u and in pixels, its length, whether `walked` shows it, and whether `other` shows the
// same curve within kCurveTolerancePixels at the same coordinate.
template <typename Visit>
void walkEdge(const CurveLookup& walked, const CurveLookup& other, std::size_t e, Visit&& visit) {
  const FeatureEdge& edge = walked.lines().edges[e];
  const CurvePlace& place = walked.lines().curvePlaces[e];
  const int steps = std::max(1, static_cast<int>(std::ceil(edge.lengthPixels() / 0.25)));
  for (int i = 0; i < steps; ++i) {
    const double u0 = double(i) / steps, u1 = double(i + 1) / steps, middle = 0.5 * (u0 + u1);
    const bool shown = contains(walked.visibility(e).visible, middle);
    const double coordinate = place.from + edge.edgeParameter(middle) * (place.to - place.from);
    const auto there = other.at(place.curve, coordinate);
    const bool matched = there && there->visible && glm::length(there->pixel - edge.pixelAt(middle)) <= kCurveTolerancePixels;
    visit(Interval{u0, u1}, edge.pixelAt(u0), edge.pixelAt(u1), (u1 - u0) * edge.lengthPixels(), shown, matched);
  }
}

// The same for every edge of `walked`, without the ends in u.
template <typename Visit>
void walkCurves(const CurveLookup& walked, const CurveLookup& other, Visit&& visit) {
  for (std::size_t e = 0; e < walked.lines().edges.size(); ++e)
    walkEdge(walked, other, e, [&](Interval, dvec2 a, dvec2 b, double length, bool shown, bool matched) { visit(a, b, length, shown, matched); });
}

std::size_t curveCount(const LineSet& drawn, const LineSet& exact) {
  std::size_t curves = 0;
  for (const LineSet* lines : {&drawn, &exact})
    for (const CurvePlace& place : lines->curvePlaces) curves = std::max<std::size_t>(curves, place.curve + 1);
  return curves;
}

}  // namespace

CurveComparison compareCurveDrawings(const LineSet& drawn, const LineSet& exact, std::span<const EdgeVisibility> exactVisibility) {
  HSR_CHECK(exactVisibility.size() == exact.edges.size());
  const std::size_t curves = curveCount(drawn, exact);
  const CurveLookup drawnCurves(drawn, edgeVisibility(drawn), curves);
  const CurveLookup exactCurves(exact, {exactVisibility.begin(), exactVisibility.end()}, curves);
  CurveComparison result;
  LineErrorPicture picture(exact.width, exact.height);
  walkCurves(exactCurves, drawnCurves, [&](dvec2 a, dvec2 b, double, bool shown, bool) {
    if (shown) picture.line(a, b, kLineWidthPixels, kExactLineGrey);
  });
  LineError& error = result.error;
  walkCurves(exactCurves, drawnCurves, [&](dvec2 a, dvec2 b, double length, bool shown, bool matched) {
    if (!shown) return;
    error.visibleLength += length;
    if (!matched) error.wronglyHidden += length, picture.line(a, b, kErrorLineWidth, kWronglyHiddenBlue);
  });
  walkCurves(drawnCurves, exactCurves, [&](dvec2 a, dvec2 b, double length, bool shown, bool matched) {
    if (shown && !matched) error.wronglyDrawn += length, picture.line(a, b, kErrorLineWidth, kWronglyDrawnRed);
  });
  error.error = error.visibleLength > 0 ? (error.wronglyDrawn + error.wronglyHidden) / error.visibleLength : 0;
  result.errorMap = picture.take();
  return result;
}

EdgeVisibility exactAlongDrawnEdge(const LineSet& drawn, std::uint32_t edge, const LineSet& exact,
                                   std::span<const EdgeVisibility> exactVisibility) {
  HSR_CHECK(exactVisibility.size() == exact.edges.size() && edge < drawn.edges.size());
  const std::size_t curves = curveCount(drawn, exact);
  const CurveLookup drawnCurves(drawn, edgeVisibility(drawn), curves);
  const CurveLookup exactCurves(exact, {exactVisibility.begin(), exactVisibility.end()}, curves);
  EdgeVisibility along{drawn.edges[edge].lengthPixels(), {}};
  walkEdge(drawnCurves, exactCurves, edge, [&](Interval step, dvec2, dvec2, double, bool, bool matched) {
    if (!matched) return;
    if (!along.visible.empty() && along.visible.back().end == step.begin) along.visible.back().end = step.end;
    else along.visible.push_back(step);
  });
  return along;
}

}  // namespace hsr
