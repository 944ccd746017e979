// Portal culling (Luebke and Georges, "Portals and Mirrors", 1995): from the eye's
// cell, a cell is drawn only when a chain of portals reaches it within the view.
//
//   1. Find the eye's cell (cells.hpp). Everything in it may be seen, within the view.
//   2. For each portal out of the cell, with the eye on this cell's side of its plane
//      (a line of sight crosses the plane once, from here to there): cut the portal by
//      what the chain so far lets through. Nothing left: no line passes, stop.
//   3. Narrow the view to what is left of the portal, and go on in the cell behind it
//      from step 2, never into a cell already on the chain (a line passes a convex cell
//      once).
//   4. An object of a cell reached is kept when its box is not wholly outside one of
//      the views that reached the cell.
//
// The view is a cone with its apex at the eye, narrowed in one of two ways (knob
// `narrowing`):
//   rect     the screen rectangle around the portal's image, intersected with the
//            rectangle so far: Luebke and Georges' cull box, four planes through the eye
//            whatever the portal's shape.
//   polygon  the cone over the portal's cut polygon itself, one plane through the eye
//            for each of its edges (kept within its own rectangle as well): tighter for
//            portals seen at an angle, and never keeps more than rect.
// Both keep every object a line of sight reaches; what they keep that is hidden (behind
// furniture, or inside a rectangle but outside the opening) the studies measure.
//
// An eye on a portal's plane (walking through a doorway) sees through the whole portal
// in every direction the view allows: the portal is passed without narrowing.
//
// Chains can multiply in a level with many loops. After `max-passes` portals passed in
// one frame (knob; 2^20 by default) the search gives up and keeps every object of every
// cell the portals connect to the eye's, counted as "portals: searches given up".
#pragma once

#include <cstdint>

#include "algorithms/culling/cells/cells.hpp"
#include "algorithms/culling/culling.hpp"

namespace hsr::culling::portals {

enum class Narrowing { rect, polygon };

struct Knobs {
  int variant = 0;  // one variant: the traversal from the eye's cell
  Narrowing narrowing = Narrowing::rect;
  int maxPasses = 1 << 20;
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table =
      KnobTable<Knobs>()
          .variants(&Knobs::variant,
                    {{0, "luebke-georges", "cells reached from the eye's cell through chains of portals, the view narrowed at each"}},
                    "the portal traversal")
          .choice("narrowing", &Knobs::narrowing, {{Narrowing::rect, "rect"}, {Narrowing::polygon, "polygon"}},
                  "rect: the screen rectangle of each portal (Luebke and Georges' cull box); polygon: the cone over the portal's "
                  "own outline, tighter, never keeping more")
          .number("max-passes", &Knobs::maxPasses, {1, 1e9}, {"1000"},
                  "portals passed in a frame before the search gives up and keeps every cell connected to the eye's");
  return table;
}

// The triangles of `in` of the objects kept. Counts "portals: cells visited" (a cell
// reached by two chains counts twice), "portals: cells reached", "portals: portals
// passed", "portals: portals cut away" (tried, and nothing of them in view), "portals:
// objects tested", "portals: objects kept", "portals: searches given up". Throws
// InputError for an orthographic camera (no eye to narrow from) and an eye in no cell.
// With why, says for hsr why's objects which of their cells a chain reached and whether
// a view through it holds their box.
VisibleSet cull(const PreparedScene& scene, const cells::CellMap& map, const CameraTransform& camera, const Knobs& knobs,
                const VisibleSet& in, Stats& stats, StageWitness* why = nullptr);

// Steps 1 to 3 alone: per cell, 1 when a chain of portals reaches it (the tests compare
// it with lines of sight walked cell by cell). Counts as cull() does, objects aside.
std::vector<std::uint8_t> cellsReached(const PreparedScene& scene, const cells::CellMap& map, const CameraTransform& camera,
                                       const Knobs& knobs, Stats& stats);

// The stage's entry in culling::stages().
StageEntry stage();

}  // namespace hsr::culling::portals
