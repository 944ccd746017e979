// The fixed-point triangle rasterizer shared by every surface algorithm.
//
// Vertices are snapped to 1/256 pixel; each edge is an integer edge function
// E(x, y) = A x + B y + C in 64 bits, positive inside. A pixel is covered when its
// center makes all three non-negative after the top-left bias (conventions.hpp), so
// coverage is exact: shared edges get every pixel center once, with no cracks.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "renderer/util/conventions.hpp"
#include "renderer/util/math.hpp"

namespace hsr {

// A triangle ready to rasterize: snapped, reordered if needed so that its corners run
// clockwise as seen on screen (positive orient2d in y-down image coordinates), with
// the plane of its screen-affine depth t.
struct ScreenTriangle {
  std::int64_t edgeA[3], edgeB[3], edgeC[3];  // E_k(X, Y) in sub-pixel units, top-left bias folded into C
  int minX, maxX, minY, maxY;                 // pixels whose centers may be covered, inside the image
  double x0, y0, t0, tdx, tdy;                // t(x, y) = t0 + tdx (x - x0) + tdy (y - y0), pixel units
  std::uint32_t triangle;                     // global triangle index (conventions.hpp)
  bool frontFacing;                           // counter-clockwise as seen, before reordering

  double depthAt(double px, double py) const { return t0 + tdx * (px - x0) + tdy * (py - y0); }
};

// Sets up a triangle from its corners in pixel coordinates and their t. Coverage uses
// the corners snapped to the sub-pixel grid; the depth plane uses them unsnapped, so
// coplanar triangles get the same depth wherever they overlap (exact ties, decided by
// submission order) instead of planes tilted apart by snapping. Returns false for a
// triangle with zero area after snapping, or whose box holds no pixel center of the
// width x height image. Corners must lie within the guard band (conventions.hpp).
bool setupScreenTriangle(const dvec2 pixel[3], const double t[3], int width, int height, std::uint32_t triangle,
                         ScreenTriangle& out);

// Spans wider than this are solved for their covered range; narrower ones test each
// pixel (three additions beat three integer divisions there). Both are exact.
inline constexpr int kSolveSpansWiderThan = 16;

// The pixels of `row` in [xBegin, xEnd) whose centers the triangle covers form one run
// (a triangle is convex): sets [first, last] to it and returns true, or returns false
// when there is none. Exact integer arithmetic, by solving each edge function for where
// it turns negative along the row. The caller keeps [xBegin, xEnd) inside [minX, maxX].
inline bool coveredRun(const ScreenTriangle& tri, int row, int xBegin, int xEnd, int& first, int& last) {
  using conventions::kSubpixelScale;
  const std::int64_t py = row * kSubpixelScale + kSubpixelScale / 2;
  const std::int64_t px = xBegin * kSubpixelScale + kSubpixelScale / 2;
  // Each edge function is linear along the row, e + step * i for the i-th pixel, so
  // "e + step * i >= 0" bounds i from below (step > 0) or above (step < 0).
  std::int64_t lo = 0, hi = xEnd - xBegin - 1;
  for (int k = 0; k < 3; ++k) {
    const std::int64_t e = tri.edgeA[k] * px + tri.edgeB[k] * py + tri.edgeC[k], step = tri.edgeA[k] * kSubpixelScale;
    if (step > 0) {
      if (e < 0) lo = std::max(lo, (-e + step - 1) / step);  // ceil(-e / step)
    } else if (step < 0) {
      if (e < 0) return false;  // negative at the start and falling: never inside on this row
      hi = std::min(hi, e / -step);  // floor(e / -step)
    } else if (e < 0) {
      return false;  // parallel to the row and outside
    }
  }
  first = xBegin + static_cast<int>(lo), last = xBegin + static_cast<int>(hi);
  return lo <= hi;
}

// Calls covered(x), in increasing x, for every pixel x in [xBegin, xEnd) of `row` whose
// center the triangle covers. The caller keeps [xBegin, xEnd) inside [minX, maxX].
// Everything is exact integer arithmetic evaluated from the span's own start, so the
// result does not depend on how the image is cut into spans.
template <typename Covered>
inline void rasterizeSpan(const ScreenTriangle& tri, int row, int xBegin, int xEnd, Covered&& covered) {
  using conventions::kSubpixelScale;
  if (xEnd - xBegin <= kSolveSpansWiderThan) {
    // Edge-function test at every pixel center: all three non-negative means no sign bit set.
    const std::int64_t py = row * kSubpixelScale + kSubpixelScale / 2;
    const std::int64_t px = xBegin * kSubpixelScale + kSubpixelScale / 2;
    std::int64_t e[3], step[3];
    for (int k = 0; k < 3; ++k) {
      e[k] = tri.edgeA[k] * px + tri.edgeB[k] * py + tri.edgeC[k];
      step[k] = tri.edgeA[k] * kSubpixelScale;
    }
    for (int x = xBegin; x < xEnd; ++x) {
      if ((e[0] | e[1] | e[2]) >= 0) covered(x);
      e[0] += step[0];
      e[1] += step[1];
      e[2] += step[2];
    }
    return;
  }
  int first, last;
  if (!coveredRun(tri, row, xBegin, xEnd, first, last)) return;
  for (int x = first; x <= last; ++x) covered(x);
}

// The line rule: a segment of width w covers the pixels whose centers lie within w / 2
// of it (a capsule: a rectangle with round caps). The decision is one distance test per
// pixel center, so a drawing's pixels depend only on its segments, never on the order
// or the tiling, and line goldens are stable. Calls covered(x, y) for each covered
// pixel of the width x height image.
inline double squaredDistanceToSegment(const dvec2& p, const dvec2& a, const dvec2& b) {
  const dvec2 ab = b - a;
  const double lengthSquared = glm::dot(ab, ab);
  const double t = lengthSquared > 0 ? std::clamp(glm::dot(p - a, ab) / lengthSquared, 0.0, 1.0) : 0.0;
  const dvec2 nearest = a + t * ab;
  return glm::dot(p - nearest, p - nearest);
}

template <typename Covered>
void rasterizeLine(const dvec2& a, const dvec2& b, double width, int imageWidth, int imageHeight, Covered&& covered) {
  const double radius = width / 2;
  const int top = std::max(0, static_cast<int>(std::floor(std::min(a.y, b.y) - radius)));
  const int bottom = std::min(imageHeight - 1, static_cast<int>(std::ceil(std::max(a.y, b.y) + radius)));
  const int left = std::max(0, static_cast<int>(std::floor(std::min(a.x, b.x) - radius)));
  const int right = std::min(imageWidth - 1, static_cast<int>(std::ceil(std::max(a.x, b.x) + radius)));
  const dvec2 ab = b - a;
  for (int y = top; y <= bottom; ++y) {
    const double yc = y + conventions::kPixelCenterOffset;
    // The capsule is convex, so its row is one interval; a generous one (the hull of
    // the segment's x over the band |y - yc| <= radius, widened by the slant) is enough,
    // since every pixel in it is decided by the distance test.
    int xBegin = left, xEnd = right;
    if (std::abs(ab.y) > 1e-12) {
      const double t0 = std::clamp((yc - radius - a.y) / ab.y, 0.0, 1.0), t1 = std::clamp((yc + radius - a.y) / ab.y, 0.0, 1.0);
      const double x0 = a.x + t0 * ab.x, x1 = a.x + t1 * ab.x;
      xBegin = std::max(left, static_cast<int>(std::floor(std::min(x0, x1) - 2 * radius)));
      xEnd = std::min(right, static_cast<int>(std::ceil(std::max(x0, x1) + 2 * radius)));
    }
    for (int x = xBegin; x <= xEnd; ++x)
      if (squaredDistanceToSegment({x + conventions::kPixelCenterOffset, yc}, a, b) <= radius * radius) covered(x, y);
  }
}

}  // namespace hsr
