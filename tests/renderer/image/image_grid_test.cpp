// The hidden-line algorithms' image grid: any two segments that cross share a cell, and
// any segment crossing a box shares a cell with it, also where both reach far outside
// the view (a ground plane's near edge projects to a hundred thousand pixels), and
// such geometry does not swell the cells inside the view.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "renderer/image/image_grid.hpp"

namespace hsr {
namespace {

const dvec2 kView(320, 180);

std::set<std::size_t> cellsOf(const ImageGrid& grid, const dvec2& a, const dvec2& b) {
  std::set<std::size_t> cells;
  grid.cellsOnSegment(a, b, [&](std::size_t cell) { cells.insert(cell); });
  return cells;
}

bool shareACell(const std::set<std::size_t>& a, const std::set<std::size_t>& b) {
  return std::any_of(a.begin(), a.end(), [&](std::size_t cell) { return b.count(cell) > 0; });
}

double cross(const dvec2& u, const dvec2& v) { return u.x * v.y - u.y * v.x; }

// Whether segments ab and cd cross at a point inside both, away from their ends (so that
// rounding cannot decide it).
bool clearlyCross(const dvec2& a, const dvec2& b, const dvec2& c, const dvec2& d) {
  const double denominator = cross(b - a, d - c);
  if (denominator == 0) return false;
  const double s = cross(c - a, d - c) / denominator, t = cross(c - a, b - a) / denominator;
  return s > 1e-6 && s < 1 - 1e-6 && t > 1e-6 && t < 1 - 1e-6;
}

// Endpoints mostly near the view, some a hundred thousand pixels away.
dvec2 randomPoint(std::mt19937_64& random) {
  std::uniform_real_distribution<double> near(-100, 420), far(-2e5, 2e5);
  std::bernoulli_distribution isFar(0.2);
  return {isFar(random) ? far(random) : near(random), isFar(random) ? far(random) : near(random)};
}

TEST(ImageGrid, CrossingSegmentsShareACellAlsoFarOutsideTheView) {
  std::mt19937_64 random(11);
  std::vector<std::pair<dvec2, dvec2>> segments(600);
  dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (auto& [a, b] : segments) {
    a = randomPoint(random), b = randomPoint(random);
    lo = glm::min(lo, glm::min(a, b)), hi = glm::max(hi, glm::max(a, b));
  }
  const ImageGrid grid(lo, hi, kView, 16);
  std::vector<std::set<std::size_t>> cells;
  for (const auto& [a, b] : segments) cells.push_back(cellsOf(grid, a, b));
  int crossings = 0;
  for (std::size_t i = 0; i < segments.size(); ++i)
    for (std::size_t j = i + 1; j < segments.size(); ++j)
      if (clearlyCross(segments[i].first, segments[i].second, segments[j].first, segments[j].second)) {
        ++crossings;
        ASSERT_TRUE(shareACell(cells[i], cells[j])) << "segments " << i << " and " << j << " cross but share no cell";
      }
  EXPECT_GT(crossings, 10000);  // the far segments cross each other outside the view too
}

TEST(ImageGrid, SegmentsThroughABoxShareOneOfItsCells) {
  std::mt19937_64 random(12);
  const ImageGrid grid(dvec2(-2e5), dvec2(2e5), kView, 16);
  for (int trial = 0; trial < 2000; ++trial) {
    const dvec2 a = randomPoint(random), b = randomPoint(random);
    const dvec2 corner = randomPoint(random), boxLo = glm::min(corner, corner + dvec2(40)), boxHi = boxLo + dvec2(40);
    // The segment's point nearest the box's center, when it lies inside the box.
    const dvec2 center = 0.5 * (boxLo + boxHi), along = b - a;
    const double t = std::clamp(glm::dot(center - a, along) / glm::dot(along, along), 0.0, 1.0);
    const dvec2 nearest = a + t * along;
    if (glm::any(glm::lessThan(nearest, boxLo)) || glm::any(glm::greaterThan(nearest, boxHi))) continue;
    std::set<std::size_t> box;
    grid.cellsInBox(boxLo, boxHi, [&](std::size_t cell) { box.insert(cell); });
    ASSERT_TRUE(shareACell(cellsOf(grid, a, b), box)) << "trial " << trial;
  }
}

TEST(ImageGrid, FarGeometryKeepsTheCellsInTheViewTheirSize) {
  // Without the reach limit, a span of 400,000 pixels in 1,024 cells would make cells
  // of 390 pixels: the whole view in one cell.
  const ImageGrid grid(dvec2(-2e5), dvec2(2e5), kView, 16);
  std::set<std::size_t> cells;
  grid.cellsInBox(dvec2(0), kView, [&](std::size_t cell) { cells.insert(cell); });
  // 320 x 180 pixels in 16-pixel cells: 20 x 12 at the least, one more each way where
  // the view's edges fall inside cells.
  EXPECT_GE(cells.size(), std::size_t(20 * 12));
  EXPECT_LE(cells.size(), std::size_t(21 * 13));
  EXPECT_LE(grid.cellCount(), std::size_t(ImageGrid::kMaxCellsPerSide) * ImageGrid::kMaxCellsPerSide);
}

}  // namespace
}  // namespace hsr
