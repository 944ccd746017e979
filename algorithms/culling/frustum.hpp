// Frustum culling: whatever lies wholly outside the view volume (the six planes of
// CameraTransform::frustumPlanes, Gribb and Hartmann's extraction) cannot be seen.
//
// Per object, with the bounds the prepared scene keeps for each copy (Instance):
//   sphere    outside when the center is farther than the radius behind some plane
//   aabb      outside when the box's center is farther behind some plane than the box
//             reaches towards it (its extent projected on the plane's normal)
//   bvh       the aabb test down the object BVH (renderer/rays/bvh): a node outside a plane
//             drops its whole subtree; a node wholly inside a plane passes that plane on
//             to its children as already settled, so they do not test it again (plane
//             masking). Keeps exactly what aabb keeps, with fewer tests on big scenes.
// Per triangle:
//   triangle     outside when all three corners are outside one and the same plane:
//                conservative, as the geometry stage's own rejection is
//   any-vertex   kept only when some corner is inside the volume, the test of many
//                shader tutorials. Wrong: a big triangle can cross the view with every
//                corner outside (a floor under the camera). Kept to show why.
//
// Every "outside" is decided with a margin far above the rounding of the distances, so
// a test never drops what is exactly on a plane; all the correct variants keep every
// triangle the reference sees (a false cull is a bug).
#pragma once

#include <array>
#include <cstdint>

#include "algorithms/culling/culling.hpp"
#include "renderer/geometry/camera.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/scene/visible_set.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::culling::frustum {

// In the order of the stage's variants (culling.cpp).
enum class Variant { sphere, aabb, bvh, triangle, anyVertex };

// The six planes, and the margin a distance must clear to count as outside: 2^-40 of the
// largest magnitude in play (the scene's boxes, the planes' offsets), thousands of times
// the rounding error of a distance (a few units in the last place), and far below
// anything a pixel can show. Counts the planes it tests.
struct ViewVolume {
  enum class Side { outside, crossing, inside };
  static constexpr std::uint32_t kAllPlanes = 0b111111;

  std::array<Plane, 6> planes;
  double slack = 0;
  std::int64_t planesTested = 0;

  ViewVolume(const PreparedScene& scene, const CameraTransform& camera);
  // A box given by its center and half extent, against plane `side`.
  Side boxSide(int side, const dvec3& center, const dvec3& halfExtent);
  // `outsideOf`, when given: the FrustumSide of the plane it lies wholly outside, if any.
  bool sphereOutside(const dvec3& center, double radius, int* outsideOf = nullptr);
  // The box against the planes still in `mask` (bit i: plane i unsettled); clears the
  // bits of the planes the box is wholly inside. False when it is outside one: what a
  // hierarchy's traversal passes down, so that children skip the planes settled above.
  bool boxMayBeInside(const dvec3& center, const dvec3& halfExtent, std::uint32_t& mask, int* outsideOf = nullptr);
  bool boxMayBeInside(const Aabb& box, std::uint32_t& mask, int* outsideOf = nullptr) {
    return boxMayBeInside(box.center(), (box.hi - box.lo) * 0.5, mask, outsideOf);
  }
};

// The triangles of `in` not proven outside the view volume. Counts, as they apply:
// "frustum: objects tested", "frustum: objects culled", "frustum: planes tested",
// "frustum: bvh nodes visited", "frustum: triangles tested", "frustum: triangles culled".
// `why`: hsr why's objects and triangles, where each test says which plane an object's
// bound (or a BVH node's above it) or a triangle's corners lie wholly outside, or that
// it may meet the view volume; null: not asked.
VisibleSet cull(const PreparedScene& scene, const CameraTransform& camera, Variant variant, const VisibleSet& in,
                int threads, Stats& stats, StageWitness* why = nullptr);

struct Knobs {
  Variant variant = Variant::sphere;
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table = KnobTable<Knobs>().variants(
      &Knobs::variant,
      {{Variant::sphere, "sphere", "per object: its bounding sphere against the six planes"},
       {Variant::aabb, "aabb", "per object: its box, by center and extent, against the six planes"},
       {Variant::bvh, "bvh", "per object, hierarchically: boxes down the object BVH, with plane masking"},
       {Variant::triangle, "triangle", "per triangle: outside when all three corners are outside one plane"},
       {Variant::anyVertex, "any-vertex", "per triangle: kept only if a corner is inside; wrong for big triangles, kept to show why"}},
      "which volume is tested");
  return table;
}

// The stage's entry in culling::stages().
StageEntry stage();

}  // namespace hsr::culling::frustum
