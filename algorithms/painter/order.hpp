// What the three orders share: the back-to-front list they produce (renderer/raster/pieces:
// PaintOrder), the splitting of a polygon by a plane, and which side of a plane the eye
// is on.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "algorithms/painter/painter.hpp"
#include "renderer/geometry/predicates.hpp"
#include "renderer/raster/pieces.hpp"
#include "renderer/raster/screen_triangles.hpp"

namespace hsr::painter {

// Splits a convex polygon by a plane, given each vertex's exact side of it (+1, 0, -1)
// and its signed height above it in double precision (only to place the crossings on
// the edges whose ends lie on opposite sides). Vertices on the plane go to both pieces.
struct SplitPolygon {
  std::vector<dvec3> positive, negative;
};
SplitPolygon splitPolygon(const std::vector<dvec3>& vertices, const std::vector<int>& sides, const std::vector<double>& heights);

// The orders (sort.cpp, newell.cpp; the BSP tree's is in bsp.hpp).
PaintOrder sortOrder(const ScreenGeometry& geometry, SortKey key, Stats& stats);
// steps: where Newell records its reorders and splits (renderer/steps/steps.hpp), or null.
PaintOrder newellOrder(const PreparedScene& scene, const ScreenGeometry& geometry, const Knobs& knobs, Stats& stats,
                       StepRecorder* steps = nullptr);

// Which side of the triangle's plane the eye is on, in the sign convention of Cut:
// +1, -1, or 0 when the plane passes through the eye (seen edge-on). Under orthographic
// projection the eye is the point at infinity behind the camera.
int eyeSide(const PreparedScene& scene, const CameraTransform& camera, std::uint32_t triangle, ExactPredicates& predicates);

}  // namespace hsr::painter
