#include "algorithms/floating_horizon/floating_horizon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <span>

#include "algorithms/floating_horizon/curve_comparison.hpp"
#include "algorithms/floating_horizon/curves.hpp"
#include "renderer/lines/line_drawing.hpp"
#include "renderer/steps/steps.hpp"

namespace hsr::floating_horizon {

namespace {

// The upper and lower horizons, in pixel coordinates (y grows down the image, so the
// upper horizon is the smallest y drawn so far). Each is known at the centers of equal
// screen columns, `columns` of them across the image, and taken as straight between
// them. They extend past the image's sides as far as the drawing does (at most
// kMaxWidths image widths each way), since what is hidden there counts too.
class Horizons {
 public:
  static constexpr double kMaxWidths = 16;

  Horizons(int columns, double width, double drawnFrom, double drawnTo, bool keepLower)
      : spacing_(width / columns), keepLower_(keepLower) {
    const double from = std::max(drawnFrom, -kMaxWidths * width), to = std::min(drawnTo, (kMaxWidths + 1) * width);
    first_ = std::floor(from / spacing_ - 0.5);
    const double count = std::max(1.0, std::ceil(to / spacing_ - 0.5) - first_ + 1);
    upper_.assign(static_cast<std::size_t>(count), kNothingDrawn);
    lower_.assign(upper_.size(), -kNothingDrawn);
  }
  std::size_t columnCount() const { return upper_.size(); }

  // Step 3: visible above the upper horizon, or below the lower one.
  bool visible(const dvec2& p) const { return p.y < at(upper_, p.x) || (keepLower_ && p.y > at(lower_, p.x)); }

  // hsr why --edge: where point p (at u along the edge asked about) lies against the
  // horizons, and so whether step 3 sees it.
  EdgeEvent placeOf(double u, const dvec2& p, std::string subject) const {
    const double upper = at(upper_, p.x), lower = at(lower_, p.x);
    // Interpolated toward kNothingDrawn, a horizon is far beyond any image: no curve has
    // reached a column beside p yet.
    const bool undrawn = upper > kNothingDrawn * 1e-100;
    const std::string numbers = "the segment at y = " + whyNumber(p.y) +
                                (undrawn ? ", no horizon yet at a column beside it" : ", the upper horizon at y = " + whyNumber(upper) +
                                 (!keepLower_ ? " (lower=off: no lower horizon kept)" : ", the lower at y = " + whyNumber(lower))) +
                                " (y grows down the image)";
    const char* place = undrawn                           ? "no curve drawn there yet: visible"
                        : p.y < upper                     ? "above the upper horizon: visible"
                        : keepLower_ && p.y > lower       ? "below the lower horizon: visible"
                        : keepLower_                      ? "between the horizons: hidden"
                                                          : "under the upper horizon: hidden";
    return {u, 0, place, numbers + "; " + (visible(p) ? "step 3 sees it" : "step 3 hides it"), std::move(subject)};
  }

  // Step 4 with interpolation: the parts of segment a-b (parameter t in [0, 1]) that are
  // visible. Between consecutive column centers both horizons are straight, as is the
  // segment, so visibility changes at most once per horizon there, where they cross.
  // `why`: hsr why --edge's events for this segment, or null.
  std::vector<Interval> visibleParts(const dvec2& a, const dvec2& b, std::int64_t& crossings, std::vector<EdgeEvent>* why = nullptr) const {
    std::vector<double> breaks = {0.0};
    forEachCenterBetween(a.x, b.x, [&](std::size_t, double x) { breaks.push_back((x - a.x) / (b.x - a.x)); });
    breaks.push_back(1.0);
    if (b.x < a.x) std::sort(breaks.begin(), breaks.end());
    std::vector<Interval> parts;
    const auto add = [&](double from, double to) {
      if (to <= from) return;
      if (!parts.empty() && parts.back().end >= from)
        parts.back().end = std::max(parts.back().end, to);
      else
        parts.push_back({from, to});
    };
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
      const double t0 = breaks[i], t1 = breaks[i + 1];
      const dvec2 p0 = a + t0 * (b - a), p1 = a + t1 * (b - a);
      // Above the upper horizon where y - upper < 0; below the lower one where y - lower > 0.
      const Interval above = signedPart(t0, t1, at(upper_, p0.x) - p0.y, at(upper_, p1.x) - p1.y, crossings);
      const Interval below = keepLower_ ? signedPart(t0, t1, p0.y - at(lower_, p0.x), p1.y - at(lower_, p1.x), crossings)
                                        : Interval{t0, t0};
      if (why) [[unlikely]] witnessPiece(t0, t1, p0, above, below, *why);
      // Between the horizons is hidden, so the two parts are disjoint: add them in order.
      const bool aboveFirst = above.begin <= below.begin;
      add(aboveFirst ? above.begin : below.begin, aboveFirst ? above.end : below.end);
      add(aboveFirst ? below.begin : above.begin, aboveFirst ? below.end : above.end);
    }
    return parts;
  }

