// Outlines: the feature edges (renderer/lines/feature_edges: boundaries, silhouettes, creases
// sharper than the outline's crease angle) drawn over a shaded image where the surface
// the frame shows does not hide them. Counts "outline edges" (tested) and "outline
// pixels" (drawn).
#pragma once

#include "renderer/geometry/camera.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/util/stats.hpp"

namespace hsr {

// Phase "outline". A 1.5-pixel line covers pixels on both sides of its edge, and on a
// crease or a silhouette one side shows the face beyond it, so an edge point counts as
// seen when it is no farther than the farthest surface within one pixel: edges on
// visible faces are drawn whole, edges behind a face are not (up to one pixel from that
// face's own outline). Under fog (when `fog` is given), a line fades with the distance
// of its nearest edge point at the pixel, as the surfaces did.
void drawOutline(const PreparedScene& scene, const CameraTransform& camera, const OutlineSettings& outline, const FogSettings* fog,
                 Frame& frame, Stats& stats);

}  // namespace hsr
