// Line drawings: the feature edges of a scene for one view, and the LineSet every
// hidden-line algorithm (Roberts, Appel, the floating horizon) produces and the line
// reference (renderer/line_reference) judges.
//
// An edge is judged along its projection: a parameter u in [0, 1] runs from the
// projected first endpoint to the projected second one in pixel coordinates, so a
// sub-interval's length times the projected length is a length in pixels (the line
// error of renderer/metrics). Under perspective, u is not the 3D parameter s of the
// edge; FeatureEdge::edgeParameter converts.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "renderer/camera.hpp"
#include "renderer/metrics.hpp"
#include "renderer/predicates.hpp"
#include "renderer/prepare.hpp"
#include "renderer/stats.hpp"

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

// One piece of an edge's projection, [begin, end] in its parameter u, with how many
// front-facing surfaces hide it: 0 is visible. An algorithm that only knows "hidden"
// (Roberts) reports kHidden.
struct LineSegment {
  static constexpr int kHidden = -1;
  std::uint32_t edge;
  double begin, end;
  int qi;
  bool visible() const { return qi == 0; }
};

// Where an edge of a drawing of curves lies: on curve `curve`, from running coordinate
// `from` to `to` (from < to; the 3D parameter s is linear in it). Two drawings of the same
// curves sampled differently are compared at equal coordinates (curveLineError).
struct CurvePlace {
  std::uint32_t curve;
  double from, to;
};

struct LineSet {
  int width = 0, height = 0;
  std::vector<FeatureEdge> edges;
  // Pieces covering every edge's [0, 1] with no gap, edge by edge, in increasing u.
  std::vector<LineSegment> segments;
  // A drawing of curves (the floating horizon's): one per edge. Empty otherwise.
  std::vector<CurvePlace> curvePlaces;
  // Why the drawing may be wrong somewhere, when the algorithm knows it may be ("" when
  // it is exact wherever its method is); hsr render prints it as a warning.
  std::string partial;
};

// Per edge, its projected length and its visible sub-intervals merged (the line error's
// input, renderer/metrics).
std::vector<EdgeVisibility> edgeVisibility(const LineSet& lines);

// How a drawing shows hidden parts.
enum class LineStyle {
  visible,  // visible parts only, solid black
  hidden,   // and hidden parts dashed grey
  qi,       // by quantitative invisibility: QI 0 black, 1 grey dashed, 2 and more light grey
};
inline constexpr double kLineWidthPixels = 1.5;
inline constexpr double kDashPixels = 6, kGapPixels = 4;

// SVG in the view's pixel coordinates (y down), one <line> per drawn piece.
std::string lineSetSvg(const LineSet& lines, LineStyle style);
// The drawing rasterized (renderer/raster's line rule) over a white background.
Frame lineSetFrame(const LineSet& lines, LineStyle style);

// The length in pixels of the parts drawn visible that the reference hides and that do
// not lie on a visible line of the exact drawing (within 1e-6 pixel). Where an edge lies
// exactly behind a nearer edge (an orthographic view along a face, say), the reference's
// closed triangles hide it while an algorithm may draw it: that counts in the line error
// but changes no pixel, and not here. Sampled every half pixel. truth[i] describes lines.edges[i].
double strayDrawnLength(const LineSet& lines, std::span<const EdgeVisibility> truth);

// Where a drawing is wrong, as an RGBA8 picture: the exactly visible lines light grey,
// parts drawn but hidden in the reference red, parts visible there but not drawn blue.
// truth[i] describes lines.edges[i].
std::vector<std::uint8_t> lineErrorMap(const LineSet& lines, std::span<const EdgeVisibility> truth);

// Appends edge `edge`'s pieces covering [0, 1]: the visible parts (sorted, disjoint) with QI
// 0, the parts between them kHidden.
void appendPieces(LineSet& lines, std::uint32_t edge, std::span<const Interval> visible);

// Two drawings of the same curves (both with curvePlaces), sampled differently: the drawn
// one (an algorithm's) against the exact one. They are compared at equal running
// coordinates along each curve, every quarter pixel: a point drawn visible is right when
// the exact drawing shows the curve there within kCurveTolerancePixels of it; a point the
// exact drawing shows is missed unless the drawn one shows it so. A curve drawn through
// the wrong place (a spike cut off by coarse sampling) is then wrongly drawn where it is
// and wrongly hidden where it should be. Lengths in pixels; the picture as lineErrorMap's.
inline constexpr double kCurveTolerancePixels = 0.5;
struct CurveComparison {
  LineError error;
  std::vector<std::uint8_t> errorMap;
};
CurveComparison compareCurveDrawings(const LineSet& drawn, const LineSet& exact, std::span<const EdgeVisibility> exactVisibility);

}  // namespace hsr