  // hsr why --edge: the segment's piece from t0 to t1 between two column centers (or its
  // ends): where its start lies, then each horizon it crosses on the way.
  void witnessPiece(double t0, double t1, const dvec2& p0, const Interval& above, const Interval& below, std::vector<EdgeEvent>& why) const {
    why.push_back(placeOf(t0, p0, t0 == 0 ? "its start" : "the column center at x = " + whyNumber(p0.x)));
    const std::size_t first = why.size();
    const auto crossing = [&](double u, bool becomesVisible, const char* horizon, const char* how) {
      why.push_back({u, becomesVisible ? -1 : 1, becomesVisible ? "visible from here" : "hidden from here",
                     std::string("it ") + how + ", where the two cross; between column centers the horizon is straight, so the "
                     "crossing is computed (interpolate=on)", std::string("the ") + horizon});
    };
    if (above.end > above.begin && above.begin > t0) crossing(above.begin, true, "upper horizon", "comes out above the upper horizon");
    if (above.end > above.begin && above.end < t1) crossing(above.end, false, "upper horizon", "sinks under the upper horizon");
    if (below.end > below.begin && below.begin > t0) crossing(below.begin, true, "lower horizon", "comes out below the lower horizon");
    if (below.end > below.begin && below.end < t1) crossing(below.end, false, "lower horizon", "rises above the lower horizon");
    std::sort(why.begin() + std::ptrdiff_t(first), why.end(), [](const EdgeEvent& a, const EdgeEvent& b) { return a.u < b.u; });
  }

  // Step 5: the horizons take in segment a-b at every column center it spans.
  void raise(const dvec2& a, const dvec2& b) {
    forEachCenterBetween(a.x, b.x, [&](std::size_t column, double x) {
      const double y = a.y + (x - a.x) / (b.x - a.x) * (b.y - a.y);
      upper_[column] = std::min(upper_[column], y);
      lower_[column] = std::max(lower_[column], y);
    });
  }

  // For the steps: the horizons drawn over a picture as lines through their column
  // centers, upper in blue and lower in orange, where a curve has reached the column.
  void drawOver(Image& picture) const {
    for (std::size_t column = 0; column + 1 < upper_.size(); ++column) {
      const double x0 = (first_ + double(column) + 0.5) * spacing_, x1 = x0 + spacing_;
      if (upper_[column] < kNothingDrawn && upper_[column + 1] < kNothingDrawn)
        drawSegment(picture, {x0, upper_[column]}, {x1, upper_[column + 1]}, kSecondHighlight, 2.0);
      if (keepLower_ && lower_[column] > -kNothingDrawn && lower_[column + 1] > -kNothingDrawn)
        drawSegment(picture, {x0, lower_[column]}, {x1, lower_[column + 1]}, kThirdHighlight, 2.0);
    }
  }

 private:
  // Far beyond any image: "nothing drawn in this column yet". Finite, so interpolating
  // toward it stays arithmetic.
  static constexpr double kNothingDrawn = 1e300;

  // The center of column i (counted from the first kept) is at (first_ + i + 0.5) spacing_.
  double at(const std::vector<double>& horizon, double x) const {
    const double column = std::clamp(x / spacing_ - 0.5 - first_, 0.0, double(horizon.size() - 1));
    const std::size_t left = std::min(static_cast<std::size_t>(column), horizon.size() - 1);
    const std::size_t right = std::min(left + 1, horizon.size() - 1);
    const double f = column - double(left);
    return f == 0 ? horizon[left] : (1 - f) * horizon[left] + f * horizon[right];
  }

