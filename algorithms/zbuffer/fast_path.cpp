// The z-buffer's fast path (fast_path.hpp says what it computes and why it is the same).
// Only the functions marked HSR_AVX2 use AVX2 instructions (renderer/util/simd.hpp); on
// other targets than x86 this file compiles to nothing.
#include "algorithms/zbuffer/fast_path.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <type_traits>

#include "renderer/util/conventions.hpp"
#include "renderer/util/simd.hpp"

#if HSR_X86

namespace hsr::zbuffer {
namespace {

constexpr int kBlock = 8;  // a block is 8 x 8 pixels; a row of a block is one vector of 8 floats
// Triangles whose box in the tile has fewer pixels than this are drawn by the textbook
// loop (worthDrawing).
constexpr int kVectorsFromPixels = 24;
// The depth bound's margin against the rounding of the per-pixel formula: a few units in
// the last place of its terms' magnitudes, taken a thousand times over.
constexpr double kRoundingMargin = 1e-12;

// The triangle's box in the tile, [x0, x1) x [y0, y1).
TileGrid::Rect boxIn(const ScreenTriangle& tri, const TileGrid::Rect& tile) {
  return {std::max(tri.minX, tile.x0), std::max(tri.minY, tile.y0), std::min(tri.maxX + 1, tile.x1), std::min(tri.maxY + 1, tile.y1)};
}

// Lane i of a row's 8 lanes is pixel x + i; its bit in the masks below is 1 << i.
HSR_AVX2 __m256i laneMask(int bits) {
  const __m256i laneBits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(bits), laneBits), laneBits);
}

// The lanes, of four, where all three edge functions are non-negative (no sign bit set).
HSR_AVX2 int insideLanes(__m256i e0, __m256i e1, __m256i e2) {
  return ~_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_or_si256(_mm256_or_si256(e0, e1), e2))) & 0xF;
}

// One triangle's edge functions at the top-left pixel center of the 8 x 8 blocks, the
// three in the lanes of one vector (the fourth lane 0: never outside, never in the way
// of inside), stepped a block to the right by adding 8 A, exact in 64-bit integers as
// in rasterizeSpan. An edge function being linear, its least and greatest over the
// pixel centers of a block clipped to the triangle's box are at the clipped block's
// corners: i A and i B for i = 0..7, tabulated once per triangle, give them by adding. A
// block is outside the triangle where some edge is negative at its greatest, and inside
// where every edge is non-negative at its least.
class BlockCorners {
 public:
  HSR_AVX2 explicit BlockCorners(const ScreenTriangle& tri) : tri_(tri) {
    using conventions::kSubpixelScale;
    const __m256i acrossOne = _mm256_setr_epi64x(tri.edgeA[0] * kSubpixelScale, tri.edgeA[1] * kSubpixelScale, tri.edgeA[2] * kSubpixelScale, 0);
    const __m256i downOne = _mm256_setr_epi64x(tri.edgeB[0] * kSubpixelScale, tri.edgeB[1] * kSubpixelScale, tri.edgeB[2] * kSubpixelScale, 0);
    across_[0] = down_[0] = _mm256_setzero_si256();
    for (int i = 1; i < kBlock; ++i) {
      across_[i] = _mm256_add_epi64(across_[i - 1], acrossOne);
      down_[i] = _mm256_add_epi64(down_[i - 1], downOne);
    }
    right_ = _mm256_add_epi64(across_[kBlock - 1], acrossOne);
  }

