#include "algorithms/ray_casting/occupancy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hsr::ray_casting {
namespace {

// Does the triangle touch the cube of half-size `half` centered at the origin? The
// separating axis test of Akenine-Möller (2001): the box and the triangle are disjoint
// exactly when one of 13 axes separates them (the box's 3 normals, the triangle's
// normal, and the 9 cross products of a box normal with a triangle edge).
bool triangleTouchesCube(const dvec3& a, const dvec3& b, const dvec3& c, double half) {
  const auto separates = [&](const dvec3& axis) {
    const double pa = glm::dot(a, axis), pb = glm::dot(b, axis), pc = glm::dot(c, axis);
    const double radius = half * (std::abs(axis.x) + std::abs(axis.y) + std::abs(axis.z));
    return std::min({pa, pb, pc}) > radius || std::max({pa, pb, pc}) < -radius;
  };
  const dvec3 edges[3] = {b - a, c - b, a - c};
  for (int axis = 0; axis < 3; ++axis) {
    dvec3 normal(0);
    normal[axis] = 1;
    if (separates(normal)) return false;
    for (const dvec3& edge : edges)
      if (separates(glm::cross(normal, edge))) return false;
  }
  return !separates(glm::cross(edges[0], edges[1]));
}

// The squared distance from p to the triangle's closest point (Ericson, Real-Time
// Collision Detection, 5.1.5): find the Voronoi region of p among the triangle's
// vertices, edges and face, and project onto that feature. The triangle must have area:
// the edge projections divide by an edge's squared length.
double squaredDistanceToTriangle(const dvec3& p, const dvec3& a, const dvec3& b, const dvec3& c) {
  const auto squared = [](const dvec3& v) { return glm::dot(v, v); };
  const dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return squared(ap);  // vertex a
  const dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return squared(bp);  // vertex b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return squared(ap - ab * (d1 / (d1 - d3)));  // edge ab
  const dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return squared(cp);  // vertex c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return squared(ap - ac * (d2 / (d2 - d6)));  // edge ac
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)  // edge bc
    return squared(bp - (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const double denominator = va + vb + vc;
  if (denominator == 0) return std::min({squared(ap), squared(bp), squared(cp)});  // a degenerate triangle
  return squared(ap - ab * (vb / denominator) - ac * (vc / denominator));  // the face
}

}  // namespace

OccupancyGrid::OccupancyGrid(const Mesh& mesh, int voxelsAlongLongestSide) {
  Aabb box;
  for (const dvec3& p : mesh.positions) box.grow(p);
  if (box.empty()) box.grow(dvec3(0));
  const dvec3 extent = box.hi - box.lo;
  const double longest = std::max({extent.x, extent.y, extent.z});
  voxel_ = longest > 0 ? longest / voxelsAlongLongestSide : 1.0;
  // One voxel of padding on every side: the border the flood starts from is empty.
  for (int axis = 0; axis < 3; ++axis) dims_[axis] = int(std::ceil(extent[axis] / voxel_ - 1e-9)) + 2 + (extent[axis] == 0);
  dims_ = glm::max(dims_, glm::ivec3(3));
  bounds_.lo = box.lo - voxel_;
  bounds_.hi = bounds_.lo + dvec3(dims_) * voxel_;
  state_.assign(std::size_t(dims_.x) * std::size_t(dims_.y) * std::size_t(dims_.z), kUnknown);

  // Step 1: surface voxelization, one (voxel, triangle) pair per touching voxel. The
  // cube is grown by a hair so a triangle on a voxel face touches both voxels.
  const double half = 0.5 * voxel_ * (1 + 1e-9);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> touches;
  for (std::uint32_t triangle = 0; triangle < mesh.triangles.size(); ++triangle) {
    const Triangle& t = mesh.triangles[triangle];
    const dvec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    const glm::ivec3 first = cellOf(glm::min(a, glm::min(b, c)) - half), last = cellOf(glm::max(a, glm::max(b, c)) + half);
    for (int z = first.z; z <= last.z; ++z)
      for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) {
          const dvec3 center = bounds_.lo + (dvec3(x, y, z) + 0.5) * voxel_;
          if (triangleTouchesCube(a - center, b - center, c - center, half)) touches.emplace_back(indexOf({x, y, z}), triangle);
        }
  }
  std::sort(touches.begin(), touches.end());
  // A triangle without area still walls its voxels in, but it covers no pixel, so it is
  // never the triangle a ray sees: only triangles with area are listed for the search.
  std::vector<bool> hasArea(mesh.triangles.size());
  for (std::uint32_t triangle = 0; triangle < mesh.triangles.size(); ++triangle) {
    const Triangle& t = mesh.triangles[triangle];
    const dvec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    hasArea[triangle] = glm::cross(b - a, c - a) != dvec3(0);
  }
  for (const auto& [voxel, triangle] : touches) {
    if (surfaceVoxels_.empty() || surfaceVoxels_.back() != voxel) {
      surfaceVoxels_.push_back(voxel);
      firstTriangle_.push_back(std::uint32_t(triangles_.size()));
      state_[voxel] = kSurface;
    }
    if (hasArea[triangle]) triangles_.push_back(triangle);
  }
  firstTriangle_.push_back(std::uint32_t(triangles_.size()));

