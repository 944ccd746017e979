// Roberts' hidden-line algorithm (1963), the first one: every edge is tested against
// every convex body, and the part a body hides is found by solving the body's linear
// inequalities along the family of sight lines through the edge.
//
// Roberts works in a space where sight lines are parallel: the screen coordinates
// (x, y in pixels) and a nearness z (1/d under perspective, -d under orthographic). The
// perspective map takes planes to planes and lines to lines, so a convex body stays a
// convex body there, an edge stays a segment with the screen parameter u, and the sight
// line from a point toward the eye is the point plus alpha (0, 0, 1), alpha > 0. Then:
//   1. Back faces: an edge whose faces are both back-facing is hidden by its own body
//      and is never tested (for a convex body, every other edge is not hidden by it).
//   2. Every remaining edge against every other body: a point S(u) of the edge is hidden
//      by body B when, for some alpha > 0, S(u) + alpha z lies strictly inside B, that is
//      h_i(u) + alpha g_i < 0 for every face plane i of B, with h_i linear in u and g_i
//      the plane normal's z. Each pair of a lower and an upper bound on alpha gives one
//      linear inequality in u, so the hidden part is one interval, found from the pairs
//      (Roberts' 2-variable linear program). Bodies whose projections miss the edge's, or
//      which lie wholly behind it, are skipped first (the minimax test); with the screen
//      grid, only the bodies listed in the cells the edge crosses are looked at.
//   3. Junctions: where two bodies interpenetrate, the lines where a face of one meets a
//      face of the other are drawn too, and judged like edges (hidden by a body they lie
//      on when its face there is a back face, else tested against the other bodies).
// Faces are the bodies' planes: triangles coplanar up to their coordinates' rounding
// merged (renderer/geometry/rounding.hpp). A body must be convex up to that rounding: the decimals
// of its file and its placement (Instance), so a sphere exported with six digits, whose
// quads are flat only to those digits, is accepted. Strict insideness uses a tolerance of
// the larger of 1e-9 of the body's size and eight times that rounding, so bodies touching
// face to face do not hide each other's edges lying on the shared face, and meet in no
// junction.
//
// Input: scenes of closed convex polyhedra only (boxes, prisms, pyramids, convex meshes),
// all beyond the near plane; anything else is refused naming the object.
// Output: a LineSet of the feature edges (renderer/lines/feature_edges) plus the junction lines, each
// piece visible (QI 0) or hidden (LineSegment::kHidden: Roberts does not count faces).
#pragma once

#include <cstdint>
#include <string>

#include "algorithms/algorithm.hpp"
#include "algorithms/knobs.hpp"
#include "renderer/lines/feature_edges.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::roberts {

struct Knobs {
  bool grid = true;                              // the screen-grid acceleration
  double cellPixels = 32;                        // its cell side
  double creaseDegrees = kDefaultCreaseDegrees;  // feature edges: creases sharper than this
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table =
      KnobTable<Knobs>()
          .onOff("grid", &Knobs::grid, "on: only the bodies listed in the screen-grid cells an edge crosses are tested; off: every body")
          .number("cell", &Knobs::cellPixels, {1, 65536}, {"8", "128", "512"}, "side in pixels of the screen grid's cells")
          .number("crease", &Knobs::creaseDegrees, {0, 180}, {"0", "10", "60"}, kCreaseKnobHelp);
  return table;
}

// Roberts' bodies are polyhedra of a few faces; merging a body's coplanar triangles and
// checking its convexity take time quadratic in its triangles, so larger bodies are refused.
inline constexpr std::uint32_t kMaxBodyTriangles = 8192;

// Why Roberts cannot draw this scene, or "" when it can.
std::string refusal(const PreparedScene& scene);

// Stats: "bodies", "body faces" (planes after merging), "back-face edges" (step 1),
// "edge-body pairs" (considered), "minimax rejections", "body tests" (linear programs
// solved), "hidden intervals", "junction lines". `edge`: hsr why --edge's, where the
// test of each body looked at for that edge is recorded, or null.
LineSet run(const PreparedScene& scene, const Knobs& knobs, Stats& stats, StepRecorder* steps = nullptr, EdgeWitness* edge = nullptr);

// The registry's entry (algorithms/algorithm.hpp).
AlgorithmEntry entry();

}  // namespace hsr::roberts
