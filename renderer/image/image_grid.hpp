// A uniform grid over a rectangle of the image plane that lists which items (edges,
// bodies) pass through each cell: the image-plane acceleration of the hidden-line
// algorithms (Roberts' screen grid, Appel's crossing search).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "renderer/util/math.hpp"

namespace hsr {

class ImageGrid {
 public:
  static constexpr int kMaxCellsPerSide = 1024;

  // Covers [lo, hi] with square cells of cellPixels (larger only when the view itself
  // would need more than kMaxCellsPerSide), as far as kMaxCellsPerSide cells around the
  // view's center reach. Geometry projected beyond that (a ground plane reaching under
  // the eye projects to hundreds of thousands of pixels) falls in the border cells,
  // which reach to infinity: cells grown to cover all of it would each hold a good part
  // of the view.
  ImageGrid(const dvec2& lo, const dvec2& hi, const dvec2& view, double cellPixels) {
    cell_ = std::max({cellPixels, view.x / kMaxCellsPerSide, view.y / kMaxCellsPerSide, 1e-9});
    const dvec2 reachLo = 0.5 * view - 0.5 * kMaxCellsPerSide * cell_, reachHi = 0.5 * view + 0.5 * kMaxCellsPerSide * cell_;
    origin_ = glm::clamp(lo, reachLo, reachHi);
    const dvec2 end = glm::max(origin_, glm::clamp(hi, reachLo, reachHi));
    columns_ = std::clamp(static_cast<int>(std::floor((end.x - origin_.x) / cell_)) + 1, 1, kMaxCellsPerSide);
    rows_ = std::clamp(static_cast<int>(std::floor((end.y - origin_.y) / cell_)) + 1, 1, kMaxCellsPerSide);
  }

  std::size_t cellCount() const { return std::size_t(columns_) * std::size_t(rows_); }

  // The cells a segment passes through: row by row, those between where it enters and
  // leaves the row (a superset near the ends).
  template <typename Visit>
  void cellsOnSegment(const dvec2& a, const dvec2& b, Visit&& visit) const {
    const int rowEnd = row(std::max(a.y, b.y));
    for (int r = row(std::min(a.y, b.y)); r <= rowEnd; ++r) {
      double x0 = a.x, x1 = b.x;
      if (a.y != b.y) {
        // The first and the last row reach to infinity.
        const double top = r == 0 ? -kEndless : origin_.y + r * cell_;
        const double bottom = r == rows_ - 1 ? kEndless : origin_.y + (r + 1) * cell_;
        const double t0 = std::clamp((top - a.y) / (b.y - a.y), 0.0, 1.0), t1 = std::clamp((bottom - a.y) / (b.y - a.y), 0.0, 1.0);
        x0 = a.x + t0 * (b.x - a.x);
        x1 = a.x + t1 * (b.x - a.x);
      }
      const int columnEnd = column(std::max(x0, x1));
      for (int c = column(std::min(x0, x1)); c <= columnEnd; ++c) visit(std::size_t(r) * columns_ + c);
    }
  }

  template <typename Visit>
  void cellsInBox(const dvec2& lo, const dvec2& hi, Visit&& visit) const {
    const int rowEnd = row(hi.y), columnEnd = column(hi.x);
    for (int r = row(lo.y); r <= rowEnd; ++r)
      for (int c = column(lo.x); c <= columnEnd; ++c) visit(std::size_t(r) * columns_ + c);
  }

  // Lists item i in every cell cellsOf(i, add) passes to add.
  template <typename CellsOf>
  void bin(std::size_t items, CellsOf&& cellsOf) {
    std::vector<std::uint32_t> fill(cellCount() + 1, 0);
    for (std::size_t i = 0; i < items; ++i) cellsOf(i, [&](std::size_t cell) { ++fill[cell + 1]; });
    for (std::size_t c = 1; c < fill.size(); ++c) fill[c] += fill[c - 1];
    first_ = fill;
    entries_.resize(first_.back());
    for (std::size_t i = 0; i < items; ++i)
      cellsOf(i, [&](std::size_t cell) { entries_[fill[cell]++] = static_cast<std::uint32_t>(i); });
  }

  template <typename Visit>
  void itemsIn(std::size_t cell, Visit&& visit) const {
    for (std::uint32_t i = first_[cell]; i < first_[cell + 1]; ++i) visit(entries_[i]);
  }

 private:
  static constexpr double kEndless = std::numeric_limits<double>::infinity();

  int row(double y) const { return std::clamp(static_cast<int>(std::floor((y - origin_.y) / cell_)), 0, rows_ - 1); }
  int column(double x) const { return std::clamp(static_cast<int>(std::floor((x - origin_.x) / cell_)), 0, columns_ - 1); }

  dvec2 origin_;
  double cell_;
  int columns_, rows_;
  std::vector<std::uint32_t> first_, entries_;
};

}  // namespace hsr
