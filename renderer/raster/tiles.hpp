// Screen tiles: the unit of parallel work of the tile-parallel rasterizing algorithms.
// One thread owns a tile at a time, and within a tile the items are drawn in their
// submission order, so the image is the same for any thread count.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "renderer/raster/raster.hpp"

namespace hsr {

struct TileGrid {
  static constexpr int kTileSize = 64;  // pixels per side of a tile
  int width, height, tileSize, tileShift, tilesX, tilesY;

  // tileSize: kTileSize, or a tile as large as the image to draw it in one submission-ordered
  // pass (what a step-by-step recording watches). Rounded up to a power of two (a tile
  // is cut at the image's edges anyway), so that a pixel's tile is a shift away, not a
  // division: binning's four divisions a triangle took 7-9% of dragons' rasterization.
  TileGrid(int imageWidth, int imageHeight, int tileSize_ = kTileSize)
      : width(imageWidth),
        height(imageHeight),
        tileSize(int(std::bit_ceil(unsigned(tileSize_)))),
        tileShift(std::countr_zero(unsigned(tileSize))),
        tilesX((imageWidth + tileSize - 1) >> tileShift),
        tilesY((imageHeight + tileSize - 1) >> tileShift) {}
  std::size_t count() const { return std::size_t(tilesX) * std::size_t(tilesY); }

  // A tile's pixels: [x0, x1) x [y0, y1).
  struct Rect {
    int x0, y0, x1, y1;
  };
  // The pixels of the largest tile (tiles at the image's right and bottom edges are cut).
  std::size_t largestTileArea() const { return std::size_t(std::min(tileSize, width)) * std::size_t(std::min(tileSize, height)); }
  Rect rect(std::size_t tile) const {
    const int x0 = int(tile % std::size_t(tilesX)) * tileSize, y0 = int(tile / std::size_t(tilesX)) * tileSize;
    return {x0, y0, std::min(x0 + tileSize, width), std::min(y0 + tileSize, height)};
  }

  // Binning: for each tile, the indices of the items whose screen triangle's pixel box
  // overlaps it, in submission order. triangleOf(i) is item i's ScreenTriangle.
  template <typename TriangleOf>
  std::vector<std::vector<std::uint32_t>> bin(std::size_t items, TriangleOf&& triangleOf) const {
    std::vector<std::vector<std::uint32_t>> bins(count());
    for (std::uint32_t i = 0; i < items; ++i) {
      const ScreenTriangle& tri = triangleOf(i);
      for (int ty = tri.minY >> tileShift; ty <= tri.maxY >> tileShift; ++ty)
        for (int tx = tri.minX >> tileShift; tx <= tri.maxX >> tileShift; ++tx) bins[std::size_t(ty * tilesX + tx)].push_back(i);
    }
    return bins;
  }
};

}  // namespace hsr
