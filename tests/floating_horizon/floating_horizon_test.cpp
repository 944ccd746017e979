// The floating horizon against the exact drawing of the same curves, on the ripple and on
// each of its hard cases (scenes/hard/fh_*.toml), and its refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "algorithms/floating_horizon/floating_horizon.hpp"
#include "algorithms/registry.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

constexpr int kWidth = 320;  // the drawings are judged at this width (the reference is per pixel)

struct Judged {
  LineSet lines;
  Stats stats;
  LineError error;
};

Judged judge(const PreparedScene& scene, const KnobSettings& knobs = {}) {
  const AlgorithmEntry& entry = findAlgorithm("floating_horizon");
  const KnobValues values = resolveKnobs(entry, knobs);
  EXPECT_EQ(entry.refusal(scene, values), "");
  Judged judged;
  judged.lines = entry.drawLines(scene, values, 1, judged.stats, nullptr);
  Stats referenceStats;
  judged.error = entry.judgeLines(scene, values, judged.lines, 2, referenceStats).error;
  return judged;
}

test::LoadedScene load(const std::string& name) { return test::LoadedScene(test::sourcePath("scenes/" + name + ".toml"), kWidth); }

double drawnVisibleLength(const LineSet& lines) {
  double length = 0;
  for (const LineSegment& piece : lines.segments)
    if (piece.visible()) length += (piece.end - piece.begin) * lines.edges[piece.edge].lengthPixels();
  return length;
}

// The highest point of the drawing, in world units.
double highestDrawn(const LineSet& lines) {
  double highest = -1e300;
  for (const FeatureEdge& edge : lines.edges) highest = std::max({highest, edge.from.y, edge.to.y});
  return highest;
}

TEST(FloatingHorizon, RippleAgreesWithTheExactDrawingWithinAPercent) {
  const auto loaded = load("ripple");
  for (const KnobSettings& knobs : {KnobSettings{}, KnobSettings{{"mesh", "on"}}}) {
    const Judged judged = judge(loaded.prepared, knobs);
    EXPECT_GT(judged.error.visibleLength, 5000);
    EXPECT_LT(judged.error.error, 0.01) << resolveKnobs(findAlgorithm("floating_horizon"), knobs).described();
  }
}

// Seen square on (azimuth 0), each screen column cuts the surface along one line of the
// ground that the rows cross at right angles: nothing between two curves can rise above
// both, and the horizons alone decide. At 30 degrees the strips between curves hide a
// little that the curves do not know about: the method's own error, not the arrays'.
TEST(FloatingHorizon, NearlyExactWhenColumnsCutAcrossTheCurves) {
  auto loaded = load("ripple");
  const double oblique = judge(loaded.prepared).error.error;
  Camera& camera = loaded.scene.camera;
  camera.eye = camera.target + glm::length(camera.eye - camera.target) * dvec3(0, 0.5, std::sqrt(0.75));
  camera.up = dvec3(0, std::sqrt(0.75), -0.5);
  const double squareOn = judge(loaded.prepared).error.error;
  EXPECT_LT(squareOn, 0.0005);
  EXPECT_GT(oblique, 4 * squareOn);
}

TEST(FloatingHorizon, SpikeIsMissedBetweenSparseSamplesAndCaughtByDenseOnes) {
  const auto loaded = load("hard/fh_spike");
  const Judged sparse = judge(loaded.prepared, {{"samples", "5%"}});
  const Judged dense = judge(loaded.prepared);
  // The spike is 3 high. Sparse samples straddle it, so the drawing stops far below its
  // top and the curves behind it are drawn where it hides them.
  EXPECT_LT(highestDrawn(sparse.lines), 1.5);
  EXPECT_GT(sparse.error.error, 0.05);
  EXPECT_GT(sparse.error.wronglyDrawn, 100);
  EXPECT_GT(highestDrawn(dense.lines), 0.99 * 3);
  EXPECT_LT(dense.error.error, 0.001);
}

TEST(FloatingHorizon, NothingIsDrawnAcrossAJump) {
  const auto loaded = load("hard/fh_step");
  const Judged judged = judge(loaded.prepared);
  // Every curve of constant z breaks once at x = 0, and no drawn edge spans it.
  EXPECT_EQ(judged.stats.counter("breaks"), judged.stats.counter("curves"));
  for (const CurvePlace& place : judged.lines.curvePlaces) EXPECT_FALSE(place.from < 0 && place.to >= 0);
  // What remains is the method's blind spot at a gap: the horizons take everything
  // between the highest and lowest points drawn in a column as covered (README).
  EXPECT_LT(judged.error.error, 0.03);
}

