// The pieces of the painter's orders: splitting a polygon by a plane, and which side of
// a plane the eye is on.
#include "algorithms/painter/order.hpp"

#include <algorithm>
#include <cmath>

namespace hsr::painter {

SplitPolygon splitPolygon(const std::vector<dvec3>& vertices, const std::vector<int>& sides, const std::vector<double>& heights) {
  SplitPolygon pieces;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (sides[i] >= 0) pieces.positive.push_back(vertices[i]);
    if (sides[i] <= 0) pieces.negative.push_back(vertices[i]);
    if (sides[i] * sides[j] < 0) {
      // The height is affine along the edge: it crosses zero at heights[i] / (heights[i]
      // - heights[j]). Rounding may put that a hair outside the edge (clamped) or make it
      // NaN when both heights round to zero (the midpoint).
      const double ratio = heights[i] / (heights[i] - heights[j]);
      const double along = std::isfinite(ratio) ? std::clamp(ratio, 0.0, 1.0) : 0.5;
      const dvec3 crossing = vertices[i] + along * (vertices[j] - vertices[i]);
      pieces.positive.push_back(crossing);
      pieces.negative.push_back(crossing);
    }
  }
  return pieces;
}

int eyeSide(const PreparedScene& scene, const CameraTransform& camera, std::uint32_t triangle, ExactPredicates& predicates) {
  const Triangle& t = scene.triangles()[triangle];
  const dvec3 &a = scene.positions()[t[0]], &b = scene.positions()[t[1]], &c = scene.positions()[t[2]];
  if (camera.perspective()) return predicates.orient3d(a, b, c, camera.camera().eye);
  return predicates.facing(a, b, c, -camera.forward());
}

}  // namespace hsr::painter
