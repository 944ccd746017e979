// Weiler and Atherton's hidden-surface algorithm (1977): visibility decided in object
// space, by clipping polygons against each other, before any pixel is touched.
//
// The polygons (the screen triangles) are sorted by their nearest depth. The first is
// the clip polygon: every polygon is clipped against its outline into the pieces inside
// it and the pieces outside. An inside piece that lies behind the clip polygon
// everywhere is hidden and removed. If an inside piece lies in front of it somewhere
// (the sort by nearest depth is only a guess), the inside list is processed again with
// that piece's polygon as the clip polygon: recursion. When nothing inside is in front,
// the inside list is what is visible there; the outside list goes on with its own
// nearest polygon. The answer is a list of visible polygons with exact outlines, drawn
// as an SVG (hsr render -o out.svg) as well as scan-converted into the image.
//
// Exactness. Every outline is an intersection of half-planes whose lines are the
// rasterizer's integer edge functions, moved half a unit so that no pixel center lies
// on any of them (2E + 1, renderer/raster/raster); corners are intersections of two such lines,
// kept as exact rationals in 128-bit integers, and which side of a line a corner lies
// on is an exact sign. So a sliver is kept exactly when it has area, pieces cut along a
// shared edge meet without gap or overlap, and a piece's pixels (the centers strictly
// inside its outline) are the pixels its polygon covers in the z-buffer. Where two
// polygons pass through each other inside a piece, the piece keeps only the part where
// it is nearer, decided at each pixel center by the same plane comparison as the other
// image-space algorithms (renderer/raster/plane_depth.hpp): the one step not in object space.
//
// The image is its pixel centers, so a part of a polygon that holds none can change no
// pixel: such a part is dropped as it is cut off, and a piece whose part inside a clip
// polygon holds none and is a sliver is not cut at all (a mesh's triangles that meet at
// a corner overlap so).
//
// Cost grows with how much polygons overlap on screen: each clip polygon clips every
// piece its outline meets (found through a grid of tiles), and the recursion clips the
// inside list again for each polygon found in front. The knob `budget` refuses scenes
// with more triangles than it, so a large scene is not started by accident.
//
// Inputs: a PreparedScene, a view, the knobs. Output: per pixel, the visible triangle's
// id + 1 (0 = background) and its distance at the pixel center; and the visible polygons.
#pragma once

#include "algorithms/algorithm.hpp"
#include "algorithms/knobs.hpp"

namespace hsr::weiler_atherton {

struct Knobs {
  double budget = 250000;  // refuses scenes with more triangles than this
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table = KnobTable<Knobs>().number(
      "budget", &Knobs::budget, {1, 1e9, true}, {"1e5", "1e6"},
      "refuses scenes with more triangles than this (each clip polygon clips every piece its outline meets: the work grows "
      "with the overlap on screen; at most about 0.5 s per 100,000 triangles of the shipped scenes on one core)");
  return table;
}

// The visibility pass: the geometry stage, then the clipping, on one thread (the same
// bits for every thread count). Stats: "clip polygons" (outlines clipped against, the
// recursion's included), "recursions", "pieces clipped" (pieces an outline cut), "pieces
// made", "cuts undone" (pieces left whole: their part inside was a sliver holding no
// pixel center), "pieces with no pixel dropped" (polygons and parts cut off that held
// none), "pieces hidden" (behind a clip polygon everywhere), "pieces cut by depth"
// (passing through a clip polygon: kept where nearer), "visible pieces", "visible pieces
// with no pixel" (kept where nearer than a polygon they pass through, and nearer at no
// center: not among the polygons drawn), "most pieces in an inside list", "deepest
// recursion", "pixels claimed twice" (0 unless two visible pieces hold the same pixel
// center, which they must not).
void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility);

// The registry's entry (algorithms/algorithm.hpp).
AlgorithmEntry entry();

}  // namespace hsr::weiler_atherton
