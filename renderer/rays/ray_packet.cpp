#include "renderer/rays/ray_packet.hpp"

#include <cmath>

namespace hsr {

namespace {

// The least and greatest of eight lanes: the two halves lane by lane, then the four
// lanes folded onto themselves twice (a lane's value never leaves the vector registers).
HSR_AVX2 double leastOf(const Double4 (&halves)[RayPacket::kHalves]) {
  Double4 least = smaller(halves[0], halves[1]);
  least = smaller(least, __builtin_shufflevector(least, least, 2, 3, 0, 1));
  return smaller(least, __builtin_shufflevector(least, least, 1, 0, 3, 2))[0];
}
HSR_AVX2 double greatestOf(const Double4 (&halves)[RayPacket::kHalves]) {
  Double4 greatest = larger(halves[0], halves[1]);
  greatest = larger(greatest, __builtin_shufflevector(greatest, greatest, 2, 3, 0, 1));
  return larger(greatest, __builtin_shufflevector(greatest, greatest, 1, 0, 3, 2))[0];
}

// A bit per ray where the halves' masks hold.
HSR_AVX2 int raysWhere(Mask4 low, Mask4 high) { return laneBits(low) | laneBits(high) << 4; }

}  // namespace

HSR_AVX2 RayPacket::RayPacket(const FourRays (&rays)[kHalves], const Double4 (&inverses)[kHalves][3])
    : sharedOrigin(true), closeDirections(true) {
  const double length = std::sqrt(rays[0].direction[0][0] * rays[0].direction[0][0] + rays[0].direction[1][0] * rays[0].direction[1][0] +
                                  rays[0].direction[2][0] * rays[0].direction[2][0]);
  for (int axis = 0; axis < 3; ++axis) {
    for (int half = 0; half < kHalves; ++half) {
      origin[axis][half] = rays[half].origin[axis];
      direction[axis][half] = rays[half].direction[axis];
      inverse[axis][half] = inverses[half][axis];
    }
    nearSide[axis] = std::signbit(direction[axis][0][0]) ? 1 : 0;
    originLow[axis] = leastOf(origin[axis]), originHigh[axis] = greatestOf(origin[axis]);
    inverseLow[axis] = leastOf(inverse[axis]), inverseHigh[axis] = greatestOf(inverse[axis]);
    sharedOrigin = sharedOrigin && originLow[axis] == originHigh[axis];
    closeDirections = closeDirections && greatestOf(direction[axis]) - leastOf(direction[axis]) <= kCloseDirections * length;
  }
}

HSR_AVX2 bool RayPacket::travelTogether(const FourRays (&rays)[kHalves]) {
  Double4 size[kHalves][3];
  for (int axis = 0; axis < 3; ++axis) {
    const Double4 &low = rays[0].direction[axis], &high = rays[1].direction[axis];
    const int negative = raysWhere(low < 0, high < 0);
    if ((negative != 0 && negative != 0xFF) || raysWhere(low == 0, high == 0) != 0) return false;
    for (int half = 0; half < kHalves; ++half) size[half][axis] = negative ? -rays[half].direction[axis] : rays[half].direction[axis];
  }
  // The largest component's axis, chosen as WatertightRay::largestAxis chooses it.
  const auto onX = [&](int half) HSR_AVX2 { return (size[half][0] >= size[half][1]) & (size[half][0] >= size[half][2]); };
  const auto onY = [&](int half) HSR_AVX2 { return ~onX(half) & (size[half][1] >= size[half][2]); };
  const int x = raysWhere(onX(0), onX(1)), y = raysWhere(onY(0), onY(1));
  return (x == 0 || x == 0xFF) && (y == 0 || y == 0xFF);
}

}  // namespace hsr