  // Starts a row of blocks at the block whose top-left pixel is (x, y), of which rows
  // [y0, y1) lie in the triangle's box.
  HSR_AVX2 void startRow(int x, int y, int y0, int y1) {
    using conventions::kSubpixelScale;
    const std::int64_t px = std::int64_t(x) * kSubpixelScale + kSubpixelScale / 2, py = std::int64_t(y) * kSubpixelScale + kSubpixelScale / 2;
    const auto edge = [&](int k) { return tri_.edgeA[k] * px + tri_.edgeB[k] * py + tri_.edgeC[k]; };
    at_ = _mm256_setr_epi64x(edge(0), edge(1), edge(2), 0);
    splitLeastGreatest(down_[y0 - y], down_[y1 - 1 - y], rowLeast_, rowGreatest_);
  }
  HSR_AVX2 void right() { at_ = _mm256_add_epi64(at_, right_); }
  // Of the current block, columns [x0, x1) from its left, x1 > x0: outside, inside, or
  // neither.
  HSR_AVX2 void test(int x0, int x1, bool& outside, bool& inside) const {
    __m256i least, greatest;
    splitLeastGreatest(across_[x0], across_[x1 - 1], least, greatest);
    outside = _mm256_movemask_pd(_mm256_castsi256_pd(_mm256_add_epi64(_mm256_add_epi64(at_, greatest), rowGreatest_))) != 0;
    inside = _mm256_movemask_pd(_mm256_castsi256_pd(_mm256_add_epi64(_mm256_add_epi64(at_, least), rowLeast_))) == 0;
  }
  // The current block's edge functions at its first column, `rowsDown` rows below its
  // top, where its walk row by row starts.
  HSR_AVX2 __m256i firstColumn(int rowsDown) const { return _mm256_add_epi64(at_, down_[rowsDown]); }

 private:
  HSR_AVX2 static void splitLeastGreatest(__m256i a, __m256i b, __m256i& least, __m256i& greatest) {
    const __m256i aGreater = _mm256_cmpgt_epi64(a, b);
    least = _mm256_blendv_epi8(a, b, aGreater);
    greatest = _mm256_blendv_epi8(b, a, aGreater);
  }
  const ScreenTriangle& tri_;
  __m256i across_[kBlock], down_[kBlock];  // i A and i B, lane k edge k
  __m256i right_, at_ = {}, rowLeast_ = {}, rowGreatest_ = {};
};

// One triangle's edge functions over the lanes of a block's rows: lane i of row y is
// E(x + i, y) = E(x, y) + i A, and a row down adds B, exact in 64-bit integers as in
// rasterizeSpan. Stepped row by row from the block's first.
class EdgeLanes {
 public:
  HSR_AVX2 explicit EdgeLanes(const ScreenTriangle& tri) {
    for (int k = 0; k < 3; ++k) {
      const std::int64_t step = tri.edgeA[k] * conventions::kSubpixelScale;
      across_[k] = _mm256_setr_epi64x(0, step, 2 * step, 3 * step);
      acrossHalf_[k] = _mm256_set1_epi64x(4 * step);
      down_[k] = _mm256_set1_epi64x(tri.edgeB[k] * conventions::kSubpixelScale);
    }
  }

  // Starts a block whose first row's first lane has edge functions e (lane k: edge k).
  HSR_AVX2 void start(__m256i e) {
    const __m256i each[3] = {_mm256_permute4x64_epi64(e, 0x00), _mm256_permute4x64_epi64(e, 0x55), _mm256_permute4x64_epi64(e, 0xAA)};
    for (int k = 0; k < 3; ++k) {
      low_[k] = _mm256_add_epi64(each[k], across_[k]);
      high_[k] = _mm256_add_epi64(low_[k], acrossHalf_[k]);
    }
  }

  // The covered lanes of the current row (bit i: lane i), and a step down to the next.
  HSR_AVX2 int coveredThenDown() {
    const int covered = insideLanes(low_[0], low_[1], low_[2]) | insideLanes(high_[0], high_[1], high_[2]) << 4;
    for (int k = 0; k < 3; ++k) {
      low_[k] = _mm256_add_epi64(low_[k], down_[k]);
      high_[k] = _mm256_add_epi64(high_[k], down_[k]);
    }
    return covered;
  }

 private:
  __m256i across_[3], acrossHalf_[3], down_[3];  // i A for lanes 0..3; 4 A; B
  __m256i low_[3] = {}, high_[3] = {};                // the current row's lanes 0..3 and 4..7 (set by start)
};

