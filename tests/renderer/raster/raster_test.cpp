// Properties of the fixed-point rasterizer: watertight coverage of shared edges,
// exactness at the extremes of the coordinate range.
#include <gtest/gtest.h>

#include <random>

#include "coverage.hpp"
#include "renderer/raster/raster.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

__extension__ using Int128 = __int128;  // exact products of 30-bit differences, for the check only

// A jittered grid of quads, split along random diagonals, covering more than the view:
// every pixel center must be covered exactly once, whatever the vertex positions.
TEST(Raster, RandomMeshesCoverEveryPixelExactlyOnce) {
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);  // small enough that no quad folds over
  for (int trial = 0; trial < 20; ++trial) {
    const int cells = 6 + trial;
    const double cell = 80.0 / cells;  // the lattice spans [-40, 40]^2 around a 64 x 48 view
    Mesh mesh;
    for (int j = 0; j <= cells; ++j)
      for (int i = 0; i <= cells; ++i) {
        const bool border = i == 0 || j == 0 || i == cells || j == cells;
        mesh.positions.push_back({-40 + cell * (i + (border ? 0 : jitter(random))),
                                  -40 + cell * (j + (border ? 0 : jitter(random))), 0});
      }
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (cells + 1) + i); };
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i) {
        const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
        if (random() & 1) {
          mesh.triangles.push_back({a, b, c});
          mesh.triangles.push_back({a, c, d});
        } else {
          mesh.triangles.push_back({a, b, d});
          mesh.triangles.push_back({b, c, d});
        }
      }
    for (const Triangle& t : mesh.triangles)  // precondition: every triangle faces the camera
      ASSERT_GT(glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]], mesh.positions[t[2]] - mesh.positions[t[0]]).z, 0);
    const Scene scene = test::sceneOf(test::pixelCamera(48), 64, 48, {mesh});
    const PreparedScene prepared(scene);
    const test::Coverage coverage = test::rasterCoverage(prepared, 0, static_cast<std::uint32_t>(prepared.triangleCount()));
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x) {
        ASSERT_EQ(coverage.at(coverage.front, x, y), 1) << "trial " << trial << " pixel " << x << "," << y;
        ASSERT_EQ(coverage.at(coverage.back, x, y), 0);
      }
  }
}

// The edge functions must not overflow at the guard band's extremes: a triangle with
// corners 2^20 pixels out covers a pixel iff its center is inside (checked in exact
// integer arithmetic with 128-bit products here, independent of the rasterizer).
TEST(Raster, EdgeFunctionsExactAtTheGuardBand) {
  using conventions::kSubpixelScale;
  const std::int64_t far = std::int64_t(1) << (20 + conventions::kSubpixelBits);
  const std::int64_t x[3] = {-far, far, 40 * kSubpixelScale + 77};
  const std::int64_t y[3] = {-far + 3, -far / 2 + 1, far};
  const double t[3] = {1, 1, 1};
  dvec2 pixel[3];
  for (int k = 0; k < 3; ++k) pixel[k] = dvec2(double(x[k]), double(y[k])) / double(kSubpixelScale);  // exact: on the grid
  ScreenTriangle tri;
  ASSERT_TRUE(setupScreenTriangle(pixel, t, 128, 128, 0, tri));
  long checked = 0;
  for (int row = tri.minY; row <= tri.maxY; ++row) {
    std::vector<bool> covered(128, false);
    rasterizeSpan(tri, row, tri.minX, tri.maxX + 1, [&](int column) { covered[std::size_t(column)] = true; });
    for (int column = 0; column < 128; ++column) {
      const Int128 px = column * kSubpixelScale + kSubpixelScale / 2, py = row * kSubpixelScale + kSubpixelScale / 2;
      bool inside = true, onEdge = false;
      for (int k = 0; k < 3; ++k) {  // the winding here is clockwise on screen: edge values > 0 inside
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        const Int128 e = (Int128(x[b]) - x[a]) * (py - y[a]) - (Int128(y[b]) - y[a]) * (px - x[a]);
        inside = inside && e > 0;
        onEdge = onEdge || e == 0;
      }
      if (onEdge) continue;  // decided by the fill rule, tested in conventions_test
      EXPECT_EQ(covered[std::size_t(column)], inside) << column << "," << row;
      ++checked;
    }
  }
  EXPECT_GT(checked, 128 * 127);
}

}  // namespace
}  // namespace hsr

namespace hsr {
namespace {

// The two ways rasterizeSpan decides a span (per-pixel tests for narrow spans, solved
// ranges for wide ones) agree with an independent per-pixel check on random triangles
// of every size, cut into spans of random widths.
TEST(Raster, SolvedSpansMatchPerPixelTests) {
  std::mt19937 random(777);
  std::uniform_real_distribution<double> coordinate(-40, 200);
  std::uniform_int_distribution<int> cut(1, 40);
  long pixels = 0;
  for (int trial = 0; trial < 300; ++trial) {
    dvec2 corners[3];
    const double scale = trial % 3 == 0 ? 0.05 : 1.0;  // some tiny triangles too
    for (dvec2& c : corners) c = dvec2(coordinate(random), coordinate(random)) * scale + (trial % 3 == 0 ? 80.0 : 0.0);
    const double t[3] = {1, 1, 1};
    ScreenTriangle tri;
    if (!setupScreenTriangle(corners, t, 160, 160, 0, tri)) continue;
    for (int row = tri.minY; row <= tri.maxY; ++row) {
      std::vector<int> spans;
      for (int x = tri.minX; x <= tri.maxX;) {  // random span boundaries, like tiles
        const int end = std::min(tri.maxX + 1, x + cut(random));
        rasterizeSpan(tri, row, x, end, [&](int covered) { spans.push_back(covered); });
        x = end;
      }
      std::vector<int> expected;
      for (int x = tri.minX; x <= tri.maxX; ++x) {
        const std::int64_t px = x * conventions::kSubpixelScale + 128, py = row * conventions::kSubpixelScale + 128;
        bool inside = true;
        for (int k = 0; k < 3; ++k) inside = inside && tri.edgeA[k] * px + tri.edgeB[k] * py + tri.edgeC[k] >= 0;
        if (inside) expected.push_back(x);
      }
      ASSERT_EQ(spans, expected) << "trial " << trial << " row " << row;
      pixels += static_cast<long>(expected.size());
    }
  }
  EXPECT_GT(pixels, 100000);
}

}  // namespace
}  // namespace hsr
