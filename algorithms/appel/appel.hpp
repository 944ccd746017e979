// Appel's quantitative invisibility (1967): the hidden-line algorithm for closed
// polyhedral surfaces that walks along edges instead of testing each against every face.
//
// The quantitative invisibility (QI) of a point is how many front-facing faces lie
// between it and the eye; a point is visible when its QI is 0. Along an edge the QI is
// constant except where the edge passes behind a contour (silhouette) edge, where it
// changes by exactly one, and at vertices on the contour, where the faces around the
// vertex can start or stop hiding the next edge. So:
//   1. Facing and contours: classify every triangle as front or back for this view; the
//      contour edges separate front from back.
//   2. Start: in each connected set of feature edges, the QI of one vertex is found by
//      counting the front faces its eye ray crosses (a BVH ray cast).
//   3. Propagate: walk edge by edge; along each edge, find where its projection crosses a
//      contour edge that lies in front of it (an image-plane grid of contour edges keeps
//      the search short) and add +1 entering the region behind that contour's front face,
//      -1 leaving it, and where it passes through a counted face, +1 going behind it, -1
//      coming out; at each vertex, correct for the faces around the vertex that hide one
//      edge's end or the next edge's start.
//   4. Intersection lines: where two faces cross, the line between them is drawn too,
//      its QI counted by a ray cast to its longest piece, then changing as along any edge.
// Every decision is an exact predicate on the scene's doubles (renderer/geometry/predicates), so
// the QI is exact wherever it is defined; where an edge's projection runs exactly along a
// contour, or through a contour vertex, the rules below settle it the way the line
// reference does (renderer/reference/line_reference).
//
// Input: closed, consistently oriented meshes (every edge in exactly two triangles that
// run it in opposite directions), all beyond the near plane; anything else is refused
// with the first edge that breaks the assumption, unless surfaces=any (below) is asked
// for. The contours are then every edge where the counted faces around it do not
// balance: a rim, a non-manifold fan. Surfaces may pass through each other and through
// themselves (renderer/scene/intersections.hpp finds where). Where an edge passes exactly
// through a side or corner of a face, or ends on its plane, the QI after that point is
// counted afresh by a ray cast; a count that still does not close labels the drawing
// partial (LineSet::partial).
// Output: a LineSet of the feature edges (renderer/lines/feature_edges) with each piece's QI.
#pragma once

#include <string>

#include "algorithms/algorithm.hpp"
#include "algorithms/knobs.hpp"
#include "renderer/lines/feature_edges.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::appel {

// Which faces the QI counts. Appel's own: the front faces, on closed, consistently oriented
// meshes. `any` counts every face not seen edge-on, which stays right on open,
// non-manifold or double-sided meshes (a point is visible when nothing at all is in front
// of it); QI is then the number of surfaces in front, twice Appel's on a closed mesh.
enum class Surfaces { closed, any };

struct Knobs {
  Surfaces surfaces = Surfaces::closed;
  double cellPixels = 16;                      // the contour grid's cell side, in pixels
  double creaseDegrees = kDefaultCreaseDegrees;  // feature edges: creases sharper than this
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table =
      KnobTable<Knobs>()
          .choice("surfaces", &Knobs::surfaces, {{Surfaces::closed, "closed"}, {Surfaces::any, "any"}},
                  "closed: count front faces (Appel's QI; needs closed, consistently oriented meshes); any: count every face, "
                  "so open, non-manifold and double-sided meshes are drawn too (wrong where surfaces pass through or lie on "
                  "each other)")
          .number("cell", &Knobs::cellPixels, {1, 65536}, {"4", "64", "256"},
                  "side in pixels of the image-plane grid that lists the contour edges each edge may cross")
          .number("crease", &Knobs::creaseDegrees, {0, 180}, {"0", "10", "60"}, kCreaseKnobHelp);
  return table;
}

// Why Appel's algorithm cannot draw this scene, or "" when it can.
std::string refusal(const PreparedScene& scene, const Knobs& knobs);

// Stats: "contour edges", "grid cells", "crossings tested", "QI changes", "vertex
// corrections", "start-vertex ray casts", "recount ray casts" (steps 3 and 4),
// "QI mismatches" (an edge's end disagreeing with the QI its vertex already has),
// "degenerate start rays", "degenerate recounts", "negative QI", and the surface
// intersections' counters on first use. With an edge witness (hsr why --edge), what the
// walk meets along that edge: where it starts and with what QI, each change of QI along
// it and what made it, and the vertex it arrives at.
LineSet run(const PreparedScene& scene, const Knobs& knobs, Stats& stats, StepRecorder* steps = nullptr, EdgeWitness* edge = nullptr);

// The registry's entry (algorithms/algorithm.hpp).
AlgorithmEntry entry();

}  // namespace hsr::appel
