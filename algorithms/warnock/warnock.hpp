// Warnock's area subdivision (1969): look at a window of the screen; if what it holds
// is simple enough to draw at once, draw it; if not, cut it into four and look again.
//
// A polygon stands to a window in one of four relations: disjoint (no pixel center of
// the window inside it), contained (its pixel box inside the window), intersecting (the
// rest that meet the window) or surrounding (every pixel center of the window inside
// it). A window is simple when
//   1. no polygon meets it (empty: background),
//   2. one polygon meets it (drawn by scan conversion within the window), or
//   3. a surrounding polygon is nearer at every pixel of the window than every other
//      polygon meeting it (filled with that polygon).
// Anything else is subdivided, down to the knob `smallest-window`: a window that small
// is decided by its central pixel's sample alone, the nearest polygon covering that
// center. At one pixel that is exact (the same sampling as the z-buffer's); larger
// stops are faster and wrong at every pixel of a stop-window whose center shows
// something its other pixels do not.
//
// Inputs: a PreparedScene, a view, the knobs. Output: per pixel, the visible
// triangle's id + 1 (0 = background) and its distance at the pixel center.
#pragma once

#include "algorithms/algorithm.hpp"
#include "algorithms/knobs.hpp"

namespace hsr::warnock {

struct Knobs {
  // The side, in pixels, at which subdivision stops and a window is decided by its
  // central sample: 1 is exact sampling; larger is coarser, faster and wrong.
  int smallestWindow = 1;
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table = KnobTable<Knobs>().number(
      "smallest-window", &Knobs::smallestWindow, {1, 4096, true}, {"2", "4", "8", "16"},
      "pixels: a window this wide and high or smaller is not subdivided but filled with the polygon nearest at its central "
      "pixel's center (1: exact sampling; larger: faster, and wrong where the window holds more than that polygon)");
  return table;
}

// The visibility pass: the geometry stage, then the subdivision from the whole image
// down. threads: 0 = all cores; the same bits and counters for every count. Stats:
// "windows examined", "windows empty", "windows with one polygon", "windows surrounded",
// "windows at smallest size", "windows subdivided", "polygon-window tests", and the
// relations found: "polygons disjoint", "polygons contained", "polygons intersecting",
// "polygons surrounding".
void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility);

// The registry's entry (algorithms/algorithm.hpp).
AlgorithmEntry entry();

}  // namespace hsr::warnock
