#include "renderer/scene/intersections.hpp"

#include <algorithm>
#include <optional>
#include <unordered_map>

#include "renderer/geometry/predicates.hpp"
#include "renderer/scene/prepare.hpp"

namespace hsr {
namespace {

class FaceTests {
 public:
  explicit FaceTests(const PreparedScene& scene) : scene_(scene) {}

  const dvec3& corner(std::uint32_t face, int k) const { return scene_.positions()[scene_.triangles()[face][std::size_t(k)]]; }

  // Whether segment pq meets the face inside its closed outline, and how.
  std::optional<Piercing> pierce(const dvec3& p, const dvec3& q, double rounding, std::uint32_t face) {
    const dvec3 corners[3] = {corner(face, 0), corner(face, 1), corner(face, 2)};
    int first = exact_.orient3d(corners[0], corners[1], corners[2], p);
    int second = exact_.orient3d(corners[0], corners[1], corners[2], q);
    if (first == second || first * second > 0) return std::nullopt;  // the same side, or both ends on the plane
    int signs[3];
    for (int k = 0; k < 3; ++k) signs[k] = exact_.orient3d(p, q, corners[k], corners[(k + 1) % 3]);
    const bool anyPositive = signs[0] > 0 || signs[1] > 0 || signs[2] > 0;
    const bool anyNegative = signs[0] < 0 || signs[1] < 0 || signs[2] < 0;
    if (anyPositive == anyNegative) return std::nullopt;  // outside, or a face with no area
    const RoundedPlane plane = scene_.planeUpToPlacement(face);
    if (first != 0 && plane.holds(p, rounding)) first = 0;
    if (second != 0 && plane.holds(q, rounding)) second = 0;
    if (first == second) return std::nullopt;
    // The plane's heights at the ends, in double precision: only for where, never whether.
    const dvec3 normal = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
    const double hp = glm::dot(normal, p - corners[0]), hq = glm::dot(normal, q - corners[0]);
    const double s = first == 0 ? 0.0 : second == 0 ? 1.0 : std::clamp(hp / (hp - hq), 0.0, 1.0);
    return Piercing{face, s, static_cast<std::int8_t>(first), static_cast<std::int8_t>(second),
                    first == 0 || second == 0 || signs[0] == 0 || signs[1] == 0 || signs[2] == 0};
  }

  // Whether some corner of `face` lies strictly on each side of the plane of `other`,
  // beyond what the placements' rounding can move: faces that only touch (a solid
  // resting on another) do not cross.
  bool straddles(std::uint32_t face, std::uint32_t other) {
    const RoundedPlane plane = scene_.planeUpToPlacement(other);
    const double rounding = scene_.instanceOf(face).placementRounding;
    bool positive = false, negative = false;
    for (int k = 0; k < 3; ++k) {
      const dvec3& v = corner(face, k);
      const int side = exact_.orient3d(corner(other, 0), corner(other, 1), corner(other, 2), v);
      if (side == 0 || plane.holds(v, rounding)) continue;
      positive |= side > 0;
      negative |= side < 0;
    }
    return positive && negative;
  }

 private:
  const PreparedScene& scene_;
  ExactPredicates exact_;
};

}  // namespace

std::vector<Piercing> segmentPiercings(const PreparedScene& scene, const dvec3& p, const dvec3& q, double rounding,
                                       std::span<const std::uint32_t> skip) {
  FaceTests tests(scene);
  std::vector<Piercing> found;
  const dvec3 lo = glm::min(p, q), hi = glm::max(p, q);
  Stats ignored;
  scene.triangleBvh(ignored).visitPrimitives(
      [&](const BvhNode& node) {
        for (int axis = 0; axis < 3; ++axis)
          if (double(node.bounds[0][axis]) > hi[axis] || double(node.bounds[1][axis]) < lo[axis]) return false;
        return true;
      },
      [&](std::uint32_t face, std::uint32_t) {
        if (std::find(skip.begin(), skip.end(), face) != skip.end()) return;
        if (const std::optional<Piercing> piercing = tests.pierce(p, q, rounding, face)) found.push_back(*piercing);
      });
  return found;
}

SurfaceIntersections findSurfaceIntersections(const PreparedScene& scene, Stats& stats) {
  const EdgeAdjacency& adjacency = scene.edgeAdjacency(stats);
  const std::vector<std::uint32_t>& point = scene.distinctPoints(stats);
  const Bvh& bvh = scene.triangleBvh(stats);
  const auto& leaves = scene.leafTriangles(stats);
  PhaseTimer timer(stats, "surface intersections");
  const auto sharesPoint = [&](std::uint32_t face, std::uint32_t p) {
    const Triangle& t = scene.triangles()[face];
    return point[t[0]] == p || point[t[1]] == p || point[t[2]] == p;
  };
  FaceTests tests(scene);
  SurfaceIntersections result;
  result.byEdge.resize(adjacency.edges.size());

  // 1. Candidates: every two faces whose boxes overlap (the BVH against itself). Each mesh
  //    edge is tested with the faces near its first face, as that face's; the faces
  //    around its own ends are left out.
  std::int64_t facePairs = 0, edgeFaceTests = 0;
  const auto testEdgesOf = [&](std::uint32_t face, std::uint32_t other) {
    const Triangle& o = scene.triangles()[other];
    const std::uint32_t otherPoints[3] = {point[o[0]], point[o[1]], point[o[2]]};
    const auto onOther = [&](std::uint32_t v) { return point[v] == otherPoints[0] || point[v] == otherPoints[1] || point[v] == otherPoints[2]; };
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t e = adjacency.edgesOf[3 * face + std::uint32_t(k)];
      const MeshEdge& edge = adjacency.edges[e];
      if (edge.faces[0] != face || onOther(edge.a) || onOther(edge.b)) continue;
      ++edgeFaceTests;
      if (const std::optional<Piercing> piercing =
              tests.pierce(scene.positions()[edge.a], scene.positions()[edge.b], scene.instanceOf(face).placementRounding, other))
        result.byEdge[e].push_back(*piercing);
    }
  };
  std::vector<Aabb> boxes(leaves.size());  // by BVH slot
  for (std::size_t slot = 0; slot < leaves.size(); ++slot) {
    boxes[slot].grow(leaves[slot].a);
    boxes[slot].grow(leaves[slot].b);
    boxes[slot].grow(leaves[slot].c);
  }
  bvh.visitPairs(
      [](const BvhNode& x, const BvhNode& y) {
        for (int axis = 0; axis < 3; ++axis)
          if (x.bounds[0][axis] > y.bounds[1][axis] || y.bounds[0][axis] > x.bounds[1][axis]) return false;
        return true;
      },
      [&](std::uint32_t f, std::uint32_t slotF, std::uint32_t g, std::uint32_t slotG) {
        const Aabb &x = boxes[slotF], &y = boxes[slotG];
        if (glm::any(glm::lessThan(x.hi, y.lo)) || glm::any(glm::lessThan(y.hi, x.lo))) return;
        ++facePairs;
        testEdgesOf(f, g);
        testEdgesOf(g, f);
      });

