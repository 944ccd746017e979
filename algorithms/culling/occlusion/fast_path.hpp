// The occluder map's fast path: a row's texels eight at a time with AVX2, for each
// rule, beside the textbook loops (depth_map.hpp: conservativeRow, centerRow) that write
// them one at a time.
//
// Each computes what its textbook loop computes, with the same operations in the same
// order on each texel, so the map comes out bit for bit the same (tests/culling/
// occlusion_test.cpp checks random rows):
//   conservative  each face plane's key at the texel's worst corner, atZero + slope x
//                 (RowKey), in double, four texels to a vector; their maximum; rounded
//                 to float upward and one float further (roundedUp), eight texels to a
//                 vector; the smaller of that and what the texel holds.
//   center        each face plane's key at the texel's center, atZero + slope x
//                 (CenterRowKey), in float, eight texels to a vector; their maximum; the
//                 smaller of that and what the texel holds.
#pragma once

#include "algorithms/culling/occlusion/depth_map.hpp"

namespace hsr::culling::occlusion {

// Writes texels first .. of `row` eight at a time as conservativeRow writes them, given
// each face's key along the row; returns the first texel it did not write (at most
// seven before last + 1), for that loop to finish. Only on a CPU with AVX2
// (renderer/util/simd.hpp).
int conservativeRowEightAtATime(float* row, int first, int last, const RowKey* keys, int count);

// Writes texels first .. last of `row` as centerRow writes them, eight at a time, the
// last few of the run under a mask. Only on a CPU with AVX2.
void centerRowEightAtATime(float* row, int first, int last, const CenterRowKey* keys, int count);

}  // namespace hsr::culling::occlusion