  // visit(column, x) for each column center x strictly between x0 and x1 (either order),
  // or at one of them.
  template <typename Visit>
  void forEachCenterBetween(double x0, double x1, Visit visit) const {
    const double lo = std::min(x0, x1), hi = std::max(x0, x1);
    if (!(hi > lo)) return;  // a vertical segment meets no center line, except by chance
    const double first = std::max(0.0, std::ceil(lo / spacing_ - 0.5 - first_));
    const double last = std::min(double(upper_.size() - 1), std::floor(hi / spacing_ - 0.5 - first_));
    for (double column = first; column <= last; ++column)
      visit(static_cast<std::size_t>(column), (first_ + column + 0.5) * spacing_);
  }

  // Where, in [t0, t1], a quantity going linearly from g0 to g1 is positive.
  static Interval signedPart(double t0, double t1, double g0, double g1, std::int64_t& crossings) {
    if (g0 > 0 && g1 > 0) return {t0, t1};
    if (!(g0 > 0) && !(g1 > 0)) return {t0, t0};
    ++crossings;
    const double t = t0 + (t1 - t0) * g0 / (g0 - g1);
    return g0 > 0 ? Interval{t0, t} : Interval{t, t1};
  }

  double spacing_;
  bool keepLower_;
  double first_ = 0;  // the first kept column's index, counted from the image's left side
  std::vector<double> upper_, lower_;
};

// One sampled point of a curve.
struct Sample {
  double along;   // running coordinate on the curve
  double height;  // f there
  dvec3 world;
  dvec2 pixel;
  bool defined;   // f is defined there (and it lies beyond the near plane)
};

// A count given as a number, or as a percentage of the image width.
int countOf(const KnobNumber& knob, int width, int minimum) {
  return std::max(minimum, static_cast<int>(std::lround(knob.percent ? knob.value / 100 * width : knob.value)));
}

class FloatingHorizon {
 public:
  FloatingHorizon(const PreparedScene& scene, const Knobs& knobs, Stats& stats, StepRecorder* steps, EdgeWitness* witness)
      : view_(scene), knobs_(knobs), stats_(stats), steps_(steps), witness_(witness), layout_(view_.layout(knobs.mesh)),
        columns_(countOf(knobs.columns, scene.width(), 1)), samples_(countOf(knobs.samples, scene.width(), 2)) {
    lines_.width = scene.width();
    lines_.height = scene.height();
  }

  LineSet run() {
    const CurveFamily& rows = layout_.rows;
    const CurveFamily& cross = layout_.cross;
    stats_.add("curves", static_cast<std::int64_t>(layout_.curveCount()));
    // Step 2: the samples; a mesh's curves also pass through every crossing with the other family.
    const dvec2 half = view_.halfFootprint();
    const std::vector<double> alongRows = coordinatesAcross(half[1 - rows.fixedAxis], samples_, cross.positions);
    const std::vector<double> alongCross = coordinatesAcross(half[rows.fixedAxis], samples_, rows.positions);
    std::vector<std::vector<Sample>> rowSamples, crossSamples;
    for (const double position : rows.positions) rowSamples.push_back(sample(rows, position, alongRows));
    for (const double position : cross.positions) crossSamples.push_back(sample(cross, position, alongCross));
    double drawnFrom = 0, drawnTo = lines_.width;
    for (const auto* family : {&rowSamples, &crossSamples})
      for (const std::vector<Sample>& curve : *family)
        for (const Sample& s : curve)
          if (s.defined) drawnFrom = std::min(drawnFrom, s.pixel.x), drawnTo = std::max(drawnTo, s.pixel.x);
    horizons_.emplace(columns_, double(lines_.width), drawnFrom, drawnTo, knobs_.lowerHorizon);
    stats_.add("horizon columns", static_cast<std::int64_t>(horizons_->columnCount()));

    // Step 1: the order. Each row is drawn after the cross pieces between it and the row
    // in front, which lie in front of it.
    for (std::size_t row = 0; row < rows.positions.size(); ++row) {
      if (row > 0)
        for (std::size_t c = 0; c < cross.positions.size(); ++c) {
          // The samples are in increasing `along` and include both rows' positions.
          const auto [from, to] = std::minmax(rows.positions[row - 1], rows.positions[row]);
          const std::vector<Sample>& curve = crossSamples[c];
          const auto alongLess = [](const Sample& s, double along) { return s.along < along; };
          const auto first = std::lower_bound(curve.begin(), curve.end(), from, alongLess);
          const auto last = std::lower_bound(first, curve.end(), to, alongLess);
          drawCurve(cross, cross.positions[c], rows.positions.size() + c, 
                    std::span<const Sample>(&*first, std::size_t(last - first) + 1));
        }
      drawCurve(rows, rows.positions[row], row, rowSamples[row]);
    }
    stats_.add("horizon crossings", crossings_);
    return std::move(lines_);
  }