// Eight pixels of a tile's row from column x, as read and written: all eight with plain
// loads and stores where they lie in the tile (masked stores are far slower on some
// CPUs, and the tile is this thread's), else only those up to the tile's right edge (a
// row at the image's right edge, where eight would reach into another tile's row).
// Ids go through it as the float bits they are stored in.
class RowOfEight {
 public:
  HSR_AVX2 RowOfEight(int x, int tileEnd) : whole_(x + kBlock <= tileEnd), lanes_(laneMask(whole_ ? 0xFF : (1 << (tileEnd - x)) - 1)) {}
  HSR_AVX2 __m256 load(const float* row) const { return whole_ ? _mm256_loadu_ps(row) : _mm256_maskload_ps(row, lanes_); }
  HSR_AVX2 __m256i load(const std::uint32_t* row) const { return _mm256_castps_si256(load(reinterpret_cast<const float*>(row))); }
  HSR_AVX2 void store(float* row, __m256 value) const {
    if (whole_)
      _mm256_storeu_ps(row, value);
    else
      _mm256_maskstore_ps(row, lanes_, value);
  }
  HSR_AVX2 void store(std::uint32_t* row, __m256i value) const { store(reinterpret_cast<float*>(row), _mm256_castsi256_ps(value)); }
  HSR_AVX2 __m256i lanes() const { return lanes_; }  // the lanes inside the tile

 private:
  bool whole_;
  __m256i lanes_;
};

// The scalar loop's z for eight lanes: a + b t, clamped to [0, 1] as std::clamp does
// (max(0, z) keeps -0.0 and NaN, as it does), rounded to float. tx holds
// t0 + tdx (x - x0) per lane; ty is tdy (y - y0).
HSR_AVX2 __m256 storedDepth(const __m256d tx[2], double ty, const DepthEncoding& encoding) {
  const __m256d a = _mm256_set1_pd(encoding.a), b = _mm256_set1_pd(encoding.b), zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  __m128 half[2];
  for (int h = 0; h < 2; ++h) {
    const __m256d t = _mm256_add_pd(tx[h], _mm256_set1_pd(ty));
    const __m256d z = _mm256_add_pd(a, _mm256_mul_pd(b, t));
    half[h] = _mm256_cvtpd_ps(_mm256_min_pd(one, _mm256_max_pd(zero, z)));
  }
  return _mm256_set_m128(half[1], half[0]);
}

// The nearest depth value, as stored, any pixel center of [x0, x1] x [y0, y1] can get
// from the triangle's plane: its value at the nearest corner, moved toward the near end
// by the margin. The formula at a pixel rounds, so its value there may lie below the
// plane's least value by a few units in the last place; the margin covers that.
float nearestStored(const ScreenTriangle& tri, const DepthEncoding& encoding, bool reversed, int x0, int x1, int y0, int y1) {
  const double dx[2] = {conventions::pixelCenter(x0) - tri.x0, conventions::pixelCenter(x1) - tri.x0};
  const double dy[2] = {conventions::pixelCenter(y0) - tri.y0, conventions::pixelCenter(y1) - tri.y0};
  double nearest = reversed ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  for (const double u : dx)
    for (const double v : dy) {
      const double z = encoding.z(tri.t0 + tri.tdx * u + tri.tdy * v);
      nearest = reversed ? std::max(nearest, z) : std::min(nearest, z);
    }
  const double magnitude = std::abs(tri.t0) + std::abs(tri.tdx) * std::max(std::abs(dx[0]), std::abs(dx[1])) +
                           std::abs(tri.tdy) * std::max(std::abs(dy[0]), std::abs(dy[1]));
  const double margin = kRoundingMargin * (std::abs(encoding.a) + std::abs(encoding.b) * magnitude);
  return static_cast<float>(std::clamp(reversed ? nearest + margin : nearest - margin, 0.0, 1.0));
}

