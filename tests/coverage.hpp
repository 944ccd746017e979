// Counts how many times the shared rasterizer covers each pixel, per triangle facing:
// the raw coverage, before any depth test, for the watertightness tests.
#pragma once

#include <vector>

#include "renderer/raster/screen_triangles.hpp"

namespace hsr::test {

struct Coverage {
  int width = 0, height = 0;
  std::vector<int> front, back;  // per pixel: covering front-facing / back-facing triangles
  int at(const std::vector<int>& layer, int x, int y) const { return layer[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

// Only triangles whose global index is in [firstTriangle, endTriangle) are counted.
inline Coverage rasterCoverage(const PreparedScene& scene, std::uint32_t firstTriangle, std::uint32_t endTriangle) {
  Stats stats;
  const ScreenGeometry geometry = buildScreenTriangles(scene, {}, 1, stats);
  Coverage coverage{scene.width(), scene.height(), {}, {}};
  coverage.front.assign(std::size_t(scene.width()) * std::size_t(scene.height()), 0);
  coverage.back = coverage.front;
  for (const ScreenTriangle& tri : geometry.triangles) {
    if (tri.triangle < firstTriangle || tri.triangle >= endTriangle) continue;
    std::vector<int>& layer = tri.frontFacing ? coverage.front : coverage.back;
    for (int y = tri.minY; y <= tri.maxY; ++y)
      rasterizeSpan(tri, y, tri.minX, tri.maxX + 1, [&](int x) { ++layer[std::size_t(y) * std::size_t(scene.width()) + std::size_t(x)]; });
  }
  return coverage;
}

}  // namespace hsr::test
