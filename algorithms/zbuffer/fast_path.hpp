// The z-buffer's fast path: the full-frame loop's step 2 for one tile, eight
// pixels at a time with AVX2, with hierarchical rejection of 8 x 8 blocks, and step 3
// (decoding the depth kept) eight pixels at a time.
//
// It computes what the textbook loop computes, with the same operations in the same
// order on each pixel, so the ids, the depths and the counters come out bit for bit the
// same (tests/zbuffer/fast_path_test.cpp checks every shipped scene, every hard case and
// the property generator's random scenes):
//   - coverage: the same 64-bit integer edge functions, four pixels to a vector;
//   - depth: t = t0 + tdx (x - x0) + tdy (y - y0), then z = a + b t, clamped and
//     rounded to float, in double lanes, without fused multiply-adds (neither loop may
//     contract them: the scalar build has no FMA, and this file is compiled for AVX2
//     only);
//   - the test: "nearer", ties counted as the scalar DepthTest counts them.
// What it adds: each 8 x 8 block keeps a bound on the depths it holds, and a block whose
// bound is nearer than the nearest the triangle can store in its box is skipped whole
// (Greene, Kass and Miller's hierarchical z-buffer, one level). The bound is the
// block's farthest depth when a triangle last read all its rows; writes only bring
// depths nearer, so it stays a bound until then. The nearest is a lower bound too: the
// plane's least value at the box's corners, less a margin a thousand times the worst
// rounding of the per-pixel formula. The skipped fragments
// are still counted as tested (their coverage is counted, not their depth), so the
// counters stay the textbook loop's; "fragments skipped by block depth" says how many.
// Only float depth formats with the depth test on have a fast path; elsewhere, on a CPU
// without AVX2, and on targets other than x86 (where this file compiles to nothing and
// full_frame.cpp never names it: renderer/util/simd.hpp), the textbook loop runs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "algorithms/zbuffer/textbook.hpp"
#include "renderer/raster/depth.hpp"
#include "renderer/raster/raster.hpp"
#include "renderer/raster/tiles.hpp"

namespace hsr::zbuffer {

class SimdTile {
 public:
  // The tile `rect` of a width-wide image with ids `ids`, its depth (float32, or
  // reversed-float32 when `reversed`) in `depth`. Both already cleared; adds to `counts`.
  SimdTile(TileGrid::Rect rect, int width, DepthBuffer<float> depth, std::uint32_t* ids, DepthEncoding encoding, bool reversed,
           DepthCounts& counts);

  // Whether the triangle's pixels in this tile are worth the vectors: a triangle of a
  // few pixels costs less a pixel at a time (the textbook loop) than its lanes and
  // blocks cost set up.
  bool worthDrawing(const ScreenTriangle& tri) const;
  // Step 2 for one triangle: every pixel of the tile it covers, depth-tested.
  void draw(const ScreenTriangle& tri);

 private:
  TileGrid::Rect rect_;
  int width_;
  DepthBuffer<float> depth_;
  std::uint32_t* ids_;
  DepthEncoding encoding_;
  bool reversed_;
  DepthCounts& counts_;
  int blocksX_;
  // Per 8 x 8 block, row by row: a bound on the depths it holds, as far as any of them
  // (exactly the farthest when last found; writes since can only have brought depths nearer).
  std::vector<float> blockFarthest_;
};

// Step 3 (decodeRows, textbook.hpp) for a float format, eight pixels at a time: the same
// operations on each pixel, the same bits. `stored` may hold its values where the
// distances go; each eight are read before they are written.
void decodeRowsFast(const DepthEncoding& encoding, bool perspective, DepthBuffer<const float> stored, std::span<const std::uint32_t> ids,
                    std::span<float> distance, std::pair<int, int> rows);

// The textbook's loop on one tile (drawTile, textbook.hpp), with the tile's large
// triangles drawn by SimdTile: the same steps, the same bits.
// For Float32Depth and ReversedFloat32Depth.
template <typename Format>
void drawTileFast(const Tile<Format>& tile, TileWatcher* watcher);

}  // namespace hsr::zbuffer