// The farthest of a block's rows' lanes, the lanes past the tile's right edge left out.
HSR_AVX2 float farthestLane(__m256 rows, bool reversed) {
  __m128 half = reversed ? _mm_min_ps(_mm256_castps256_ps128(rows), _mm256_extractf128_ps(rows, 1))
                         : _mm_max_ps(_mm256_castps256_ps128(rows), _mm256_extractf128_ps(rows, 1));
  const __m128 swapped = _mm_movehl_ps(half, half);
  half = reversed ? _mm_min_ps(half, swapped) : _mm_max_ps(half, swapped);
  const __m128 second = _mm_shuffle_ps(half, half, 1);
  return _mm_cvtss_f32(reversed ? _mm_min_ss(half, second) : _mm_max_ss(half, second));
}

}  // namespace

SimdTile::SimdTile(TileGrid::Rect rect, int width, DepthBuffer<float> depth, std::uint32_t* ids, DepthEncoding encoding, bool reversed,
                   DepthCounts& counts)
    : rect_(rect),
      width_(width),
      depth_(depth),
      ids_(ids),
      encoding_(encoding),
      reversed_(reversed),
      counts_(counts),
      blocksX_((rect.x1 - rect.x0 + kBlock - 1) / kBlock),
      blockFarthest_(std::size_t(blocksX_) * std::size_t((rect.y1 - rect.y0 + kBlock - 1) / kBlock), reversed ? 0.0f : 1.0f) {}

bool SimdTile::worthDrawing(const ScreenTriangle& tri) const {
  const TileGrid::Rect box = boxIn(tri, rect_);
  return (box.x1 - box.x0) * (box.y1 - box.y0) >= kVectorsFromPixels;
}

