// The suite's conventions, in one place. tests/renderer/util/conventions_test.cpp renders known
// triangles to prove each statement below; change one and a test must change with it.
#pragma once

#include <cstdint>

namespace hsr::conventions {

// World space is right-handed with +y up. The camera looks down its own -z axis,
// +x to the right and +y up on screen (view space = "eye space" of OpenGL).

// Front faces are counter-clockwise as seen from outside, i.e. from the side the
// normal (b - a) x (c - a) points to. Procedural solids are built that way, and the
// shipped models were checked to be (positive signed volume).

// Images: row 0 is the top row, x grows to the right. Pixel (i, j) covers
// [i, i+1) x [j, j+1) in pixel coordinates and is sampled at its center (i + 0.5, j + 0.5).
inline constexpr double kPixelCenterOffset = 0.5;
// The pixel coordinate of the center of pixel column or row i.
inline constexpr double pixelCenter(int i) { return i + kPixelCenterOffset; }

// Rasterization snaps vertex positions to fixed point with this many sub-pixel bits
// (1/256 pixel), so coverage is decided with exact integer arithmetic.
inline constexpr int kSubpixelBits = 8;
inline constexpr std::int64_t kSubpixelScale = std::int64_t{1} << kSubpixelBits;

// Fill rule: a pixel center exactly on an edge belongs to the triangle only when the
// edge is a top edge (horizontal, triangle below it in the image) or a left edge
// (triangle to its right). Two triangles sharing an edge therefore never both cover,
// and never both miss, a pixel center on it.

// Guard band: x and y are clipped only beyond this many pixels from the viewport
// center. Snapped coordinates then stay below 2^29 sub-pixel units, so an edge
// function (a difference of two products of coordinate differences) fits in 63 bits.
inline constexpr double kGuardBandPixels = double(1 << 20);

// Depth formats (renderer/raster/depth.hpp): each stores a value where the depth test
// "less" (float32, unorm24, unorm16) or "greater" (the reversed formats) means nearer.
// Ties keep the triangle drawn first, so submission order breaks exact ties.
//   float32          z in [0, 1]: 0 at the near plane, 1 at the far plane, as a float
//   reversed-float32 1 at the near plane, 0 at the far plane, as a float (precision where
//                    perspective needs it: float has most values near 0)
//   reversed-float32-inf  as reversed-float32 with the far plane at infinity: near / distance
//   unorm24, unorm16 z in [0, 1] rounded to the nearest of 2^24 - 1 or 2^16 - 1 steps
// Frame::depth stores what the algorithm decided with, decoded back to the distance
// along the view axis (world units), +infinity where nothing was drawn.

// Ids: every triangle of a prepared scene has a global index, counting objects in
// file order, their instances in generation order, and triangles in mesh order.
// Frame::ids holds (global index + 1), 0 for the background; the --ids PNG stores
// that number as 24-bit big-endian RGB (R = high byte).
inline constexpr std::uint32_t kBackgroundId = 0;

}  // namespace hsr::conventions
