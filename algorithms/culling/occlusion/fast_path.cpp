// The occluder map's fast path (fast_path.hpp says what it computes and why it is the
// same). Only the functions marked HSR_AVX2 use AVX2 (renderer/util/simd.hpp).
#include "algorithms/culling/occlusion/fast_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "renderer/util/simd.hpp"

namespace hsr::culling::occlusion {
namespace {

// Where a run of a row can be rounded by its bits: +1 where every face's key over the
// run is positive, -1 where every one is negative, 0 where that is not certain. Each key
// is affine in x, so over the run it lies between its values at the run's ends, as
// computed to within the slack (far above the rounding of atZero + slope x); the
// magnitudes are kept well inside float's normal range.
HSR_AVX2 int signOfEveryKey(const RowKey* keys, int count, int first, int last) {
  constexpr double kSmallest = 1e-30, kLargest = 1e30;
  int sign = 0;
  for (int k = 0; k < count; ++k) {
    const double atFirst = keys[k].atZero + keys[k].slope * first, atLast = keys[k].atZero + keys[k].slope * last;
    const double slack = 0x1p-50 * (std::abs(keys[k].atZero) + std::abs(keys[k].slope) * std::max(std::abs(first), std::abs(last)));
    const double low = std::min(std::abs(atFirst), std::abs(atLast)) - slack, high = std::max(std::abs(atFirst), std::abs(atLast)) + slack;
    const int keySign = atFirst > 0 && atLast > 0 ? 1 : atFirst < 0 && atLast < 0 ? -1 : 0;
    if (keySign == 0 || (sign != 0 && keySign != sign) || !(low > kSmallest && high < kLargest)) return 0;
    sign = keySign;
  }
  return sign;
}

// The largest face key at eight texels from x, rounded as roundedUp rounds it, for a run
// up to texel `last` whose keys all have the sign `sign` (signOfEveryKey); lanes past
// the run repeat its last texel, so that no lane holds a key the run's check did not
// cover (extrapolated, it could overflow a float, and a trapping build would stop on
// it), though those lanes are never stored. The smallest float at or above a
// double in float's normal range is its bits with the 29 that float drops cleared:
// toward zero, which is up for a negative key; a positive key's bits get 2^29 - 1 added
// first, so that a nonzero dropped part carries into the bits float keeps. That double is
// a float, narrowed exactly; one float further (nextUp) is then its bits plus the sign.
HSR_AVX2 Float8 eightKeysRoundedUp(int x, int last, int sign, const RowKey* keys, int count) {
  const Double4 low = smaller(double(x) + Double4{0, 1, 2, 3}, lanesOf(last)), high = smaller(double(x) + Double4{4, 5, 6, 7}, lanesOf(last));
  Double4 lowFarthest = lanesOf(-std::numeric_limits<double>::infinity()), highFarthest = lowFarthest;
  for (int k = 0; k < count; ++k) {
    const Double4 atLow = keys[k].atZero + keys[k].slope * low, atHigh = keys[k].atZero + keys[k].slope * high;
    lowFarthest = lowFarthest < atLow ? atLow : lowFarthest;  // std::max(farthest, key)
    highFarthest = highFarthest < atHigh ? atHigh : highFarthest;
  }
  constexpr std::int64_t kDropped = (std::int64_t(1) << 29) - 1;
  const Mask4 carry = Mask4{} + (sign > 0 ? kDropped : 0), kept = Mask4{} + ~kDropped;
  const Float8 atOrAbove = narrowed(Double4((Mask4(lowFarthest) + carry) & kept), Double4((Mask4(highFarthest) + carry) & kept));
  return Float8(Int8(atOrAbove) + sign);
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

HSR_AVX2 bool conservativeRowEightAtATime(float* row, int first, int last, const RowKey* keys, int count) {
  const int sign = signOfEveryKey(keys, count, first, last);
  if (sign == 0) return false;
  int x = first;
  for (; x + 7 <= last; x += 8) {
    const Float8 up = eightKeysRoundedUp(x, last, sign, keys, count);
    Float8 held;
    __builtin_memcpy(&held, row + x, sizeof held);
    const Float8 kept = up < held ? up : held;  // std::min(held, up)
    __builtin_memcpy(row + x, &kept, sizeof kept);
  }
  if (x <= last) {  // the run's last few texels, loaded and stored under a mask
    const Int8 inRun = x + Int8{0, 1, 2, 3, 4, 5, 6, 7} <= last;
    const Float8 up = eightKeysRoundedUp(x, last, sign, keys, count), held = maskedLoad(row + x, inRun);
    maskedStore(row + x, inRun, up < held ? up : held);
  }
  return true;
}

HSR_AVX2 void centerRowEightAtATime(float* row, int first, int last, const CenterRowKey* keys, int count) {
  int x = first;
  for (; x + 7 <= last; x += 8) eightCenterTexels(row, x, Int8{} - 1, keys, count);
  if (x <= last) eightCenterTexels(row, x, x + Int8{0, 1, 2, 3, 4, 5, 6, 7} <= last, keys, count);
}

}  // namespace hsr::culling::occlusion
