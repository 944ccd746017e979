// The feature edges of a scene for one view: what a line drawing draws (contours,
// creases and boundaries of the meshes, and the junction lines and curves algorithms
// compute), each projected to the image; and the exact signs relative to the viewer
// that every hidden-line decision reduces to.
//
// An edge is judged along its projection: a parameter u in [0, 1] runs from the
// projected first endpoint to the projected second one in pixel coordinates, so a
// sub-interval's length times the projected length is a length in pixels (the line
// error of renderer/reference/metrics). Under perspective, u is not the 3D parameter s of the
// edge; FeatureEdge::edgeParameter converts.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/geometry/predicates.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/stats.hpp"

namespace hsr {

// Exact signs relative to the viewer: the eye point under perspective, the view
// direction (the eye at infinity) under orthographic. Every visibility decision of the
// line algorithms reduces to these and to orient3d of scene vertices.
class ViewerPredicates {
 public:
  explicit ViewerPredicates(const CameraTransform& camera) : camera_(camera) {}

  // +1 when the counter-clockwise (front) side of triangle abc faces the viewer, -1 when
  // its back does, 0 when it is seen exactly edge-on.
  int facing(const dvec3& a, const dvec3& b, const dvec3& c);
  // Which side of the plane through the eye, p and q the point y lies on: the plane holds
  // every eye ray through the segment pq, so two segments' projections cross exactly when
  // each one's endpoints lie on opposite sides of the other's plane.
  int side(const dvec3& p, const dvec3& q, const dvec3& y);
  ExactPredicates& exact() { return exact_; }

 private:
  const CameraTransform& camera_;
  ExactPredicates exact_;
};

// Per triangle: ViewerPredicates::facing (+1 front, 0 edge-on, -1 back).
std::vector<std::int8_t> viewFacing(const PreparedScene& scene, const CameraTransform& camera, Stats& stats);

enum class EdgeKind : std::uint8_t {
  boundary,  // one triangle: the rim of an open surface
  contour,   // between a front-facing triangle and one that is not: the silhouette
  crease,    // the normals of its two triangles differ by more than the crease angle
  junction,  // not a mesh edge: where two bodies' faces intersect (Roberts)
  curve,     // not a mesh edge: a piece of a curve drawn on a surface (the floating horizon)
};
const char* edgeKindName(EdgeKind kind);

struct FeatureEdge {
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  dvec3 from, to;                  // world space
  dvec2 pixelFrom, pixelTo;        // their projections (pixel coordinates)
  double divisorFrom, divisorTo;   // the projection's w at each end: d under perspective, 1 under orthographic
  std::uint32_t vertexFrom = kNone, vertexTo = kNone;  // scene vertices (kNone for a junction)
  std::uint32_t meshEdge = kNone;  // index into EdgeAdjacency::edges (kNone for a junction)
  // The triangles it bounds (the second kNone on a boundary), or for a junction a triangle
  // of each surface that meets there: whose edge it is, for a reader (SVG titles).
  std::array<std::uint32_t, 2> faces = {kNone, kNone};
  EdgeKind kind = EdgeKind::crease;

  double lengthPixels() const;
  // The 3D parameter s (from + s (to - from)) of the point projected at parameter u.
  double edgeParameter(double u) const;
  // Its inverse: the projected parameter u of the point at 3D parameter s.
  double projectedParameter(double s) const;
  dvec2 pixelAt(double u) const { return pixelFrom + u * (pixelTo - pixelFrom); }
};

// A world-space segment as a FeatureEdge of this view (every point beyond the near plane).
FeatureEdge projectEdge(const CameraTransform& camera, const dvec3& from, const dvec3& to, EdgeKind kind);

// The feature edges of the scene for this view: boundary, contour and crease edges
// (a non-manifold edge counts as a crease, so it is always drawn), in mesh-edge order.
// The diagonals of flat quads have an angle of zero and are never creases.
// Stats: "feature edges", and the adjacency's counters on first use.
inline constexpr double kDefaultCreaseDegrees = 30;
std::vector<FeatureEdge> featureEdges(const PreparedScene& scene, const CameraTransform& camera,
                                      std::span<const std::int8_t> facing, double creaseDegrees, Stats& stats);

// "" when every vertex lies beyond the near plane, which the line algorithms and the
// line reference assume (they do not clip); otherwise why not, naming the object.
std::string nearPlaneRefusal(const PreparedScene& scene);

}  // namespace hsr