 private:
  std::vector<Sample> sample(const CurveFamily& family, double position, const std::vector<double>& along) {
    std::vector<Sample> samples;
    samples.reserve(along.size());
    for (const double a : along) {
      const dvec2 ground = SurfaceView::ground(family, position, a);
      const double h = view_.height(ground);
      Sample s{a, h, dvec3(0), dvec2(0), !std::isnan(h)};
      if (s.defined) {
        s.world = view_.world(ground, h);
        s.pixel = view_.camera().pixelFromClip(view_.camera().clipFromWorld(s.world));
      }
      samples.push_back(s);
    }
    stats_.add("samples", static_cast<std::int64_t>(samples.size()));
    stats_.add("undefined samples", std::count_if(samples.begin(), samples.end(), [](const Sample& s) { return !s.defined; }));
    return samples;
  }

  // Steps 3 to 5 for one curve: every segment is tested against the horizons as the
  // curves in front left them, and only then does the curve raise them.
  void drawCurve(const CurveFamily& family, double position, std::size_t curve, std::span<const Sample> samples) {
    const auto firstEdge = static_cast<std::uint32_t>(lines_.edges.size());
    std::vector<std::pair<dvec2, dvec2>> drawn;
    for (std::size_t i = 0; i + 1 < samples.size(); ++i) {
      const Sample &a = samples[i], &b = samples[i + 1];
      if (!a.defined || !b.defined) continue;
      // A hole or a jump between the samples: nothing is drawn across it, and it raises
      // no horizon (the near-vertical chord would hide what lies behind the gap).
      if (view_.breaksBetween(SurfaceView::ground(family, position, a.along), a.height,
                              SurfaceView::ground(family, position, b.along), b.height)) {
        stats_.add("breaks", 1);
        continue;
      }
      std::vector<EdgeEvent>* const why = witness_ && witness_->edge == lines_.edges.size() ? &witness_->events : nullptr;
      if (why) [[unlikely]]
        why->push_back({kWholeEdge, 0, "curve " + std::to_string(curvesDrawn_ + 1) + " of " + std::to_string(curvesToDraw()) + ", front to back",
                        "the curves in front of it have raised the horizons; each of its segments is tested against them, and "
                        "only then does the curve raise them (steps 3 to 5)"});
      std::vector<Interval> visible;
      if (knobs_.interpolate) {
        visible = horizons_->visibleParts(a.pixel, b.pixel, crossings_, why);
      } else {
        if (why) [[unlikely]]
          why->push_back(horizons_->placeOf(0, a.pixel, "its start")), why->push_back(horizons_->placeOf(1, b.pixel, "its end"));
        const bool seenA = horizons_->visible(a.pixel), seenB = horizons_->visible(b.pixel);
        if (seenA && seenB) {
          visible = {{0.0, 1.0}};
        } else if (seenA || seenB) {
          stats_.add("segments dropped", 1);  // the classic ragged end: visibility changes between samples
        }
        if (why) [[unlikely]]
          why->push_back({kWholeEdge, 0, visible.empty() ? "hidden whole" : "drawn whole",
                          "interpolate=off looks only at the two samples: " +
                              std::string(seenA && seenB ? "both are visible"
                                          : seenA || seenB ? "one is visible and the other not, so the segment is dropped (the classic ragged end)"
                                                           : "neither is visible")});
      }
      addEdge(a, b, static_cast<std::uint32_t>(curve), visible);
      drawn.emplace_back(a.pixel, b.pixel);
    }
    for (const auto& [a, b] : drawn) horizons_->raise(a, b);
    if (witness_ && witness_->edge >= firstEdge && witness_->edge < lines_.edges.size()) [[unlikely]]
      witness_->events.push_back({kWholeEdge, 0, "then the curve raises the horizons",
                                  "at every column center its segments span, the upper horizon to the least y drawn there and the lower "
                                  "to the greatest (step 5): what the curves behind it are tested against"});
    if (steps_ && steps_->due(curvesDrawn_, curvesToDraw())) recordCurve(firstEdge);
    ++curvesDrawn_;
  }

