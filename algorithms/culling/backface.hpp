// Backface culling: on a closed surface wound counter-clockwise seen from outside
// (conventions.hpp), a triangle whose back faces the eye is hidden by the surface's
// own front, so it need not be drawn. Half the triangles of a closed mesh, for the
// price of one sign per triangle.
//
// It is only as right as that premise: an open surface seen from behind (a sheet, a
// plane seen from below, a model with holes) shows its back faces, and culling them
// removes what the reference sees. algorithms/culling/README.md lists the shipped
// scenes where that happens.
//
// Three ways to ask "does it face away?":
//   object          the triangle's plane against the eye: which side of it the eye is on
//                   (under orthographic projection, against the view direction), an exact
//                   sign (renderer/geometry/predicates). Culls the edge-on triangles too: they
//                   cover no pixel.
//   screen          the signed area of the triangle as projected, after clipping at the
//                   near plane (a corner behind the eye projects through it and flips
//                   the sign). A triangle wholly behind the near plane has no projection
//                   to judge and is kept for the clipper.
//   view-direction  the normal against the camera's forward vector only: right under
//                   orthographic projection, wrong under perspective, where a triangle
//                   off the center of the view can face the eye and away from the
//                   forward vector at once. Kept to show why.
#pragma once

#include "algorithms/culling/culling.hpp"
#include "renderer/geometry/camera.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/scene/visible_set.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::culling::backface {

// In the order of the stage's variants (culling.cpp).
enum class Variant { object, screen, viewDirection };

// The triangles of `in` that face the eye. Counts "backface: triangles tested" and
// "backface: triangles culled". With why, says for hsr why's triangles what the sign
// was read from (the eye's distance from the plane, the projected area, the cosine).
VisibleSet cull(const PreparedScene& scene, const CameraTransform& camera, Variant variant, const VisibleSet& in,
                int threads, Stats& stats, StageWitness* why = nullptr);

struct Knobs {
  Variant variant = Variant::object;
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table = KnobTable<Knobs>().variants(
      &Knobs::variant,
      {{Variant::object, "object", "the eye against the triangle's plane, an exact sign"},
       {Variant::screen, "screen", "the sign of the projected area, after clipping at the near plane"},
       {Variant::viewDirection, "view-direction", "the normal against the view direction only: wrong under perspective, kept to show why"}},
      "which facing test");
  return table;
}

// The stage's entry in culling::stages().
StageEntry stage();

}  // namespace hsr::culling::backface
