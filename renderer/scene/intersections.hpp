// Where a scene's surfaces pass through one another, within one mesh or between meshes:
// every mesh edge that passes through a face, and the segments along which two faces
// cross. It is the scene's own geometry, the same for every view, so PreparedScene builds
// it once, on first use (surfaceIntersections). Appel's walk needs it: an edge's QI
// changes where it passes through a face, with no contour in sight, and the lines where
// faces cross are lines of the drawing, as Roberts' junction lines are.
//
// Exact predicates decide (renderer/geometry/predicates):
//   - a segment pq meets a face's plane where orient3d(face, p) and orient3d(face, q)
//     differ in sign (an end on the plane counts: it is where the segment leaves it),
//     inside the face where the three signs orient3d(p, q, corner, next corner) do not
//     differ. An end within what the placements' rounding can move of the plane is on
//     it (renderer/geometry/rounding.hpp): solids resting on each other as modelled touch, and do
//     not cross by rounding noise;
//   - two faces cross when each has corners strictly on both sides of the other's plane
//     (beyond the same rounding); their intersection is convex, so it is the segment
//     between the farthest two of the points where an edge of one passes through the
//     other (and a corner they share).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "renderer/util/math.hpp"

namespace hsr {

class PreparedScene;
class Stats;

// A segment meeting a triangle inside its closed outline.
struct Piercing {
  std::uint32_t face;
  double s;                   // where: the segment's 3D parameter, 0 at its first end, 1 at its second
  std::int8_t first, second;  // orient3d(face's corners, end) for each end: of opposite signs, or one 0
  // An end on the plane, or the segment through a side or a corner of the face: solids
  // touching, or a crossing where the faces around that side or corner decide together
  // what is crossed. No rule about this face alone settles what such a point changes.
  bool degenerate;
};

// Two faces crossing along a segment (faces that share a side are never a pair).
struct Junction {
  std::uint32_t faces[2];
  dvec3 from, to;
};

struct SurfaceIntersections {
  // Per mesh edge (EdgeAdjacency::edges), the faces it passes through, not counting those
  // around its own ends (which meet it there, at a corner); s runs from its vertex a to b.
  std::vector<std::vector<Piercing>> byEdge;
  std::vector<Junction> junctions;  // in order of their faces
};

// Stats: "face pairs with overlapping boxes", "edge-face tests", "edges through faces",
// "intersection lines"; phase "surface intersections".
SurfaceIntersections findSurfaceIntersections(const PreparedScene& scene, Stats& stats);
// The same, found the first time it is asked for and kept with the scene
// (PreparedScene::derived): the scene's own geometry, the same for every view.
const SurfaceIntersections& surfaceIntersectionsOf(const PreparedScene& scene, Stats& stats);

// Where segment pq, each of whose coordinates may be off by up to `rounding`, meets the
// scene's faces other than those in `skip`.
std::vector<Piercing> segmentPiercings(const PreparedScene& scene, const dvec3& p, const dvec3& q, double rounding,
                                       std::span<const std::uint32_t> skip);

}  // namespace hsr