  // Step 2: flood the outside from a corner through 6-connected empty voxels.
  std::vector<glm::ivec3> frontier = {glm::ivec3(0)};
  state_[0] = kOutside;
  while (!frontier.empty()) {
    const glm::ivec3 cell = frontier.back();
    frontier.pop_back();
    for (int axis = 0; axis < 3; ++axis)
      for (const int direction : {-1, 1}) {
        glm::ivec3 next = cell;
        next[axis] += direction;
        if (next[axis] < 0 || next[axis] >= dims_[axis]) continue;
        State& state = state_[indexOf(next)];
        if (state != kUnknown) continue;
        state = kOutside;
        frontier.push_back(next);
      }
  }
  for (State& state : state_)
    if (state == kUnknown) state = kInside, ++insideVoxels_;
}

glm::ivec3 OccupancyGrid::cellOf(const dvec3& point) const {
  const dvec3 cell = glm::floor((point - bounds_.lo) / voxel_);
  return glm::clamp(glm::ivec3(glm::clamp(cell, dvec3(-1), dvec3(dims_))), glm::ivec3(0), dims_ - 1);
}

bool OccupancyGrid::occupied(const dvec3& point) const {
  for (int axis = 0; axis < 3; ++axis)
    if (!(point[axis] >= bounds_.lo[axis] && point[axis] < bounds_.hi[axis])) return false;
  return state_[indexOf(cellOf(point))] != kOutside;
}

std::uint32_t OccupancyGrid::nearestTriangle(const Mesh& mesh, const dvec3& point, std::int64_t& voxelsSearched) const {
  const glm::ivec3 center = cellOf(point);  // clamped into the grid when the point is outside it
  double best = std::numeric_limits<double>::infinity();
  std::uint32_t nearest = 0;
  const auto visit = [&](const glm::ivec3& cell) {
    ++voxelsSearched;
    const auto found = std::lower_bound(surfaceVoxels_.begin(), surfaceVoxels_.end(), indexOf(cell));
    if (found == surfaceVoxels_.end() || *found != indexOf(cell)) return;
    const std::size_t row = std::size_t(found - surfaceVoxels_.begin());
    for (std::uint32_t i = firstTriangle_[row]; i < firstTriangle_[row + 1]; ++i) {
      const Triangle& t = mesh.triangles[triangles_[i]];
      const double distance =
          squaredDistanceToTriangle(point, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
      if (distance < best || (distance == best && triangles_[i] < nearest)) best = distance, nearest = triangles_[i];
    }
  };
  // Shell r holds the cells at Chebyshev distance r from the point's cell; every cell
  // beyond it lies at least r voxels from the point (along the axis where it is r + 1
  // cells away; a point outside the grid is only farther from the cells inside).
  const int maxShell = std::max({dims_.x, dims_.y, dims_.z});
  for (int r = 0; r <= maxShell; ++r) {
    for (int z = std::max(0, center.z - r); z <= std::min(dims_.z - 1, center.z + r); ++z)
      for (int y = std::max(0, center.y - r); y <= std::min(dims_.y - 1, center.y + r); ++y) {
        if (std::abs(z - center.z) == r || std::abs(y - center.y) == r) {
          for (int x = std::max(0, center.x - r); x <= std::min(dims_.x - 1, center.x + r); ++x) visit({x, y, z});
          continue;
        }
        if (center.x - r >= 0) visit({center.x - r, y, z});
        if (center.x + r < dims_.x) visit({center.x + r, y, z});
      }
    const double reach = r * voxel_;
    if (best <= reach * reach) break;
  }
  return nearest;
}

}  // namespace hsr::ray_casting