TEST(FloatingHorizon, ASteepSlopeIsNotTakenForAJump) {
  const auto loaded = load("hard/fh_cliff");
  const Judged judged = judge(loaded.prepared);
  EXPECT_EQ(judged.stats.counter("breaks"), 0);
  EXPECT_LT(judged.error.error, 1e-4);
  // 16 samples per curve put a few samples on the cliff: the chords cut its corners.
  EXPECT_GT(judge(loaded.prepared, {{"samples", "5%"}}).error.error, 0.1);
}

TEST(FloatingHorizon, OnlyTheLowerHorizonShowsCurvesBelowTheFirst) {
  const auto loaded = load("hard/fh_below_first");
  const Judged both = judge(loaded.prepared);
  const Judged upperOnly = judge(loaded.prepared, {{"lower", "off"}});
  EXPECT_LT(both.error.error, 0.005);
  // Without the lower horizon, the far side (seen from below, under the front edge) is lost.
  EXPECT_GT(upperOnly.error.wronglyHidden, 0.3 * upperOnly.error.visibleLength);
  EXPECT_LT(drawnVisibleLength(upperOnly.lines), 0.7 * drawnVisibleLength(both.lines));
}

TEST(FloatingHorizon, NearlyEdgeOnTheErrorStaysBounded) {
  const auto loaded = load("hard/fh_edge_on");
  const Judged judged = judge(loaded.prepared);
  EXPECT_GT(judged.stats.counter("horizon crossings"), 100);
  EXPECT_LT(judged.error.error, 0.06);
}

TEST(FloatingHorizon, StraightDownEveryCurveIsDrawnWhole) {
  const auto loaded = load("hard/fh_top_down");
  const Judged judged = judge(loaded.prepared);
  double hidden = 0;
  for (const LineSegment& piece : judged.lines.segments)
    if (!piece.visible()) hidden += (piece.end - piece.begin) * judged.lines.edges[piece.edge].lengthPixels();
  EXPECT_LT(hidden, 1e-9);
  EXPECT_EQ(judged.error.wronglyDrawn + judged.error.wronglyHidden, 0);
  EXPECT_NEAR(drawnVisibleLength(judged.lines), judged.error.visibleLength, 1e-6 * judged.error.visibleLength);
}

TEST(FloatingHorizon, HolesBreakTheCurvesAtTheirRims) {
  const auto loaded = load("hard/fh_holes");
  const Judged judged = judge(loaded.prepared);
  EXPECT_GT(judged.stats.counter("undefined samples"), 1000);
  const Solid& solid = loaded.scene.objects[0].solid;
  // Every drawn edge lies where f is defined, its middle too.
  for (std::size_t e = 0; e < judged.lines.edges.size(); ++e) {
    const dvec3 middle = 0.5 * (judged.lines.edges[e].from + judged.lines.edges[e].to);
    ASSERT_FALSE(std::isnan(solid.function.evaluate(middle.x, middle.z))) << "edge " << e;
  }
  EXPECT_LT(judged.error.error, 0.02);
}

// The interpolation lesson: without it, a segment whose samples disagree is dropped, so
// visible lines end short of the horizon they pass behind.
TEST(FloatingHorizon, WithoutInterpolationLinesEndShortAtTheHorizon) {
  const auto loaded = load("ripple");
  const Judged interpolated = judge(loaded.prepared, {{"samples", "10%"}});
  const Judged dropped = judge(loaded.prepared, {{"samples", "10%"}, {"interpolate", "off"}});
  EXPECT_GT(dropped.stats.counter("segments dropped"), 20);
  EXPECT_GT(interpolated.stats.counter("horizon crossings"), 20);
  EXPECT_GT(dropped.error.wronglyHidden, interpolated.error.wronglyHidden + 50);
}

