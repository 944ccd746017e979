// Carpenter's A-buffer (1984): antialiased visibility, with a list of fragments per pixel.
//
// Each polygon that reaches a pixel leaves a fragment there: its coverage mask (which of
// the pixel's k x k subsamples it covers) and its depth at the pixel's center. The lists
// are built in any submission order. Resolving a pixel sorts its fragments front to back
// and gives each the share of the pixel it shows: at each subsample, a fragment covering
// it takes its opacity times what nearer fragments let through there, so partial
// coverage and transparency are resolved together, in any order of submission. The
// pixel's colour is each surface's colour (shaded once, at the pixel's center) weighted
// by its share, the rest the background's (the shading pass: renderer/shading/shading.hpp,
// shadeCoverage).
//
// Coverage is exact per subsample: the masks are the rasterizer's coverage of the
// subsample positions, the centers of a k-times finer grid (the same samples a z-buffer
// supersampled k x k takes). What the A-buffer saves over that z-buffer is storage and
// shading per subsample: a fragment per polygon per pixel, one colour each. Its depth
// order is, by default, each fragment's plane compared at each subsample (the
// supersampled z-buffer's order, exactly); with depth=center, Carpenter's one depth per
// fragment, the order at the pixel's center, which is wrong where surfaces pass through
// each other inside a pixel or meet at a silhouette.
//
// Inputs: a PreparedScene, a view, the knobs. Output: per pixel, its surfaces and their
// shares (Visibility::coverage), and for the id and depth images the surface with the
// largest share (the background's when it has the most).
#pragma once

#include "algorithms/algorithm.hpp"
#include "algorithms/knobs.hpp"

namespace hsr::abuffer {

// The coverage mask: k x k subsamples per pixel.
enum class Mask { twoByTwo = 2, fourByFour = 4, eightByEight = 8 };

// Where the fragments of a pixel are put in depth order.
enum class Depth {
  subsample,  // at each subsample, by each fragment's plane there: what a supersampled z-buffer compares
  center,     // once, by each fragment's depth at the pixel's center (Carpenter's one depth per fragment)
};

struct Knobs {
  Mask mask = Mask::fourByFour;
  Depth depth = Depth::subsample;
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table =
      KnobTable<Knobs>()
          .choice("mask", &Knobs::mask, {{Mask::fourByFour, "4x4"}, {Mask::eightByEight, "8x8"}, {Mask::twoByTwo, "2x2"}},
                  "subsamples per pixel in each fragment's coverage mask: 4x4 (Carpenter's), 8x8 (finer edges, a 64-bit "
                  "mask), 2x2 (coarser, for comparison)")
          .choice("depth", &Knobs::depth, {{Depth::subsample, "subsample"}, {Depth::center, "center"}},
                  "where a pixel's fragments are ordered in depth: subsample, by each fragment's plane at each subsample (the "
                  "supersampled z-buffer's order); center, once by their depths at the pixel's center (Carpenter's: cheaper, "
                  "wrong where surfaces cross inside a pixel or meet at a silhouette)");
  return table;
}

// The visibility pass: the geometry stage at the subsamples' resolution, the fragment
// lists (one thread, in submission order), then each pixel resolved (rows in parallel:
// the same bits for any thread count). Stats: "fragments", "subsamples covered", "most
// fragments in a pixel", "pixels with partial coverage" (more than one surface, or a
// surface and the background), "fragment bytes".
void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility);

// The registry's entry (algorithms/algorithm.hpp).
AlgorithmEntry entry();

}  // namespace hsr::abuffer
