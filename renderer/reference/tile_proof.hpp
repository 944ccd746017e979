// The exact reference's shortcut for a tile of pixels that shows one triangle whole, or
// nothing (renderer/reference/reference.cpp): a proof, once for the tile, that no other
// triangle can be met by any of its rays in front of its candidate's plane, instead of a
// search per ray.
//
// A ray of the tile meets a triangle N at or before its hit on the candidate T only if N
// meets the segment from the ray's origin to that hit. Every such segment lies in one
// convex region: the tile's frustum (its four sides through the outer edges of its
// pixels, half a pixel outside every pixel center), beyond the near plane, on the side of
// T's plane the rays come from (for a tile showing nothing, before the far plane). So
// when no triangle but T touches the region, T is every ray's only candidate: the
// nearest hit, alone (no pixel ambiguous), at the parameter T's own bounded test gives,
// which is what the search records when T is its one candidate.
//
// The region is tested against the BVH's boxes, a box being out when it lies surely
// outside one of the region's six faces, and then against the triangles in the boxes left,
// by separating planes (apart()): a face of the region with the triangle surely outside;
// the triangle's own plane, or the plane through one of its edges and the rays' origin,
// with the region's eight corners surely on the far side. "Surely" leaves a margin of 1e-9
// of the magnitudes involved (the differences the value is computed from, and the
// coordinates of the points, whose own rounding is relative to them), far above the
// rounding of the test and of its points (a few units of 2^-53 of the same), so a
// rounding error can only keep something in, never leave it out;
// and behind T's plane the margin keeps in any triangle close enough for its depth
// interval to meet T's, but for one seen almost exactly edge-on (README, "What the
// reference trusts"). Anything left touching the region ends the proof, and the tile's
// rays are searched one by one, as without it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/rays/bvh.hpp"
#include "renderer/scene/prepare.hpp"

namespace hsr {

class TileRegion {
 public:
  // The region the rays through the pixel rectangle [x0, x1] x [y0, y1] (pixel edges, not
  // centers) cross before meeting `candidate`, or before the far plane when it is null.
  // No region (nothing to prove) when the candidate's plane passes too close to where the
  // rays come from to say which side that is.
  // `scene` holds every triangle.
  static std::optional<TileRegion> of(const CameraTransform& camera, const Aabb& scene, double x0, double y0, double x1, double y1,
                                      const PreparedScene::LeafTriangle* candidate);

  // Whether any triangle but the candidate may touch the region: a conservative answer,
  // true whenever one does. `nodesVisited` counts the BVH nodes it tested.
  bool touchedByAnother(const Bvh& bvh, const std::vector<PreparedScene::LeafTriangle>& triangles, std::int64_t& nodesVisited) const;

 private:
  // Inside: normal . (p - anchor) >= offset, decided with the margin above, for any point
  // p in `reach` (through()); `magnitude` bounds what each component of the normal was
  // computed from.
  struct Halfspace {
    dvec3 normal, anchor;
    double offset, margin;
    static Halfspace through(const dvec3& normal, const dvec3& magnitude, const dvec3& anchor, double offset, const Aabb& reach);
    bool surelyOutside(const dvec3& p) const;
    // Every point of the box surely outside.
    bool surelyOutside(const Aabb& box) const;
    // The other side, with the same margin.
    Halfspace flipped() const { return {-normal, anchor, -offset, margin}; }
  };
  bool apart(const PreparedScene::LeafTriangle& triangle) const;

  std::array<Halfspace, 6> halfspaces_;  // the four sides, the near plane, the candidate's plane or the far plane
  std::array<dvec3, 8> corners_;         // the corner rays where they cross the near plane, then the back one
  bool perspective_ = true;
  dvec3 eye_, forward_;                   // the camera's
  Aabb reach_;                            // the scene's box and the corners
  std::uint32_t candidate_ = 0;           // its id, or 0
};

}  // namespace hsr
