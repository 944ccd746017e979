// The occluder map's fast path: the conservative rule's texels of a row eight at a time
// with AVX2, beside the textbook loop (depth_map.cpp, OccluderRasterizer::
// conservativePolygon) that writes them one at a time.
//
// It computes what the textbook loop computes, with the same operations in the same
// order on each texel, so the map comes out bit for bit the same (tests/culling/
// occlusion_test.cpp checks random rows): each face plane's key at the texel's worst
// corner, atZero + slope x (RowKey), in double, four texels to a vector; their maximum;
// rounded to float upward and one float further (roundedUp), eight texels to a vector;
// the smaller of that and what the texel holds.
#pragma once

#include "algorithms/culling/occlusion/depth_map.hpp"

namespace hsr::culling::occlusion {

// Writes texels first .. of `row` eight at a time as conservativePolygon's loop writes
// them, given each face's key along the row; returns the first texel it did not write
// (at most seven before last + 1), for that loop to finish. Only on a CPU with AVX2
// (renderer/simd.hpp).
int conservativeRowEightAtATime(float* row, int first, int last, const RowKey* keys, int count);

}  // namespace hsr::culling::occlusion