// hsr why --edge on the floating horizon: a segment's tests, watched, leave the drawing
// as it was and account for its pieces. With interpolation, each place recorded (its
// start, each column center) says whether step 3 sees the segment there as its piece
// there is drawn, and its pieces change from visible to hidden exactly where a horizon
// crossing was recorded, or at a place recorded; without, the two samples decide it
// whole: drawn exactly when both places recorded say step 3 sees them.
TEST(FloatingHorizon, TheTestsWatchedAlongASegmentAccountForItsPieces) {
  const auto loaded = load("ripple");
  const AlgorithmEntry& entry = findAlgorithm("floating_horizon");
  std::int64_t crossingsChecked = 0, placesChecked = 0;
  for (const bool interpolate : {true, false}) {
    const KnobValues values = resolveKnobs(entry, {{"samples", "10%"}, {"interpolate", interpolate ? "on" : "off"}});
    Stats plainStats;
    const LineSet plain = entry.drawLines(loaded.prepared, values, 1, plainStats, nullptr);
    // 40 edges whose pieces change along it (none without interpolation) and 40 others,
    // spread over the drawing.
    std::vector<std::uint32_t> changing, whole;
    std::vector<std::size_t> piecesOf(plain.edges.size());
    for (const LineSegment& piece : plain.segments) ++piecesOf[piece.edge];
    for (std::uint32_t e = 0; e < plain.edges.size(); ++e) (piecesOf[e] > 1 ? changing : whole).push_back(e);
    std::vector<std::uint32_t> asked;
    for (std::size_t i = 0; i < 40; ++i) {
      if (!changing.empty()) asked.push_back(changing[i * changing.size() / 40]);
      if (!whole.empty()) asked.push_back(whole[i * whole.size() / 40]);
    }
    for (const std::uint32_t e : asked) {
      const std::string where = std::string(interpolate ? "" : "interpolate=off ") + "edge " + std::to_string(e);
      EdgeWitness witness{e, {}};
      Stats stats;
      const std::optional<std::vector<LineSegment>> watchedPieces =
          test::piecesIfUnchanged(plain, entry.drawLinesWatchingEdge(loaded.prepared, values, stats, witness), e);
      ASSERT_TRUE(watchedPieces) << where << ": watching changed the drawing";
      const std::vector<LineSegment>& pieces = *watchedPieces;
      const std::vector<EdgeEvent>& events = witness.events;
      ASSERT_GE(events.size(), 3u) << where;
      EXPECT_EQ(events.front().outcome.rfind("curve ", 0), 0u) << where;
      EXPECT_EQ(events.back().outcome, "then the curve raises the horizons") << where;
      const auto visibleAt = [&](double u) {
        for (const LineSegment& piece : pieces)
          if (piece.begin <= u && u < piece.end) return piece.visible();
        return pieces.back().visible();
      };
      if (!interpolate) {
        ASSERT_EQ(events.size(), 5u) << where;  // the curve, its two samples, the verdict, the raise
        const bool bothSeen = events[1].detail.ends_with("step 3 sees it") && events[2].detail.ends_with("step 3 sees it");
        EXPECT_EQ(pieces.size() == 1 && pieces[0].visible(), bothSeen) << where;
        EXPECT_EQ(events[3].outcome, bothSeen ? "drawn whole" : "hidden whole") << where;
        ++placesChecked;
        continue;
      }
      std::vector<double> recorded;  // where the segment's visibility may change: crossings and places
      for (std::size_t i = 1; i + 1 < events.size(); ++i) {
        const EdgeEvent& event = events[i];
        recorded.push_back(event.u);
        if (event.change != 0) {
          // The pieces change here, to what the crossing says.
          EXPECT_EQ(visibleAt(event.u), event.change < 0) << where << " at u = " << event.u;
          ++crossingsChecked;
          continue;
        }
        const double next = i + 2 < events.size() ? events[i + 1].u : 1.0;
        const bool seen = event.detail.ends_with("step 3 sees it");
        EXPECT_TRUE(seen || event.detail.ends_with("step 3 hides it")) << where << ": " << event.detail;
        EXPECT_EQ(visibleAt(0.5 * (event.u + next)), seen) << where << " at u = " << event.u;
        ++placesChecked;
      }
      for (std::size_t i = 1; i < pieces.size(); ++i)
        EXPECT_TRUE(std::any_of(recorded.begin(), recorded.end(), [&](double u) { return std::abs(u - pieces[i].begin) < 1e-12; }))
            << where << ": no event where its piece from u = " << pieces[i].begin << " begins";
    }
  }
  EXPECT_GT(crossingsChecked, 20) << "too few crossings to test anything";
  EXPECT_GT(placesChecked, 60);
}

TEST(FloatingHorizon, FinerColumnsNeverCostAccuracyOnTheRipple) {
  const auto loaded = load("ripple");
  const double coarse = judge(loaded.prepared, {{"columns", "5%"}}).error.error;
  const double fine = judge(loaded.prepared).error.error;
  EXPECT_GT(coarse, fine);
}

TEST(FloatingHorizon, RefusesWhatItCannotOrder) {
  const auto refusalOf = [](test::LoadedScene& loaded) {
    const AlgorithmEntry& entry = findAlgorithm("floating_horizon");
    return entry.refusal(loaded.prepared, resolveKnobs(entry, {}));
  };
  auto cube = test::LoadedScene(test::sourcePath("scenes/cube.toml"));
  EXPECT_NE(refusalOf(cube).find("one height-field object"), std::string::npos);

  auto rolled = load("ripple");
  rolled.scene.camera.up = glm::normalize(rolled.scene.camera.up + 0.2 * glm::cross(rolled.scene.camera.target - rolled.scene.camera.eye, rolled.scene.camera.up));
  EXPECT_NE(refusalOf(rolled).find("no camera roll"), std::string::npos);

  auto above = load("hard/fh_holes");  // perspective
  above.scene.camera.eye = dvec3(0, 10, 0.3);
  above.scene.camera.up = dvec3(0, 0, -1);
  EXPECT_NE(refusalOf(above).find("eye outside the height field's footprint"), std::string::npos);
}

}  // namespace
}  // namespace hsr
