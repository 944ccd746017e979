// Weiler-Atherton: its visible pieces, scan-converted, show what sampling every pixel on
// its own shows, bit for bit (shipped scenes, hard cases, random scenes), and no pixel
// twice; its polygons are the visible surfaces' outlines, their areas the pixels' count;
// each step of the textbook (clipping, removal behind, recursion, cuts by depth) is
// counted where a scene calls for it; it refuses a scene over its budget.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "property/random_scene.hpp"
#include "renderer/image/polygon_svg.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

struct Answer {
  Visibility visibility;
  Stats stats;
};

Answer clipped(const PreparedScene& scene, int threads = 1) {
  Answer answer{{Frame(scene.width(), scene.height()), std::nullopt}, {}};
  const AlgorithmEntry& entry = findAlgorithm("weiler_atherton");
  entry.visibility({scene, scene.camera(), nullptr, threads, answer.stats}, resolveKnobs(entry, {}), answer.visibility);
  return answer;
}

// Every shipped scene and hard case (slivers, shared edges, coordinates far from the
// origin, cycles, planes through each other) at an odd size: the same ids and depths
// as the per-pixel loop, and no pixel claimed by two visible pieces (pieces that
// overlapped would be a wrong removal that the last writer happened to hide).
TEST(WeilerAtherton, SameImageAsSamplingEveryPixelOnItsOwn) {
  for (const auto& path : test::shippedScenes()) {
    if (test::isStudyLevel(path)) continue;
    const test::LoadedScene loaded(path, 317);
    const Answer answer = clipped(loaded.prepared);
    test::expectSameAsSampledOneByOne(answer.visibility.frame, test::sampledOneByOne(loaded.prepared),
                                      "weiler_atherton on " + path.filename().string());
    EXPECT_EQ(answer.stats.counter("pixels claimed twice"), 0) << path;
  }
}

// The property generator's thousand random scenes (slivers, coplanar pairs,
// interpenetrating triangles, perspective and orthographic cameras) at 150 x 101.
TEST(WeilerAtherton, SameImageAsSamplingEveryPixelOnItsOwnOnRandomScenes) {
  for (std::uint64_t seed = 1; seed <= 1000; ++seed) {
    const test::RandomScene random = test::randomScene(seed);
    PreparedScene prepared(random.scene);
    prepared.setSize(150, 101);
    const Answer answer = clipped(prepared);
    const Frame sampled = test::sampledOneByOne(prepared);
    ASSERT_EQ(answer.visibility.frame.ids, sampled.ids) << "seed " << seed << " (camera " << random.camera << ")";
    ASSERT_TRUE(test::sameDepthBits(answer.visibility.frame, sampled)) << "seed " << seed;
    ASSERT_EQ(answer.stats.counter("pixels claimed twice"), 0) << "seed " << seed;
  }
}

TEST(WeilerAtherton, SameBitsPolygonsAndCountersOnAnyThreadCount) {
  const test::LoadedScene loaded(test::sourcePath("scenes/counters.toml"), 320);
  const Answer one = clipped(loaded.prepared, 1);
  for (const int threads : {2, 3}) {
    const Answer many = clipped(loaded.prepared, threads);
    EXPECT_EQ(one.visibility.frame.ids, many.visibility.frame.ids) << threads << " threads";
    EXPECT_TRUE(test::sameDepthBits(one.visibility.frame, many.visibility.frame));
    ASSERT_EQ(one.visibility.polygons.size(), many.visibility.polygons.size());
    for (std::size_t p = 0; p < one.visibility.polygons.size(); ++p)
      EXPECT_EQ(one.visibility.polygons[p].corners, many.visibility.polygons[p].corners) << p;
    for (const std::string& counter : one.stats.counterNames()) EXPECT_EQ(one.stats.counter(counter), many.stats.counter(counter)) << counter;
  }
}

