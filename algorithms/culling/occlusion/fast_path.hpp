// The occluder map's fast path: a row's texels eight at a time with AVX2, for each
// rule, beside the textbook loops (depth_map.hpp: conservativeRow, centerRow) that write
// them one at a time.
//
// Each computes what its textbook loop computes: the keys with the same operations in
// the same order on each texel, and the conservative rule's rounding by another route
// to the same float, so the map comes out bit for bit the same (tests/culling/
// occlusion_test.cpp checks random rows):
//   conservative  each face plane's key at the texel's worst corner, atZero + slope x
//                 (RowKey), in double, four texels to a vector; their maximum; rounded
//                 up to float and one float further, as roundedUp rounds, but by the
//                 key's bits, eight texels to a vector (exact where every key of the run
//                 keeps one sign and a magnitude in float's normal range: the rows of a
//                 perspective map, all negative, and of an orthographic one, positive;
//                 another run is left to the textbook loop); the smaller of that and
//                 what the texel holds.
//   center        each face plane's key at the texel's center, atZero + slope x
//                 (CenterRowKey), in float, eight texels to a vector; their maximum; the
//                 smaller of that and what the texel holds.
#pragma once

#include "algorithms/culling/occlusion/depth_map.hpp"

namespace hsr::culling::occlusion {

// Writes texels first .. last of `row` as conservativeRow writes them, eight at a time,
// the last few of the run under a mask, and returns true; or, where the run's keys may
// change sign or leave float's normal range, writes nothing and returns false. Only on a
// CPU with AVX2 (renderer/util/simd.hpp).
bool conservativeRowEightAtATime(float* row, int first, int last, const RowKey* keys, int count);

// Writes texels first .. last of `row` as centerRow writes them, eight at a time, the
// last few of the run under a mask. Only on a CPU with AVX2.
void centerRowEightAtATime(float* row, int first, int last, const CenterRowKey* keys, int count);

}  // namespace hsr::culling::occlusion
