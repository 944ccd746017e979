// The exact line reference: for each edge of a line drawing, the parts of it that are
// truly visible, decided in object space. Every line algorithm is measured against it
// (renderer/reference/metrics: line error).
//
// A point X on an edge is hidden when some triangle meets the open segment from the eye
// to X (under orthographic, the half-line from X toward the viewer) in a point nearer
// than X. Triangles are closed (a ray through a triangle's edge meets it) and a triangle
// through X itself does not hide it, so an edge lying on a face, or two boxes touching
// face to face, stay visible. Triangles seen edge-on hide nothing.
//
// Per edge:
//   1. Candidates: the triangles whose projection overlaps the edge's and that come
//      nearer than its far end (a BVH walk with projected node boxes).
//   2. Events: every parameter where visibility can change: where the edge's
//      projection crosses a candidate's projected side or passes its projected
//      corner, and where the edge pierces a candidate's plane.
//   3. Between consecutive events visibility is constant; the midpoint decides it, by
//      the test above with every sign exact: each is the sign of alpha + s beta, with
//      alpha and beta determinants of the scene's doubles and s the midpoint's 3D
//      parameter, filtered in double precision and evaluated exactly
//      (renderer/geometry/exact.hpp) when the filter cannot decide.
// A junction line (EdgeKind::junction) is computed, not a mesh edge, so it lies on the two
// faces it joins only up to rounding: for it alone, a plane within 1e-9 of the local size
// of the point, or within 16 units in the last place of its largest coordinate (the
// rounding of a point computed far from the origin), holds it (and does not hide it).
// Event positions are computed in double precision; they bound intervals whose lengths
// the line error sums, so their rounding moves the error by about 1e-12 pixels per edge.
#pragma once

#include <span>
#include <vector>

#include "renderer/lines/feature_edges.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/stats.hpp"

namespace hsr {

// The scene must lie beyond the near plane (nearPlaneRefusal). threads: 0 = all cores.
// Stats: "line reference edges", "line reference candidates", "line reference
// intervals", "line reference exact fall-backs"; phase "line reference".
std::vector<EdgeVisibility> traceLineReference(const PreparedScene& scene, std::span<const FeatureEdge> edges, int threads,
                                               Stats& stats);

}  // namespace hsr
