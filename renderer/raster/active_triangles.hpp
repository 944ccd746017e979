// The bookkeeping every scanline algorithm does: going down the image a row at a time,
// which triangles span the current row. An edge table (the triangles bucketed by the
// first row they cover) feeds an active list (those spanning the current row), from
// which each row admits the triangles starting on it and retires those that ended
// above it. The list stays in submission order, so ties between equal depths resolve
// as in the full-frame algorithms.
#pragma once

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <span>
#include <vector>

#include "renderer/raster/raster.hpp"

namespace hsr {

// The edge table: for each row, the triangles whose first row it is, in submission order.
inline std::vector<std::vector<std::uint32_t>> trianglesByFirstRow(std::span<const ScreenTriangle> triangles, int height) {
  std::vector<std::vector<std::uint32_t>> startingAt(static_cast<std::size_t>(height));
  for (std::uint32_t i = 0; i < triangles.size(); ++i) startingAt[std::size_t(triangles[i].minY)].push_back(i);
  return startingAt;
}

// The active list of one band of rows, walked from its first row down.
class ActiveTriangles {
 public:
  // The band starts at firstRow: the triangles that began above it and reach into it
  // are active from the start.
  ActiveTriangles(std::span<const ScreenTriangle> triangles, const std::vector<std::vector<std::uint32_t>>& startingAt,
                  std::size_t firstRow)
      : triangles_(triangles), startingAt_(startingAt) {
    for (std::uint32_t i = 0; i < triangles.size(); ++i)
      if (std::size_t(triangles[i].minY) < firstRow && std::size_t(triangles[i].maxY) >= firstRow) active_.push_back(i);
  }

  // Moves to row y (each row of the band in turn): retires the triangles that ended
  // above it and admits those starting on it. Returns how many entered.
  std::size_t advanceTo(std::size_t y) {
    std::erase_if(active_, [&](std::uint32_t i) { return std::size_t(triangles_[i].maxY) < y; });
    const auto& starting = startingAt_[y];
    merged_.clear();
    std::merge(active_.begin(), active_.end(), starting.begin(), starting.end(), std::back_inserter(merged_));
    active_.swap(merged_);
    return starting.size();
  }

  // The triangles spanning the current row, in submission order (indices into the triangles).
  const std::vector<std::uint32_t>& active() const { return active_; }

 private:
  std::span<const ScreenTriangle> triangles_;
  const std::vector<std::vector<std::uint32_t>>& startingAt_;
  std::vector<std::uint32_t> active_, merged_;
};

}  // namespace hsr