  // How many times drawCurve runs: each row, and each cross curve's piece between two rows.
  std::size_t curvesToDraw() const {
    const std::size_t rows = layout_.rows.positions.size();
    return rows + (rows > 0 ? (rows - 1) * layout_.cross.positions.size() : 0);
  }

  // A step: the drawing so far, the curve just drawn in green, the horizons it raised.
  void recordCurve(std::uint32_t firstEdge, SourceLocation where = SourceLocation::current()) {
    std::vector<std::uint32_t> curveEdges(lines_.edges.size() - firstEdge);
    std::iota(curveEdges.begin(), curveEdges.end(), firstEdge);
    Image picture = lineStepPicture(lines_, curveEdges, LineStyle::hidden);
    horizons_->drawOver(picture);
    drawLegend(picture, {{kSecondHighlight, "upper horizon"}, {kThirdHighlight, "lower horizon"}, {kJustDecided, "curve just drawn"}});
    steps_->record("steps 3-5: curve " + std::to_string(curvesDrawn_ + 1) + " of " + std::to_string(curvesToDraw()) +
                       " tested against the horizons, then raising them (front to back)",
                   std::move(picture), where);
  }

  // The segment a-b as an edge of the drawing: its visible parts, and hidden ones between.
  void addEdge(const Sample& a, const Sample& b, std::uint32_t curve, const std::vector<Interval>& visible) {
    const auto edge = static_cast<std::uint32_t>(lines_.edges.size());
    lines_.edges.push_back(projectEdge(view_.camera(), a.world, b.world, EdgeKind::curve));
    lines_.curvePlaces.push_back({curve, a.along, b.along});
    appendPieces(lines_, edge, visible);
  }

  SurfaceView view_;
  const Knobs& knobs_;
  Stats& stats_;
  StepRecorder* steps_;
  EdgeWitness* witness_;  // hsr why --edge's edge, or null
  std::size_t curvesDrawn_ = 0;
  CurveLayout layout_;
  int columns_, samples_;
  std::optional<Horizons> horizons_;  // once the drawing's extent is known
  LineSet lines_;
  std::int64_t crossings_ = 0;
};

}  // namespace

LineSet run(const PreparedScene& scene, const Knobs& knobs, Stats& stats, StepRecorder* steps, EdgeWitness* edge) {
  const PhaseTimer timer(stats, "floating horizon");
  return FloatingHorizon(scene, knobs, stats, steps, edge).run();
}

AlgorithmEntry entry() {
  AlgorithmEntry entry;
  entry.name = "floating_horizon";
  entry.kind = AlgorithmKind::line;
  entry.summary = "curves of a height field front to back against upper and lower horizons (Williamson 1972, Wright 1973)";
  setKnobs(entry, knobTable());
  entry.keyCounters = {"curves", "samples", "horizon crossings", "breaks", "segments dropped"};
  entry.studyConfigurations = {{}, {{"interpolate", "off"}, {"samples", "5%"}}, {{"samples", "5%"}}, {{"lower", "off"}},
                               {{"columns", "25%"}}};
  setRefusal(entry, refusal);
  setDrawing(entry, run);
  entry.whyDecisions = {"no curve drawn there yet", "above the upper horizon", "below the lower horizon", "between the horizons",
                        "under the upper horizon"};
  entry.judgeLines = [](const PreparedScene& scene, const KnobValues& values, const LineSet& lines, int threads, Stats& stats) {
    const ExactDrawing exact = exactDrawing(scene, values.as<Knobs>().mesh, threads, stats);
    CurveComparison comparison = compareCurveDrawings(lines, exact.lines, exact.visibility);
    return LineJudgement{comparison.error, std::move(comparison.errorMap), drawingOf(exact.lines, exact.visibility)};
  };
  entry.exactAlongEdge = [](const LineSet& drawing, std::uint32_t edge, const LineSet& exact) {
    return exactAlongDrawnEdge(drawing, edge, exact, edgeVisibility(exact));
  };
  return entry;
}

}  // namespace hsr::floating_horizon
