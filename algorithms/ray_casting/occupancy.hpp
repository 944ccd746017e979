// The occupancy grid of one mesh: which voxels of its bounding box its solid fills, the
// march's inside test for meshes that have no analytic shape.
//
// Built the textbook way for closed meshes that may not be perfect:
//   1. Surface voxelization: every voxel a triangle touches (the triangle-box overlap
//      test of Akenine-Möller 2001) is occupied, and remembers the triangles.
//   2. Flood fill: the outside is every empty voxel reachable from the grid's border
//      (the grid is padded by one voxel, so the border is outside); every voxel the
//      flood cannot reach is inside.
// A duplicated face or a seam smaller than a voxel changes nothing; an open surface
// stays a shell one voxel thick. Voxels are cubes, so a flat object is one voxel thick.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/rays/bvh.hpp"
#include "renderer/scene/mesh.hpp"

namespace hsr::ray_casting {

class OccupancyGrid {
 public:
  // voxelsAlongLongestSide: the resolution along the mesh's longest bounding-box side.
  OccupancyGrid(const Mesh& mesh, int voxelsAlongLongestSide);

  // Is the object-space point in an occupied (surface or inside) voxel?
  bool occupied(const dvec3& point) const;

  // The mesh triangle nearest to an object-space point (lowest index on a tie), found in
  // growing shells of voxels around it; the mesh must be the one the grid was built from.
  // Adds the voxels it looked at to voxelsSearched: the deeper inside the point, the more.
  std::uint32_t nearestTriangle(const Mesh& mesh, const dvec3& point, std::int64_t& voxelsSearched) const;

  // The occupied region, padded by one voxel.
  const Aabb& bounds() const { return bounds_; }
  std::int64_t voxelCount() const { return std::int64_t(state_.size()); }
  std::int64_t surfaceVoxels() const { return std::int64_t(surfaceVoxels_.size()); }
  std::int64_t insideVoxels() const { return insideVoxels_; }

 private:
  enum State : std::uint8_t { kUnknown, kSurface, kInside, kOutside };

  glm::ivec3 cellOf(const dvec3& point) const;
  std::size_t indexOf(const glm::ivec3& cell) const {
    return (std::size_t(cell.z) * std::size_t(dims_.y) + std::size_t(cell.y)) * std::size_t(dims_.x) + std::size_t(cell.x);
  }

  Aabb bounds_;
  double voxel_ = 1;
  glm::ivec3 dims_{1};
  std::vector<State> state_;
  // The triangles touching each surface voxel, in compressed rows: surfaceVoxels_ holds
  // the voxel indices in increasing order, triangles_[firstTriangle_[i] ..
  // firstTriangle_[i + 1]) the triangles of surfaceVoxels_[i].
  std::vector<std::uint64_t> surfaceVoxels_;
  std::vector<std::uint32_t> firstTriangle_, triangles_;
  std::int64_t insideVoxels_ = 0;
};

}  // namespace hsr::ray_casting
