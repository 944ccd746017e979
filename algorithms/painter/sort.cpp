// The depth sort: one depth per triangle, farthest first. It is right only when that
// single number orders every pair of overlapping triangles the way they overlap at every
// pixel; overlapping triangles with interleaved depth ranges, and triangles that pass
// through each other, break it. Kept so that the error shows what Newell's tests fix.
#include <algorithm>
#include <numeric>

#include "algorithms/painter/order.hpp"

namespace hsr::painter {

PaintOrder sortOrder(const ScreenGeometry& geometry, SortKey key, Stats& stats) {
  PhaseTimer timer(stats, "ordering");
  // Step 1: the key of each screen triangle, as a distance along the view axis: of the
  // centroid (the mean of the corners', since distance is affine in world space), of the
  // nearest corner, or of the farthest.
  const CameraTransform& camera = geometry.camera;
  std::vector<double> depth(geometry.triangles.size());
  for (std::size_t i = 0; i < depth.size(); ++i) {
    double d[3];
    for (int k = 0; k < 3; ++k) d[k] = camera.distanceFromScreenAffine(geometry.corners[i][k].z);
    switch (key) {
      case SortKey::centroid: depth[i] = (d[0] + d[1] + d[2]) / 3; break;
      case SortKey::nearest: depth[i] = std::min({d[0], d[1], d[2]}); break;
      case SortKey::farthest: depth[i] = std::max({d[0], d[1], d[2]}); break;
    }
  }
  // Step 2: farthest first. The sort is stable, so equal keys keep submission order.
  std::vector<std::uint32_t> order(depth.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return depth[a] > depth[b]; });
  PaintOrder result;
  result.pieces.reserve(order.size());
  for (const std::uint32_t index : order) result.add(index, {});
  return result;
}

}  // namespace hsr::painter
