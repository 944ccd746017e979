#include "renderer/raster/raster.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace hsr {
namespace {

// a / kSubpixelScale rounded down: an arithmetic shift, since the scale is a power of
// two (C++20 defines >> of a negative value so); a division with its sign correction
// was a sixth of the set-up's time.
std::int64_t subpixelsToPixelsDown(std::int64_t a) { return a >> conventions::kSubpixelBits; }
std::int64_t subpixelsToPixelsUp(std::int64_t a) { return -subpixelsToPixelsDown(-a); }

// Pixel indices whose centers (i + 0.5) lie in [low, high] (sub-pixel units), clamped to [0, size).
std::pair<int, int> centersWithin(std::int64_t low, std::int64_t high, int size) {
  using conventions::kSubpixelScale;
  const std::int64_t first = subpixelsToPixelsUp(low - kSubpixelScale / 2);
  const std::int64_t last = subpixelsToPixelsDown(high - kSubpixelScale / 2);
  return {static_cast<int>(std::clamp<std::int64_t>(first, 0, size)),
          static_cast<int>(std::clamp<std::int64_t>(last, -1, size - 1))};
}

// Rounds a pixel coordinate to the nearest sub-pixel step (ties to even), without a
// library call: adding 1.5 * 2^52 leaves no fraction bits, so the addition itself
// rounds. Exact for |pixel| < 2^43, far beyond the guard band.
std::int64_t snapToSubpixel(double pixel) {
  constexpr double kRoundingShift = 0x1.8p52;
  const double scaled = pixel * double(conventions::kSubpixelScale);
  return static_cast<std::int64_t>((scaled + kRoundingShift) - kRoundingShift);
}

}  // namespace

bool setupScreenTriangle(const dvec2 pixelIn[3], const double tIn[3], int width, int height, std::uint32_t triangle,
                         ScreenTriangle& out) {
  std::int64_t xIn[3], yIn[3];
  for (int k = 0; k < 3; ++k) {
    xIn[k] = snapToSubpixel(pixelIn[k].x);
    yIn[k] = snapToSubpixel(pixelIn[k].y);
  }
  const std::int64_t area = orient2d(xIn[0], yIn[0], xIn[1], yIn[1], xIn[2], yIn[2]);
  if (area == 0) return false;
  // orient2d is positive for points that run clockwise as seen on screen (y points
  // down), so a counter-clockwise, front-facing triangle has negative area here.
  out.frontFacing = area < 0;
  // Orient every triangle the same way, so "inside" is "all edge functions >= 0": a
  // counter-clockwise one swaps its last two corners (selected, not branched on: the
  // two orientations come in no predictable order).
  const bool swapped = area < 0;
  const std::int64_t x[3] = {xIn[0], swapped ? xIn[2] : xIn[1], swapped ? xIn[1] : xIn[2]};
  const std::int64_t y[3] = {yIn[0], swapped ? yIn[2] : yIn[1], swapped ? yIn[1] : yIn[2]};
  const dvec2 pixel[3] = {pixelIn[0], swapped ? pixelIn[2] : pixelIn[1], swapped ? pixelIn[1] : pixelIn[2]};
  const double t[3] = {tIn[0], swapped ? tIn[2] : tIn[1], swapped ? tIn[1] : tIn[2]};

  std::tie(out.minX, out.maxX) = centersWithin(std::min({x[0], x[1], x[2]}), std::max({x[0], x[1], x[2]}), width);
  std::tie(out.minY, out.maxY) = centersWithin(std::min({y[0], y[1], y[2]}), std::max({y[0], y[1], y[2]}), height);
  if (out.minX > out.maxX || out.minY > out.maxY) return false;

  for (int k = 0; k < 3; ++k) {
    // Edge k runs from vertex k+1 to vertex k+2, opposite vertex k:
    // E(P) = (bx - ax)(Py - ay) - (by - ay)(Px - ax), positive on the triangle's side.
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    const std::int64_t dx = x[b] - x[a], dy = y[b] - y[a];
    // Top edge: horizontal with the triangle below (+y); left edge: triangle to its right.
    // Their centers count as inside; on every other edge a center exactly on it is outside.
    const bool topLeft = (dy == 0 && dx > 0) || dy < 0;
    out.edgeA[k] = -dy;
    out.edgeB[k] = dx;
    out.edgeC[k] = dy * x[a] - dx * y[a] - (topLeft ? 0 : 1);
  }

  // The plane of t through the three unsnapped corners (Cramer's rule in pixel units).
  // Snapping can make a sliver's unsnapped area vanish while its snapped area does not:
  // then t is constant across it, the mean of its corners.
  const double x1 = pixel[1].x - pixel[0].x, y1 = pixel[1].y - pixel[0].y;
  const double x2 = pixel[2].x - pixel[0].x, y2 = pixel[2].y - pixel[0].y;
  const double det = x1 * y2 - x2 * y1;
  out.x0 = pixel[0].x;
  out.y0 = pixel[0].y;
  if (det == 0) {
    out.t0 = (t[0] + t[1] + t[2]) / 3;
    out.tdx = out.tdy = 0;
  } else {
    out.t0 = t[0];
    out.tdx = ((t[1] - t[0]) * y2 - (t[2] - t[0]) * y1) / det;
    out.tdy = ((t[2] - t[0]) * x1 - (t[1] - t[0]) * x2) / det;
  }
  out.triangle = triangle;
  return true;
}

}  // namespace hsr
