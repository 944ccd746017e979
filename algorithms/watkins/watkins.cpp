// Watkins' scanline algorithm: rows top to bottom, each row cut into spans at the
// polygons' crossings, each span resolved by depth at its ends or split where polygons cross.
#include "algorithms/watkins/watkins.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "renderer/raster/active_triangles.hpp"
#include "renderer/raster/plane_depth.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr::watkins {
namespace {

// Where a polygon's edge crosses the row: its run of covered pixel centers begins at x
// (entering), or ended at x - 1 (leaving).
struct Crossing {
  int x;
  std::uint32_t polygon;
  bool entering;
};

// How a span was decided.
enum class Outcome { empty, onePolygon, decidedAtEnds, onePixel, leftEndOnly, split };
constexpr std::array<const char*, 6> kOutcomeCounters = {"spans empty",        "spans with one polygon", "spans decided at both ends",
                                                         "spans of one pixel", "spans taken from their left end", "spans split"};

// A band's counts, on cache lines of their own: the bands run side by side, and two
// threads counting spans on one line would wait for each other at every span.
struct alignas(64) Counts {
  std::int64_t crossings = 0, activePolygons = 0, depthSamples = 0, mostCrossings = 0;
  std::array<std::int64_t, 6> spans{};  // by Outcome
  Counts& operator+=(const Counts& other) {
    crossings += other.crossings, activePolygons += other.activePolygons, depthSamples += other.depthSamples;
    mostCrossings = std::max(mostCrossings, other.mostCrossings);
    for (std::size_t k = 0; k < spans.size(); ++k) spans[k] += other.spans[k];
    return *this;
  }
};

// A present polygon's depth at a span's two ends (order keys: smaller is nearer), and the
// rounding bound that holds at every center between them.
struct AtEnds {
  std::uint32_t polygon;
  double left, right, bound;
};

// Resolves rows, one at a time, into the frame (each row's pixels only: a band of rows
// per thread). Holds the row's working lists, reused from row to row.
class RowResolver {
 public:
  // why: hsr why's pixels, or null (renderer/steps/why.hpp).
  RowResolver(const ScreenGeometry& geometry, const Knobs& knobs, Frame& frame, PixelWitness* why)
      : triangles_(geometry.triangles), camera_(geometry.camera), knobs_(knobs), frame_(frame), order_(geometry.camera), why_(why) {}

  // marks: with a recording, where the row was cut (x, and whether at a split).
  void resolveRow(int y, const std::vector<std::uint32_t>& active, Counts& counts, std::vector<std::pair<int, bool>>* marks) {
    // Step 3: each active polygon's edges cross the row where its run of covered centers
    // begins and ends (solved exactly from the integer edge functions, renderer/raster/raster,
    // where the textbook steps x by dx/dy from row to row and drifts).
    crossings_.clear();
    for (const std::uint32_t i : active) {
      int first, last;
      if (!coveredRun(triangles_[i], y, triangles_[i].minX, triangles_[i].maxX + 1, first, last)) continue;
      crossings_.push_back({first, i, true});
      crossings_.push_back({last + 1, i, false});
    }
    counts.activePolygons += static_cast<std::int64_t>(active.size());
    counts.crossings += static_cast<std::int64_t>(crossings_.size());
    counts.mostCrossings = std::max(counts.mostCrossings, static_cast<std::int64_t>(crossings_.size()));
    // Step 4: sorted by x, the crossings cut the row into spans; walking them, each
    // crossing adds its polygon to the ones present or removes it, and each span between
    // two crossings is resolved with the polygons present over it (kept in submission
    // order, so a depth tie goes to the earlier polygon, as in the z-buffer).
    std::sort(crossings_.begin(), crossings_.end(), [](const Crossing& a, const Crossing& b) { return a.x < b.x; });
    if (why_) [[unlikely]]
      why_->forEachInRun(y, 0, frame_.width, [&](int, std::vector<PixelEvent>& history) {
        history.push_back({conventions::kBackgroundId, "cut into spans where the polygons' edges cross it",
                           std::to_string(active.size()) + " active polygons, " + std::to_string(crossings_.size()) + " crossings",
                           std::numeric_limits<double>::quiet_NaN(), false, "row " + std::to_string(y)});
      });
    present_.clear();
    int spanStart = 0;
    for (std::size_t k = 0; k < crossings_.size();) {
      const int x = crossings_[k].x;
      if (x > spanStart) resolveSpan(y, spanStart, x, counts, marks);
      for (; k < crossings_.size() && crossings_[k].x == x; ++k) {
        const auto at = std::lower_bound(present_.begin(), present_.end(), crossings_[k].polygon);
        if (crossings_[k].entering)
          present_.insert(at, crossings_[k].polygon);
        else
          present_.erase(at);
      }
      if (marks) marks->emplace_back(x, false);
      spanStart = x;
    }
    if (spanStart < frame_.width) resolveSpan(y, spanStart, frame_.width, counts, marks);
  }

