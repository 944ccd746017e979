// The fixed-point triangle rasterizer shared by every surface algorithm.
//
// Vertices are snapped to 1/256 pixel; each edge is an integer edge function
// E(x, y) = A x + B y + C in 64 bits, positive inside. A pixel is covered when its
// center makes all three non-negative after the top-left bias (conventions.hpp), so
// coverage is exact: shared edges get every pixel center once, with no cracks.
#pragma once

#include <cstdint>

#include "renderer/conventions.hpp"
#include "renderer/math.hpp"

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

// Calls covered(x) for every pixel x in [xBegin, xEnd) of `row` whose center the
// triangle covers. The caller keeps [xBegin, xEnd) inside [minX, maxX]. Edge functions
// are evaluated exactly at the span's start and stepped exactly in integers, so the
// result does not depend on how the image is cut into spans.
template <typename Covered>
inline void rasterizeSpan(const ScreenTriangle& tri, int row, int xBegin, int xEnd, Covered&& covered) {
  using conventions::kSubpixelScale;
  const std::int64_t py = row * kSubpixelScale + kSubpixelScale / 2;
  const std::int64_t px = xBegin * kSubpixelScale + kSubpixelScale / 2;
  std::int64_t e0 = tri.edgeA[0] * px + tri.edgeB[0] * py + tri.edgeC[0];
  std::int64_t e1 = tri.edgeA[1] * px + tri.edgeB[1] * py + tri.edgeC[1];
  std::int64_t e2 = tri.edgeA[2] * px + tri.edgeB[2] * py + tri.edgeC[2];
  const std::int64_t step0 = tri.edgeA[0] * kSubpixelScale;
  const std::int64_t step1 = tri.edgeA[1] * kSubpixelScale;
  const std::int64_t step2 = tri.edgeA[2] * kSubpixelScale;
  for (int x = xBegin; x < xEnd; ++x) {
    if ((e0 | e1 | e2) >= 0) covered(x);  // all three non-negative: no sign bit set
    e0 += step0;
    e1 += step1;
    e2 += step2;
  }
}

}  // namespace hsr
