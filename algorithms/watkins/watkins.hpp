// Watkins' scanline algorithm (1970): the image a row at a time, and each row in spans.
// Going down the image, an edge table admits polygons to an active list on their first
// row; on each row, each active polygon's edges cross the row where its run of covered
// pixel centers begins and ends. Sorted by x, the crossings cut the row into spans, and
// within a span the same polygons are present throughout. A span is resolved by depth
// at its two ends: if one polygon is nearer than every other at both ends, it is nearer
// everywhere between (planes are linear along the row) and fills the span; if the
// nearest differs from one end to the other, two polygons cross inside the span, and it
// is split where their depths cross, and each part resolved again.
//
// Memory is O(width) per row being resolved, besides the edge table: no depth buffer.
//
// Inputs: a PreparedScene, a view, the knobs. Output: per pixel, the visible triangle's
// id + 1 (0 = background) and its distance at the pixel center.
#pragma once

#include "algorithms/algorithm.hpp"
#include "algorithms/knobs.hpp"

namespace hsr::watkins {

// Where a span whose ends disagree is split.
enum class Split {
  crossing,  // where the two nearest polygons' depths cross along the row (Watkins)
  halves,    // in the middle, again and again: the same image, more spans
  none,      // not at all: the span takes the polygon nearest at its left end (wrong where polygons cross)
};

struct Knobs {
  Split split = Split::crossing;
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table = KnobTable<Knobs>().choice(
      "split", &Knobs::split, {{Split::crossing, "crossing"}, {Split::halves, "halves"}, {Split::none, "none"}},
      "where a span whose ends show different polygons is split: crossing, where their depths cross (Watkins); halves, "
      "in the middle (the same image, more spans); none, not at all (the span shows the polygon nearest at its left end: "
      "wrong where polygons pass through each other)");
  return table;
}

// The visibility pass: the geometry stage, then the rows, in bands (one per thread; the
// same bits and counters for every count). Stats: "crossings" (edges met along the rows),
// "active polygons summed over rows", "spans", "spans with one polygon", "spans resolved
// at their ends", "spans split", "spans of one pixel", "depth samples" (a polygon's depth
// at a span end), "span buffer bytes".
void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility);

// The registry's entry (algorithms/algorithm.hpp).
AlgorithmEntry entry();

}  // namespace hsr::watkins