HSR_AVX2 void SimdTile::draw(const ScreenTriangle& tri) {
  const auto [triX0, triY0, triX1, triY1] = boxIn(tri, rect_);
  if (triX0 >= triX1 || triY0 >= triY1) return;
  EdgeLanes edges(tri);
  const __m256i id = _mm256_set1_epi32(static_cast<int>(tri.triangle + 1));
  const __m256i background = _mm256_set1_epi32(static_cast<int>(conventions::kBackgroundId));
  // Lanes past the tile's right edge count as this, which is never the farthest.
  const __m256 never = _mm256_set1_ps(reversed_ ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity());
  // The nearest depth the triangle can store anywhere in its box in the tile, found once:
  // at a block's own corners it would be tighter, but cost four evaluations a block, and
  // most blocks tested that way are not hidden anyway (zbuffer/README.md, "The fast path").
  const float nearest = nearestStored(tri, encoding_, reversed_, triX0, triX1 - 1, triY0, triY1 - 1);
  std::uint32_t* const ids = ids_;
  const std::size_t width = std::size_t(width_);
  DepthCounts counts;  // kept in registers, added to counts_ at the end
  // Step 2, by blocks of the tile's 8 x 8 grid. A block's lanes are its 8 columns; the
  // triangle's box clips them to [x0, x1) and its rows to [y0, y1).
  BlockCorners corners(tri);
  const int firstBlockX = rect_.x0 + (triX0 - rect_.x0) / kBlock * kBlock;
  for (int blockY = rect_.y0 + (triY0 - rect_.y0) / kBlock * kBlock; blockY < triY1; blockY += kBlock)
    for (int blockX = firstBlockX; blockX < triX1; blockX += kBlock) {
      const int x0 = std::max(blockX, triX0), x1 = std::min(blockX + kBlock, triX1);
      const int y0 = std::max(blockY, triY0), y1 = std::min(blockY + kBlock, triY1);
      if (blockX == firstBlockX)
        corners.startRow(blockX, blockY, y0, y1);
      else
        corners.right();
      bool outside, inside;
      corners.test(x0 - blockX, x1 - blockX, outside, inside);
      if (outside) continue;  // no pixel center of the block inside the triangle
      const int columns = ((1 << (x1 - blockX)) - 1) & ~((1 << (x0 - blockX)) - 1);
      float& blockFarthest = blockFarthest_[std::size_t((blockY - rect_.y0) / kBlock) * std::size_t(blocksX_) + std::size_t((blockX - rect_.x0) / kBlock)];
      // The hierarchical test: every depth the block holds is nearer than the nearest
      // this triangle can store there, so no fragment can pass, or tie.
      const bool hidden = reversed_ ? blockFarthest > nearest : blockFarthest < nearest;
      if (hidden && inside) {  // the whole clipped block covered: its fragments counted without a walk
        counts.tested += std::int64_t(x1 - x0) * (y1 - y0);
        counts.skippedByBlockDepth += std::int64_t(x1 - x0) * (y1 - y0);
        continue;
      }
      const RowOfEight rows(blockX, rect_.x1);
      // The lanes' t0 + tdx (x - x0), the part of the depth that depends on the column.
      __m256d tx[2];
      for (int h = 0; h < 2; ++h) {
        const __m256d center = _mm256_add_pd(_mm256_set1_pd(conventions::pixelCenter(blockX)), _mm256_setr_pd(4 * h, 4 * h + 1, 4 * h + 2, 4 * h + 3));
        tx[h] = _mm256_add_pd(_mm256_set1_pd(tri.t0), _mm256_mul_pd(_mm256_set1_pd(tri.tdx), _mm256_sub_pd(center, _mm256_set1_pd(tri.x0))));
      }
      if (!inside) edges.start(corners.firstColumn(y0 - blockY));
      // The farthest depth of the rows read and written; when they are all of the block's
      // rows, it is the block's farthest depth, found without reading the block again.
      __m256 farthestRead = never;
      int rowsRead = 0;
      for (int y = y0; y < y1; ++y) {
        const int covered = (inside ? columns : edges.coveredThenDown() & columns);
        if (covered == 0) continue;
        counts.tested += std::popcount(unsigned(covered));
        if (hidden) {
          counts.skippedByBlockDepth += std::popcount(unsigned(covered));
          continue;
        }
        float* const depthRow = &depth_.at(blockX, y);
        std::uint32_t* const idRow = &ids[std::size_t(y) * width + std::size_t(blockX)];
        const __m256i coveredLanes = laneMask(covered);
        const __m256 candidate = storedDepth(tx, tri.tdy * (conventions::pixelCenter(y) - tri.y0), encoding_);
        const __m256 current = rows.load(depthRow);
        const __m256i currentIds = rows.load(idRow);
        // Nearer: candidate < current, or candidate > current when reversed.
        const __m256 passes = _mm256_and_ps(_mm256_cmp_ps(reversed_ ? current : candidate, reversed_ ? candidate : current, _CMP_LT_OQ),
                                            _mm256_castsi256_ps(coveredLanes));
        // A tie: another triangle's fragment stored at exactly this depth (seldom: the
        // ids are looked at only where some lane is equal).
        const __m256 equal = _mm256_and_ps(_mm256_cmp_ps(candidate, current, _CMP_EQ_OQ), _mm256_castsi256_ps(coveredLanes));
        if (!_mm256_testz_ps(equal, equal)) {
          const __m256i thisOrNone = _mm256_or_si256(_mm256_cmpeq_epi32(currentIds, background), _mm256_cmpeq_epi32(currentIds, id));
          counts.ties += std::popcount(unsigned(_mm256_movemask_ps(_mm256_andnot_ps(_mm256_castsi256_ps(thisOrNone), equal))));
        }
        const __m256 kept = _mm256_blendv_ps(current, candidate, passes);
        const __m256 keptInTile = _mm256_blendv_ps(never, kept, _mm256_castsi256_ps(rows.lanes()));
        farthestRead = reversed_ ? _mm256_min_ps(farthestRead, keptInTile) : _mm256_max_ps(farthestRead, keptInTile);
        ++rowsRead;
        const int passed = _mm256_movemask_ps(passes);
        if (passed == 0) continue;
        counts.written += std::popcount(unsigned(passed));
        rows.store(depthRow, kept);
        rows.store(idRow, _mm256_blendv_epi8(currentIds, id, _mm256_castps_si256(passes)));
      }
      // Writes only bring depths nearer, so a block's farthest depth, once found, stays a
      // bound on what it holds: the test above stays sound though it is found again only
      // when a triangle reads every row.
      if (rowsRead == std::min(blockY + kBlock, rect_.y1) - blockY) blockFarthest = farthestLane(farthestRead, reversed_);
    }
  counts_.tested += counts.tested, counts_.written += counts.written, counts_.ties += counts.ties;
  counts_.skippedByBlockDepth += counts.skippedByBlockDepth;
}