 private:
  // Step 5: a span [a, b) of row y, with the polygons present over all of it.
  void resolveSpan(int y, int a, int b, Counts& counts, std::vector<std::pair<int, bool>>* marks) {
    const auto decided = [&](Outcome outcome, std::optional<std::uint32_t> polygon) {
      ++counts.spans[std::size_t(outcome)];
      fill(y, a, b, polygon);
      if (why_) [[unlikely]] witnessSpan(y, a, b, outcome, polygon);
    };
    if (present_.empty()) return decided(Outcome::empty, std::nullopt);
    if (present_.size() == 1) return decided(Outcome::onePolygon, present_[0]);

    // BEGIN SOLUTION
    // The depth of each present polygon at the span's first and last pixel centers, and
    // the nearest at each end (a tie to the earlier polygon).
    ends_.clear();
    for (const std::uint32_t i : present_) {
      const ScreenTriangle& tri = triangles_[i];
      ends_.push_back({i, order_.key(tri, a, y), order_.key(tri, b - 1, y),
                       std::max(DepthOrder::roundingBound(tri, a, y), DepthOrder::roundingBound(tri, b - 1, y))});
    }
    counts.depthSamples += 2 * static_cast<std::int64_t>(ends_.size());
    const auto nearestAt = [&](double AtEnds::*end) {
      return *std::min_element(ends_.begin(), ends_.end(), [&](const AtEnds& p, const AtEnds& q) { return p.*end < q.*end; });
    };
    const AtEnds left = nearestAt(&AtEnds::left), right = nearestAt(&AtEnds::right);

    // One polygon nearest at both ends, by more than the rounding of the values on both
    // sides: the difference of two planes is linear along the row, so it is nearest at
    // every center between, and fills the span.
    const bool nearestThroughout = left.polygon == right.polygon && std::all_of(ends_.begin(), ends_.end(), [&](const AtEnds& other) {
      const double margin = 2 * (left.bound + other.bound);
      return other.polygon == left.polygon || (left.left + margin < other.left && left.right + margin < other.right);
    });
    if (nearestThroughout) return decided(Outcome::decidedAtEnds, left.polygon);
    // A span of one pixel: its two ends are its center, and the nearest there is exact sampling.
    if (b - a == 1) return decided(Outcome::onePixel, left.polygon);
    if (knobs_.split == Split::none) return decided(Outcome::leftEndOnly, left.polygon);

    // Otherwise two polygons cross inside the span (or come within rounding of it): split
    // it where the nearest at the left end and the nearest at the right end have equal
    // depth, or in the middle, and resolve each part.
    ++counts.spans[std::size_t(Outcome::split)];
    const int split = knobs_.split == Split::crossing && left.polygon != right.polygon ? whereDepthsCross(left, right, a, b) : a + (b - a) / 2;
    if (marks) marks->emplace_back(split, true);
    if (why_) [[unlikely]] witnessSpan(y, a, b, Outcome::split, std::nullopt, split);
    resolveSpan(y, a, split, counts, marks);  // the parts have the same polygons present
    resolveSpan(y, split, b, counts, marks);
    // SKELETON
    // // Exercise 15: two or more polygons (present_) over the span [a, b) of row y.
    // // Their depths at its two end centers (order_.key(triangles_[i], x, y), smaller is
    // // nearer; DepthOrder::roundingBound is how far a computed key may be off; gather
    // // them in ends_, and count them in counts.depthSamples): where one polygon is
    // // nearest at both ends by more than twice the rounding of both values, it fills the
    // // span (decided(Outcome::decidedAtEnds, polygon)); a span of one pixel is decided
    // // by the nearest there (Outcome::onePixel), and with knobs_.split == Split::none any
    // // span by the nearest at its left end (Outcome::leftEndOnly). Otherwise count
    // // Outcome::split in counts.spans, split the span where the two nearest cross
    // // (whereDepthsCross, with knobs_.split == Split::crossing) or in the middle, note the
    // // split in marks when it is not null (the steps' picture), and resolve both parts.
    // // (hsr why's events: witnessSpan, as decided() calls it; optional.) Why do the two
    // // ends suffice?
    // (void)y, (void)a, (void)b, (void)counts, (void)marks;
    // return decided(Outcome::empty, std::nullopt);
    // END SOLUTION
  }