  // 2. Per pair of crossing faces (the lower index first), the points where an edge of
  //    one passes through the other: each is a point of both faces.
  std::unordered_map<std::uint64_t, std::vector<dvec3>> crossingPoints;
  std::int64_t pierced = 0;
  for (std::uint32_t e = 0; e < adjacency.edges.size(); ++e) {
    const MeshEdge& edge = adjacency.edges[e];
    const dvec3 &a = scene.positions()[edge.a], &b = scene.positions()[edge.b];
    pierced += static_cast<std::int64_t>(result.byEdge[e].size());
    for (const Piercing& piercing : result.byEdge[e]) {
      if (piercing.first == 0 || piercing.second == 0) continue;  // an end on the plane: touching, not crossing
      for (const std::uint32_t face : adjacency.aroundVertex.around(edge.a)) {
        const Triangle& t = scene.triangles()[face];
        if (t[0] != edge.b && t[1] != edge.b && t[2] != edge.b) continue;  // not a face of this edge
        const std::uint32_t other = piercing.face;
        crossingPoints[std::uint64_t(std::min(face, other)) << 32 | std::max(face, other)].push_back(a + piercing.s * (b - a));
      }
    }
  }

  // 3. The segment of each crossing pair: the farthest two of its points, with the
  //    corner the two faces share when they share one (the segment then runs from it).
  for (auto& [key, points] : crossingPoints) {
    const auto f = static_cast<std::uint32_t>(key >> 32), g = static_cast<std::uint32_t>(key);
    if (!tests.straddles(f, g) || !tests.straddles(g, f)) continue;  // they touch, along a side or at a corner
    int shared = 0;
    for (const std::uint32_t corner : scene.triangles()[f])
      if (sharesPoint(g, point[corner])) {
        ++shared;
        points.push_back(scene.positions()[corner]);
      }
    if (shared >= 2) continue;  // neighbours along a side: they meet only there
    double longest = 0;
    Junction junction{{f, g}, {}, {}};
    for (std::size_t i = 0; i < points.size(); ++i)
      for (std::size_t j = i + 1; j < points.size(); ++j)
        if (const double length = glm::length(points[j] - points[i]); length > longest) {
          longest = length;
          junction.from = points[i];
          junction.to = points[j];
        }
    if (longest > 0) result.junctions.push_back(junction);  // else they touch at a point
  }
  // The hash map's order depends on the library: sort, so the drawing does not.
  std::sort(result.junctions.begin(), result.junctions.end(), [](const Junction& x, const Junction& y) {
    return std::pair(x.faces[0], x.faces[1]) < std::pair(y.faces[0], y.faces[1]);
  });
  stats.add("face pairs with overlapping boxes", facePairs);
  stats.add("edge-face tests", edgeFaceTests);
  stats.add("edges through faces", pierced);
  stats.add("intersection lines", static_cast<std::int64_t>(result.junctions.size()));
  return result;
}

const SurfaceIntersections& surfaceIntersectionsOf(const PreparedScene& scene, Stats& stats) {
  return scene.derived<SurfaceIntersections>([&] { return findSurfaceIntersections(scene, stats); });
}

}  // namespace hsr