// The area of a convex polygon within the image's rectangle (clipped to it first).
double areaInImage(std::vector<dvec2> polygon, double width, double height) {
  const auto clipTo = [&](auto inside, auto crossing) {
    std::vector<dvec2> kept;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const dvec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
      if (inside(a)) kept.push_back(a);
      if (inside(a) != inside(b)) kept.push_back(crossing(a, b));
    }
    polygon = kept;
  };
  const auto atX = [](double x) { return [x](dvec2 a, dvec2 b) { return a + (b - a) * ((x - a.x) / (b.x - a.x)); }; };
  const auto atY = [](double y) { return [y](dvec2 a, dvec2 b) { return a + (b - a) * ((y - a.y) / (b.y - a.y)); }; };
  clipTo([](dvec2 p) { return p.x >= 0; }, atX(0));
  clipTo([&](dvec2 p) { return p.x <= width; }, atX(width));
  clipTo([](dvec2 p) { return p.y >= 0; }, atY(0));
  clipTo([&](dvec2 p) { return p.y <= height; }, atY(height));
  double twiceArea = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const dvec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    twiceArea += a.x * b.y - b.x * a.y;
  }
  return std::abs(twiceArea) / 2;
}

// The polygons are the visible surfaces, each once: within the image their areas add up
// to the pixels the image shows covered, less than a pixel's worth off per ten pixels
// of outline (sampling at centers). Polygons that overlapped, or left a hidden part in,
// would add area no pixel shows; a visible part left out would take area away. Scenes
// of pieces larger than a pixel: the drawing leaves out pieces no pixel center lies in,
// which on the counters' far detail is 2.6% of the covered area.
TEST(WeilerAtherton, ThePolygonsCoverWhatThePixelsShowOnce) {
  for (const char* name : {"scenes/blocks.toml", "scenes/hard/crossing_blinds.toml", "scenes/hard/cyclic_overlap.toml",
                           "scenes/hard/interpenetrating.toml", "scenes/hard/touching_boxes.toml"}) {
    const test::LoadedScene loaded(test::sourcePath(name), 400);
    const Answer answer = clipped(loaded.prepared);
    const Frame& frame = answer.visibility.frame;
    double area = 0;
    for (const VisiblePolygon& polygon : answer.visibility.polygons) area += areaInImage(polygon.corners, frame.width, frame.height);
    const auto covered = static_cast<double>(frame.pixelCount()) -
                         static_cast<double>(std::count(frame.ids.begin(), frame.ids.end(), conventions::kBackgroundId));
    EXPECT_NEAR(area, covered, 0.01 * covered) << name;
    EXPECT_EQ(static_cast<std::int64_t>(answer.visibility.polygons.size()), answer.stats.counter("visible pieces") -
                                                                                 answer.stats.counter("visible pieces with no pixel"))
        << name;
  }
}

// Scenes in pixel units (test::pixelCamera), 64 x 48, for the textbook's steps.
Answer ofMeshes(const std::vector<Mesh>& meshes) {
  const Scene scene = test::sceneOf(test::pixelCamera(48), 64, 48, meshes);
  const PreparedScene prepared(scene);
  Answer answer = clipped(prepared);
  const Frame sampled = test::sampledOneByOne(prepared);
  EXPECT_EQ(answer.visibility.frame.ids, sampled.ids);
  EXPECT_TRUE(test::sameDepthBits(answer.visibility.frame, sampled));
  EXPECT_EQ(answer.stats.counter("pixels claimed twice"), 0);
  return answer;
}

TEST(WeilerAtherton, TheNearestPolygonClipsWhatIsBehindItAway) {
  // A small triangle in front of a large one (larger z is nearer): the small one clips
  // first (nearest in the sort), the large one's piece inside it is behind and removed,
  // its outside is cut in convex pieces that stay visible.
  const Answer answer = ofMeshes({test::triangleMesh({{-5, -5, 1}, {5, -5, 1}, {0, 5, 1}}),
                                  test::triangleMesh({{-20, -20, -1}, {20, -20, -1}, {0, 20, -1}})});
  EXPECT_EQ(answer.stats.counter("pieces hidden"), 1);
  EXPECT_EQ(answer.stats.counter("recursions"), 0);
  EXPECT_EQ(answer.stats.counter("pieces clipped"), 1);
  EXPECT_EQ(answer.stats.counter("visible pieces"), 4);  // the small one, and the large one outside it in three
}