HSR_AVX2 void decodeRowsFast(const DepthEncoding& encoding, bool perspective, DepthBuffer<const float> stored,
                             std::span<const std::uint32_t> ids, std::span<float> distance, std::pair<int, int> rows) {
  const __m256d a = _mm256_set1_pd(encoding.a), reciprocalB = _mm256_set1_pd(1.0 / encoding.b), one = _mm256_set1_pd(1.0);
  const __m256 infinity = _mm256_set1_ps(std::numeric_limits<float>::infinity());
  const __m256i background = _mm256_set1_epi32(static_cast<int>(conventions::kBackgroundId));
  const int width = int(stored.stride);
  for (int y = rows.first; y < rows.second; ++y)
    for (int x = 0; x < width; x += kBlock) {
      const std::size_t at = std::size_t(y) * stored.stride + std::size_t(x);
      const RowOfEight row(x, width);
      // Lanes past the image's edge read as background.
      const __m256i isBackground = _mm256_or_si256(_mm256_cmpeq_epi32(row.load(&ids[at]), background),
                                                   _mm256_xor_si256(row.lanes(), _mm256_set1_epi32(-1)));
      if (_mm256_testc_si256(isBackground, _mm256_set1_epi32(-1))) {  // all background: no division to do
        row.store(&distance[at], infinity);
        continue;
      }
      const __m256 values = row.load(&stored.at(x, y));  // read before the distances are stored where they may be
      __m128 half[2];
      for (int h = 0; h < 2; ++h) {
        // As DepthTest::distance: t = (z - a) (1 / b), and the distance 1 / t in perspective.
        // Background lanes (and those past the image's edge) divide 1 by 1 instead: the
        // far end of reversed-float32-inf is t = 0, and the scalar loop divides only
        // where a triangle was drawn (the debug build traps a division by zero).
        const __m128 four = h == 0 ? _mm256_castps256_ps128(values) : _mm256_extractf128_ps(values, 1);
        const __m256d undrawn = _mm256_castsi256_pd(_mm256_cvtepi32_epi64(h == 0 ? _mm256_castsi256_si128(isBackground) : _mm256_extracti128_si256(isBackground, 1)));
        const __m256d t = _mm256_blendv_pd(_mm256_mul_pd(_mm256_sub_pd(_mm256_cvtps_pd(four), a), reciprocalB), one, undrawn);
        half[h] = _mm256_cvtpd_ps(perspective ? _mm256_div_pd(one, t) : t);
      }
      row.store(&distance[at], _mm256_blendv_ps(_mm256_set_m128(half[1], half[0]), infinity, _mm256_castsi256_ps(isBackground)));
    }
}

template <typename Format>
void drawTileFast(const Tile<Format>& tile, TileWatcher* watcher) {
  clearTile(tile);  // step 1, as the textbook
  SimdTile fast(tile.area, tile.frame.width, tile.depth, tile.frame.ids.data(), tile.test.encoding,
                std::is_same_v<Format, ReversedFloat32Depth>, tile.test.counts);
  for (std::size_t drawn = 0; drawn < tile.triangles.size(); ++drawn) {
    const ScreenTriangle& tri = tile.triangle(drawn);
    if (fast.worthDrawing(tri)) fast.draw(tri);  // step 2, eight pixels at a time
    else depthTestTriangle(tile, tri);           // step 2, a few pixels: the textbook's
    if (watcher) watcher->drawn(drawn, tri);
  }
}
template void drawTileFast(const Tile<Float32Depth>&, TileWatcher*);
template void drawTileFast(const Tile<ReversedFloat32Depth>&, TileWatcher*);

}  // namespace hsr::zbuffer

#endif  // HSR_X86
