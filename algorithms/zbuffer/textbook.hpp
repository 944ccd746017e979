// The z-buffer as the textbooks give it (Catmull 1974), on one tile of the image:
//
//   1. clear the depth buffer to the far end of the depth range, and every pixel's id
//      to the background;
//   2. for every triangle, in the order they are submitted, and every pixel whose center
//      it covers: compute the triangle's depth there, and keep the fragment (its depth
//      and id) if it is nearer than what the pixel holds;
//   3. the depth buffer now holds, at every pixel, the nearest depth drawn there: when a
//      later stage asks for distances (fog, an outline, a --depth image, a metric), decode
//      it to a distance along the view axis; until then it stays as the format stored it.
//
// drawTile below is steps 1 and 2, decodeRows step 3. Everything around them is machinery
// (full_frame.cpp): the image cut into tiles drawn in parallel (a tile's triangles in
// submission order, so the image is the same for any number of threads), the fast path
// that draws a tile's large triangles eight pixels at a time (fast_path.hpp, the same
// bits), the depth buffer kept for step 3 (Frame::distances), and --steps' pictures.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>

#include "algorithms/zbuffer/zbuffer.hpp"
#include "renderer/raster/raster.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "renderer/raster/tiles.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/source_location.hpp"
#include "renderer/util/simd.hpp"

namespace hsr::zbuffer {

// One tile: its pixels, the triangles binned to it (indices into geometry.triangles, in
// submission order), where its depth values live, the frame it fills and the test.
template <typename Format>
struct Tile {
  TileGrid::Rect area;
  const ScreenGeometry& geometry;
  std::span<const std::uint32_t> triangles;
  DepthBuffer<typename Format::Stored> depth;
  Frame& frame;
  DepthTest<Format>& test;

  std::size_t pixel(int x, int y) const { return std::size_t(y) * std::size_t(frame.width) + std::size_t(x); }
  // The drawn-th triangle, asking for the one a few ahead meanwhile: a tile's triangles
  // lie scattered through the scene's list (a mesh's triangles fall into many tiles), and
  // each would otherwise wait on a cache miss (on dragons, most of the pass; 4 ahead
  // 6.10 ms, 8 ahead 5.68, 16 ahead 5.86).
  const ScreenTriangle& triangle(std::size_t drawn) const {
    constexpr std::size_t kPrefetchAhead = 8;
    if (drawn + kPrefetchAhead < triangles.size()) prefetch(geometry.triangles[triangles[drawn + kPrefetchAhead]]);
    return geometry.triangles[triangles[drawn]];
  }
};

// What watches the loop after each triangle: nothing, or --steps' pictures (full_frame.cpp),
// told where in the loop it was called from (the steps page shows those lines).
class TileWatcher {
 public:
  virtual void drawn(std::size_t index, const ScreenTriangle& tri, SourceLocation where = SourceLocation::current()) = 0;

 protected:
  ~TileWatcher() = default;
};

// Step 1: the depth buffer cleared to the far end of the format, the ids to background.
template <typename Format>
void clearTile(const Tile<Format>& tile) {
  const auto [x0, y0, x1, y1] = tile.area;
  for (int y = y0; y < y1; ++y) {
    // BEGIN SOLUTION
    std::fill_n(&tile.depth.at(x0, y), x1 - x0, Format::kFar);
    std::fill_n(&tile.frame.ids[tile.pixel(x0, y)], x1 - x0, conventions::kBackgroundId);
    // SKELETON
    // // Exercise 1: clear row y of the tile, from x0 to x1: its depths (tile.depth.at(x, y))
    // // to the far end of the format, its ids (tile.frame.ids[tile.pixel(x, y)]) to the
    // // background. Which constant of Format is the far end, and why not 0?
    // (void)x0, (void)x1;
    // END SOLUTION
  }
}

// Step 2, for one triangle: every pixel of the tile whose center it covers
// (rasterizeSpan: the top-left rule), its fragment kept if nearer (DepthTest::test,
// zbuffer.hpp: ties keep the earlier triangle).
template <typename Format>
void depthTestTriangle(const Tile<Format>& tile, const ScreenTriangle& tri) {
  const auto [x0, y0, x1, y1] = tile.area;
  // BEGIN SOLUTION
  const int left = std::max(tri.minX, x0), right = std::min(tri.maxX + 1, x1);
  for (int y = std::max(tri.minY, y0); y < std::min(tri.maxY + 1, y1); ++y)
    rasterizeSpan(tri, y, left, right, [&](int x) { tile.test.test(tri, x, y, tile.depth.at(x, y), tile.frame.ids[tile.pixel(x, y)]); });
  // SKELETON
  // // Exercise 1: every row of the triangle's pixel box (tri.minY to tri.maxY, tri.minX to
  // // tri.maxX) that lies in the tile (x0 to x1, y0 to y1, ends excluded): rasterizeSpan
  // // (renderer/raster/raster.hpp) calls you back for each pixel whose center the
  // // triangle covers; there, tile.test.test decides the fragment.
  // (void)tri, (void)x0, (void)y0, (void)x1, (void)y1;
  // END SOLUTION
}

// The loop: step 1, then step 2 for every triangle in the order they were submitted.
template <typename Format>
void drawTile(const Tile<Format>& tile, TileWatcher* watcher) {
  clearTile(tile);
  for (std::size_t drawn = 0; drawn < tile.triangles.size(); ++drawn) {
    const ScreenTriangle& tri = tile.triangle(drawn);
    depthTestTriangle(tile, tri);
    if (watcher) watcher->drawn(drawn, tri);
  }
}

// Step 3, for the rows `rows` of a frame as wide as `stored`'s stride: what the format
// stored, decoded to a distance along the view axis (+infinity on the background).
template <typename Format>
void decodeRows(const DepthTest<Format>& test, const CameraTransform& camera, DepthBuffer<const typename Format::Stored> stored,
                std::span<const std::uint32_t> ids, std::span<float> distance, std::pair<int, int> rows) {
  const int width = int(stored.stride);
  for (int y = rows.first; y < rows.second; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t pixel = std::size_t(y) * stored.stride + std::size_t(x);
      distance[pixel] = test.distance(ids[pixel], stored.at(x, y), camera);
    }
}

}  // namespace hsr::zbuffer