TEST(WeilerAtherton, APieceFoundInFrontOfTheClipPolygonClipsInTurn) {
  // A long thin triangle nearest at one end (so first in the sort) but tilted behind a
  // small one in front of its far end: clipping by the long one finds the small one in
  // front inside it, and the inside list is clipped again by the small one.
  const Answer answer = ofMeshes({test::triangleMesh({{-30, -3, 2}, {30, -3, -2}, {30, 3, -2}}),
                                  test::triangleMesh({{20, -5, 0}, {28, -5, 0}, {24, 5, 0}})});
  EXPECT_EQ(answer.stats.counter("recursions"), 1);
  EXPECT_EQ(answer.stats.counter("deepest recursion"), 1);
  EXPECT_GT(answer.stats.counter("pieces hidden"), 0);
}

// A cone seen from its tip: eight triangles of one mesh around a vertex. Outlines lie
// half a sub-pixel unit outside their triangles, so triangles meeting only at the tip
// overlap there, in a sliver no pixel center is in: cutting would leave slivers that
// show nothing. No triangle is cut; each is one visible piece.
TEST(WeilerAtherton, TrianglesOverlappingBetweenPixelCentersAreNotCut) {
  Mesh cone;
  cone.positions.push_back({0.3, 0.2, 1});
  for (int k = 0; k < 8; ++k) {
    const double angle = (45.0 * k + 10.0) * std::numbers::pi / 180.0;
    cone.positions.push_back({0.3 + 15 * std::cos(angle), 0.2 + 15 * std::sin(angle), 0});
  }
  for (std::uint32_t k = 0; k < 8; ++k) cone.triangles.push_back({0, k + 1, (k + 1) % 8 + 1});
  const Answer answer = ofMeshes({cone});
  EXPECT_GT(answer.stats.counter("cuts undone"), 0);
  EXPECT_EQ(answer.stats.counter("pieces clipped"), 0);
  EXPECT_EQ(answer.stats.counter("visible pieces"), 8);
  EXPECT_EQ(answer.stats.counter("visible pieces with no pixel"), 0);
}

// Pixel centers are at half-integer x and y here. A sliver whose box holds the center
// (0.5, 0.5), passing above it, is dropped before it clips anything (the geometry stage
// keeps it: it drops only triangles whose box holds no center); a strip of the large
// triangle between rows of centers, left outside a clip polygon, is dropped as it is
// cut off.
TEST(WeilerAtherton, PiecesHoldingNoPixelCenterAreDropped) {
  const Mesh large = test::triangleMesh({{-20, -10.1, -1}, {20, -10.1, -1}, {0, 20, -1}});
  const Answer between = ofMeshes({test::triangleMesh({{0, 0.2, 1}, {1, 1, 1}, {0.8, 1, 1}}), large});
  EXPECT_EQ(between.stats.counter("screen triangles"), 2);
  EXPECT_EQ(between.stats.counter("pieces with no pixel dropped"), 1);
  EXPECT_EQ(between.stats.counter("clip polygons"), 1);
  EXPECT_EQ(between.stats.counter("visible pieces"), 1);
  // The clip polygon's lower edge is 0.15 above the large one's: the strip between them
  // holds no row of centers; left and right of the clip polygon hold some.
  const Answer strip = ofMeshes({test::triangleMesh({{-5, -9.95, 1}, {5, -9.95, 1}, {0, 5, 1}}), large});
  EXPECT_EQ(strip.stats.counter("pieces with no pixel dropped"), 1);
  EXPECT_EQ(strip.stats.counter("pieces hidden"), 1);
  EXPECT_EQ(strip.stats.counter("visible pieces"), 3);  // the clip polygon, the large one left and right of it
  EXPECT_EQ(strip.stats.counter("visible pieces with no pixel"), 0);
}

// A part inside that holds no center but is no sliver is cut off all the same, so that
// the drawing does not show the piece behind over the clip polygon: the triangle behind
// overlaps the one in front in a band 0.8 pixels high and 60 long between two rows of
// centers; its polygon is drawn below the band only (to the sub-pixel unit its corners
// are snapped to).
TEST(WeilerAtherton, AWidePartInsideHoldingNoPixelCenterIsCutOff) {
  const Answer answer = ofMeshes({test::triangleMesh({{-30, -0.4, 1}, {30, -0.4, 1}, {0, 14, 1}}),
                                  test::triangleMesh({{-30, 0.4, 0}, {0, -12, 0}, {30, 0.4, 0}})});
  EXPECT_EQ(answer.stats.counter("cuts undone"), 0);
  EXPECT_EQ(answer.stats.counter("pieces clipped"), 1);
  EXPECT_EQ(answer.stats.counter("pieces with no pixel dropped"), 3);  // the band inside, and its ends beyond the sides
  EXPECT_EQ(answer.stats.counter("visible pieces"), 2);
  for (const VisiblePolygon& polygon : answer.visibility.polygons) {
    if (polygon.triangle != 1) continue;
    for (const dvec2& corner : polygon.corners) EXPECT_GT(corner.y, 24.4 - 1.0 / 256);  // world y = 24 - pixel y
  }
}