  // The first pixel of the part where `right` is the nearer: along the span the
  // difference of the two depths is linear, from d0 at the first center to d1 at the
  // last (d0 >= 0: `left` is nearer there; d1 <= 0), so it is zero a fraction
  // d0 / (d0 - d1) of the way. Kept strictly inside the span, so that both parts are
  // shorter (a crossing found from rounded depths may lie a pixel off: the part it
  // lands in is split again).
  static int whereDepthsCross(const AtEnds& left, const AtEnds& right, int a, int b) {
    const double d0 = right.left - left.left, d1 = right.right - left.right;
    const double fraction = d0 / (d0 - d1);
    const double crossing = a + fraction * double(b - 1 - a);
    if (!(crossing >= a && crossing <= b - 1)) return a + (b - a) / 2;
    return std::clamp(static_cast<int>(std::floor(crossing)) + 1, a + 1, b - 1);
  }

  // hsr why: span [a, b) of row y decided (or split at `split`), at each pixel asked
  // about in it: the polygons present, each with its distances at the span's first and
  // last pixel, and the rule that chose the one that fills it (or split it).
  void witnessSpan(int y, int a, int b, Outcome outcome, std::optional<std::uint32_t> polygon, int split = 0) const {
    static constexpr std::array<const char*, 6> kRules = {
        "empty: no polygon is present, the background fills it",
        "one polygon present: it fills the span",
        "nearest at both ends by more than rounding: it fills the span (two planes' depths differ linearly along it)",
        "one pixel: the nearest at its center fills it",
        "its two ends have different nearest polygons (or are within rounding); split=none takes the nearest at its left end",
        "the nearest differs between its ends (or is within rounding): split"};
    const auto atEnds = [&](std::uint32_t i) {
      char text[100];
      std::snprintf(text, sizeof text, "at distance %.9g at the span's first pixel, %.9g at its last", DepthOrder::distanceAt(camera_, triangles_[i], a, y),
                    DepthOrder::distanceAt(camera_, triangles_[i], b - 1, y));
      return std::string(text);
    };
    const std::string span = "span " + std::to_string(a) + ".." + std::to_string(b - 1) + " of row " + std::to_string(y);
    const double none = std::numeric_limits<double>::quiet_NaN();
    why_->forEachInRun(y, a, b, [&](int x, std::vector<PixelEvent>& history) {
      if (outcome == Outcome::split) {
        history.push_back({conventions::kBackgroundId, std::string(kRules[std::size_t(outcome)]) + " at column " + std::to_string(split),
                           std::to_string(present_.size()) + " polygons present", none, false, span});
        return;
      }
      for (const std::uint32_t i : present_)
        if (i != polygon)
          history.push_back({triangles_[i].triangle + 1, "present in " + span + ", not the one the rule chose", atEnds(i),
                             DepthOrder::distanceAt(camera_, triangles_[i], x, y), false, {}});
      if (!polygon) {
        history.push_back({conventions::kBackgroundId, span + ": " + kRules[std::size_t(outcome)], "", none, true, {}});
        return;
      }
      history.push_back({triangles_[*polygon].triangle + 1, span + ": " + kRules[std::size_t(outcome)], atEnds(*polygon),
                         DepthOrder::distanceAt(camera_, triangles_[*polygon], x, y), true, {}});
    });
  }

  void fill(int y, int a, int b, const std::optional<std::uint32_t>& polygon) const {
    const std::size_t row = std::size_t(y) * std::size_t(frame_.width);
    for (int x = a; x < b; ++x) {
      if (!polygon) {
        frame_.ids[row + std::size_t(x)] = conventions::kBackgroundId;
        frame_.depth[row + std::size_t(x)] = std::numeric_limits<float>::infinity();
        continue;
      }
      const ScreenTriangle& tri = triangles_[*polygon];
      frame_.ids[row + std::size_t(x)] = tri.triangle + 1;
      frame_.depth[row + std::size_t(x)] = DepthOrder::distanceAt(camera_, tri, x, y);
    }
  }

