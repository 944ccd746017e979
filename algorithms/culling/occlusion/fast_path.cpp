// The occluder map's fast path (fast_path.hpp says what it computes and why it is the
// same). Only the functions marked HSR_AVX2 use AVX2 (renderer/util/simd.hpp).
#include "algorithms/culling/occlusion/fast_path.hpp"

#include <limits>

#include "renderer/util/simd.hpp"

namespace hsr::culling::occlusion {
namespace {

// nextUp (depth_map.hpp) lane by lane: a positive float's bits plus one, a negative's
// minus one, and a zero the smallest positive float.
HSR_AVX2 Float8 nextUp(Float8 f) {
  const Int8 bits = Int8(f);
  const Float8 stepped = Float8(f > 0 ? bits + 1 : bits - 1);
  const float smallest = std::numeric_limits<float>::denorm_min();
  return f == 0 ? Float8{} + smallest : stepped;
}

// Two masks of four 64-bit lanes as one of eight 32-bit lanes.
HSR_AVX2 Int8 narrowedMask(Mask4 low, Mask4 high) {
  return Int8{std::int32_t(low[0]), std::int32_t(low[1]), std::int32_t(low[2]), std::int32_t(low[3]),
              std::int32_t(high[0]), std::int32_t(high[1]), std::int32_t(high[2]), std::int32_t(high[3])};
}

// roundedUp lane by lane: to the nearest float, up one where that fell below, and up
// one more; an infinity stays itself.
HSR_AVX2 Float8 roundedUp(Double4 low, Double4 high) {
  const Float8 nearest = narrowed(low, high);
  const Int8 fellBelow = narrowedMask(widenedHalf(nearest, 0) < low, widenedHalf(nearest, 1) < high);
  const Float8 above = fellBelow ? nextUp(nearest) : nearest;
  const double infinity = std::numeric_limits<double>::infinity();
  const Int8 infinite = narrowedMask((low == infinity) | (low == -infinity), (high == infinity) | (high == -infinity));
  return infinite ? nearest : nextUp(above);
}

// The center rule's eight texels from x, those of them in the run (the lanes of `inRun`)
// loaded and stored under a mask, so that a run's last few need no loop of their own.
HSR_AVX2 void eightCenterTexels(float* row, int x, Int8 inRun, const CenterRowKey* keys, int count) {
  const Float8 texels = static_cast<float>(x) + Float8{0, 1, 2, 3, 4, 5, 6, 7};  // exact: x is far below 2^24
  Float8 farthest = Float8{} - std::numeric_limits<float>::infinity();
  for (int k = 0; k < count; ++k) {
    const Float8 key = keys[k].atZero + keys[k].slope * texels;
    farthest = farthest < key ? key : farthest;  // std::max(farthest, key)
  }
  const Float8 held = maskedLoad(row + x, inRun);
  const Float8 kept = farthest < held ? farthest : held;  // std::min(held, farthest)
  maskedStore(row + x, inRun, kept);
}

}  // namespace

HSR_AVX2 int conservativeRowEightAtATime(float* row, int first, int last, const RowKey* keys, int count) {
  int x = first;
  for (; x + 7 <= last; x += 8) {
    Double4 farthest[2];
    for (int half = 0; half < 2; ++half) {
      const Double4 texels = double(x + 4 * half) + Double4{0, 1, 2, 3};
      farthest[half] = lanesOf(-std::numeric_limits<double>::infinity());
      for (int k = 0; k < count; ++k) {
        const Double4 key = keys[k].atZero + keys[k].slope * texels;
        farthest[half] = farthest[half] < key ? key : farthest[half];  // std::max(farthest, key)
      }
    }
    const Float8 up = roundedUp(farthest[0], farthest[1]);
    Float8 held;
    __builtin_memcpy(&held, row + x, sizeof held);
    const Float8 kept = up < held ? up : held;  // std::min(held, up)
    __builtin_memcpy(row + x, &kept, sizeof kept);
  }
  return x;
}

HSR_AVX2 void centerRowEightAtATime(float* row, int first, int last, const CenterRowKey* keys, int count) {
  int x = first;
  for (; x + 7 <= last; x += 8) eightCenterTexels(row, x, Int8{} - 1, keys, count);
  if (x <= last) eightCenterTexels(row, x, x + Int8{0, 1, 2, 3, 4, 5, 6, 7} <= last, keys, count);
}

}  // namespace hsr::culling::occlusion