TEST(WeilerAtherton, PolygonsThroughEachOtherAreKeptWhereEachIsNearer) {
  // test::crossingPlanes: each is cut by depth against the other and keeps its side.
  const Answer answer = ofMeshes(test::crossingPlanes());
  EXPECT_EQ(answer.stats.counter("pieces cut by depth"), 2);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) EXPECT_EQ(answer.visibility.frame.ids[std::size_t(y * 64 + x)], x < 37 ? 2u : 1u) << x << ", " << y;
  // The drawing's outlines meet at the crossing: the right plane's polygon (triangle 0)
  // starts there, the left one's ends there.
  ASSERT_EQ(answer.visibility.polygons.size(), 2u);
  for (const VisiblePolygon& polygon : answer.visibility.polygons) {
    const double side = polygon.triangle == 0 ? 1 : -1;
    std::size_t onTheCrossing = 0;
    for (const dvec2& corner : polygon.corners) {
      EXPECT_GT(side * (corner.x - 37.3), -1e-6) << polygon.triangle;
      onTheCrossing += std::abs(corner.x - 37.3) < 1e-6;
    }
    EXPECT_EQ(onTheCrossing, 2u) << polygon.triangle;
  }
}

TEST(WeilerAtherton, TheSvgHasOnePolygonPerVisiblePieceInTheImagesColours) {
  const test::LoadedScene loaded(test::sourcePath("scenes/cube.toml"), 160);
  Stats stats;
  const pipeline::Rendered rendered = pipeline::render(loaded.prepared, pipeline::configurationOf(findAlgorithm("weiler_atherton"), {}), 1, stats);
  const std::string svg = visiblePolygonsSvg(rendered.polygons, rendered.frame);
  std::size_t count = 0;
  for (std::size_t at = svg.find("<polygon"); at != std::string::npos; at = svg.find("<polygon", at + 1)) ++count;
  EXPECT_EQ(count, rendered.polygons.size());
  EXPECT_GE(count, 3u);  // three faces of the cube show
  // The first polygon's fill is its triangle's mean colour in the image.
  const std::uint32_t id = rendered.polygons.front().triangle + 1;
  std::array<double, 3> sum{};
  double pixels = 0;
  for (std::size_t p = 0; p < rendered.frame.pixelCount(); ++p)
    if (rendered.frame.ids[p] == id) {
      for (std::size_t c = 0; c < 3; ++c) sum[c] += rendered.frame.color[4 * p + c];
      ++pixels;
    }
  ASSERT_GT(pixels, 0);
  char fill[64];
  std::snprintf(fill, sizeof fill, "fill=\"rgb(%d,%d,%d)\"", int(std::lround(sum[0] / pixels)), int(std::lround(sum[1] / pixels)),
                int(std::lround(sum[2] / pixels)));
  const std::size_t first = svg.find("<polygon");
  EXPECT_NE(svg.find(fill, first), std::string::npos) << fill;
  EXPECT_LT(svg.find(fill, first), svg.find("<polygon", first + 1));
}

TEST(WeilerAtherton, RefusesAScenePastItsBudgetNamingTheKnob) {
  const test::LoadedScene loaded(test::sourcePath("scenes/cube.toml"), 64);
  const AlgorithmEntry& entry = findAlgorithm("weiler_atherton");
  EXPECT_EQ(entry.refusal(loaded.prepared, resolveKnobs(entry, {})), "");
  const std::string refusal = entry.refusal(loaded.prepared, resolveKnobs(entry, {{"budget", "11"}}));
  EXPECT_NE(refusal.find("12 triangles"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("--knob budget=11"), std::string::npos) << refusal;
}

}  // namespace
}  // namespace hsr
