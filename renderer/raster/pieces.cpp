#include "renderer/raster/pieces.hpp"

namespace hsr {

void PaintOrder::add(std::uint32_t screenTriangle, const std::vector<Cut>& pieceCuts) {
  pieces.push_back({screenTriangle, static_cast<std::uint32_t>(cuts.size()), static_cast<std::uint32_t>(pieceCuts.size())});
  cuts.insert(cuts.end(), pieceCuts.begin(), pieceCuts.end());
}

namespace pieces_detail {

Plane planeOf(const PreparedScene& scene, std::uint32_t triangle) {
  const Triangle& t = scene.triangles()[triangle];
  const dvec3& a = scene.positions()[t[0]];
  return {a, glm::cross(scene.positions()[t[1]] - a, scene.positions()[t[2]] - a)};
}

}  // namespace pieces_detail
}  // namespace hsr