  const ScreenTriangles& triangles_;
  const CameraTransform& camera_;
  const Knobs& knobs_;
  Frame& frame_;
  DepthOrder order_;
  std::vector<Crossing> crossings_;
  std::vector<std::uint32_t> present_;
  std::vector<AtEnds> ends_;
  PixelWitness* why_;
};

// A step: the rows finished so far (the rest blank), the row in blue, where it was cut
// at crossings (red ticks) and at splits (orange ticks).
void recordRow(const PreparedScene& scene, const CameraTransform& view, const Frame& frame, int y, std::size_t active,
               const std::vector<std::pair<int, bool>>& marks, StepRecorder& steps,
               SourceLocation where = SourceLocation::current()) {
  std::vector<std::uint32_t> ids(frame.ids.begin(), frame.ids.begin() + std::ptrdiff_t(std::size_t(y + 1) * std::size_t(frame.width)));
  ids.resize(frame.pixelCount(), conventions::kBackgroundId);
  Image picture = surfacePicture(scene, view, ids, frame.width, frame.height);
  const double centre = y + 0.5;
  drawSegment(picture, {0, centre}, {double(frame.width), centre}, kSecondHighlight, 1.0);
  std::size_t splits = 0;
  for (const auto& [x, isSplit] : marks) {
    drawSegment(picture, {double(x), centre - 4}, {double(x), centre + 4}, isSplit ? kThirdHighlight : kHighlight, 1.0);
    splits += isSplit;
  }
  steps.record("row " + std::to_string(y) + ": " + std::to_string(active) + " active polygons; their edges cross the row at " +
                   std::to_string(marks.size() - splits) + " places (red); spans split where polygons cross: " + std::to_string(splits) +
                   " (orange)",
               std::move(picture), where);
}

}  // namespace

void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility) {
  const ScreenGeometry geometry =
      buildScreenTriangles(request.scene, request.view, {.submitted = request.triangles}, request.threads, request.stats);
  PhaseTimer timer(request.stats, "scanlines");
  Frame& frame = visibility.frame;

  // Step 1: the edge table, polygons bucketed by the first row they cover.
  const auto startingAt = trianglesByFirstRow(geometry.triangles, frame.height);
  // Rows are cut into bands, one per worker, each with its own active list and row
  // lists; a recording watches the rows in order, on one thread.
  const int workers = request.steps ? 1 : std::min(resolveThreadCount(request.threads), frame.height);
  std::vector<Counts> bandCounts(static_cast<std::size_t>(workers));
  parallelFor(static_cast<std::size_t>(workers), workers, [&](std::size_t band, int) {
    const auto [first, last] = partRange(static_cast<std::size_t>(frame.height), static_cast<std::size_t>(workers), band);
    RowResolver rows(geometry, knobs, frame, request.why);
    // Step 2: going down, the active list admits each polygon on its first row and
    // retires it after its last (renderer/raster/active_triangles.hpp).
    ActiveTriangles activeList(geometry.triangles, startingAt, first);
    std::vector<std::pair<int, bool>> marks;
    for (std::size_t y = first; y < last; ++y) {
      activeList.advanceTo(y);
      const bool watched = request.steps && request.steps->due(y, last);
      marks.clear();
      rows.resolveRow(int(y), activeList.active(), bandCounts[band], watched ? &marks : nullptr);
      if (watched) recordRow(request.scene, request.view, frame, int(y), activeList.active().size(), marks, *request.steps);
    }
  });

  Counts total;
  for (const Counts& counts : bandCounts) total += counts;
  request.stats.add("crossings", total.crossings);
  request.stats.add("active polygons summed over rows", total.activePolygons);
  std::int64_t spans = 0;
  for (std::size_t k = 0; k < total.spans.size(); ++k) {
    request.stats.add(kOutcomeCounters[k], total.spans[k]);
    spans += total.spans[k];
  }
  request.stats.add("spans", spans);
  request.stats.add("depth samples", total.depthSamples);
  request.stats.add("most crossings on a row", total.mostCrossings);
}

AlgorithmEntry entry() {
  AlgorithmEntry entry;
  entry.name = "watkins";
  entry.summary = "scanline with spans (Watkins 1970): rows cut at edge crossings, spans resolved by depth at their ends";
  setKnobs(entry, knobTable());
  entry.keyCounters = {"crossings", "spans", "spans split"};
  entry.studyConfigurations = {{}, {{"split", "halves"}}, {{"split", "none"}}};
  entry.takesTriangleSubsets = true;
  entry.answersWhy = true;
  setVisibility(entry, visibility);
  return entry;
}

}  // namespace hsr::watkins
