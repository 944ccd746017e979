#include "renderer/prepare.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <unordered_map>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/error.hpp"

namespace hsr {
namespace {

// The box of the vertices, and the sphere about its center through the farthest one.
// The radius is rounded up by far more than its own rounding error (a few units in the
// last place of the distances): a sphere that misses a vertex by a rounding error would
// let a culling stage drop a visible object.
void setBounds(std::span<const dvec3> vertices, Instance& instance) {
  for (const dvec3& p : vertices) instance.box.grow(p);
  if (instance.box.empty()) return;
  instance.sphereCenter = instance.box.center();
  double farthest = 0;
  for (const dvec3& p : vertices) farthest = std::max(farthest, glm::length(p - instance.sphereCenter));
  const double magnitude = glm::length(glm::abs(instance.sphereCenter)) + farthest;
  instance.sphereRadius = farthest + magnitude * 0x1p-40;
}

}  // namespace

PreparedScene::PreparedScene(const Scene& scene) : PreparedScene(scene, {dmat4(1.0)}) {}

PreparedScene::PreparedScene(const Scene& scene, const std::vector<dmat4>& sceneCopies, const dmat4& objectMotion)
    : scene_(&scene), width_(scene.width), height_(scene.height) {
  // Flatten every copy of every object into world space, in id order. Transforms are
  // composed in double so a model far from the origin keeps its float precision.
  for (const dmat4& sceneCopy : sceneCopies) {
    for (std::uint32_t objectIndex = 0; objectIndex < scene.objects.size(); ++objectIndex) {
      const SceneObject& object = scene.objects[objectIndex];
      const dmat4 objectToWorld = object.transform.worldFromObject();
      // The motion about the object's own origin, where its transform placed it.
      const dmat4 motion = glm::translate(dmat4(1.0), object.transform.translate) * objectMotion *
                           glm::translate(dmat4(1.0), -object.transform.translate);
      const std::vector<dmat4> copies = object.instancing.copies();
      for (std::uint32_t copy = 0; copy < copies.size(); ++copy) {
        const dmat4 worldFromObject = sceneCopy * copies[copy] * motion * objectToWorld;
        const auto firstVertex = static_cast<std::uint32_t>(positions_.size());
        Instance instance;
        for (const dvec3& p : object.mesh->positions) {
          positions_.push_back(dvec3(worldFromObject * dvec4(p, 1.0)));
          for (int i = 0; i < 3; ++i) {  // glm's matrices are indexed [column][row]
            const double terms = std::abs(worldFromObject[0][i] * p.x) + std::abs(worldFromObject[1][i] * p.y) +
                                 std::abs(worldFromObject[2][i] * p.z) + std::abs(worldFromObject[3][i]);
            instance.placementRounding = std::max(instance.placementRounding, roundingGamma(4) * terms);
          }
        }
        for (int i = 0; i < 3; ++i)
          instance.statedRounding = std::max(instance.statedRounding, object.mesh->statedRounding *
                                                                          (std::abs(worldFromObject[0][i]) + std::abs(worldFromObject[1][i]) +
                                                                           std::abs(worldFromObject[2][i])));
        instance.firstVertex = firstVertex;
        instance.vertexCount = static_cast<std::uint32_t>(object.mesh->positions.size());
        setBounds(std::span(positions_).subspan(firstVertex), instance);
        instance.object = objectIndex;
        instance.copy = copy;
        instance.firstTriangle = static_cast<std::uint32_t>(triangles_.size());
        instance.triangleCount = static_cast<std::uint32_t>(object.mesh->triangles.size());
        instance.color = object.color;
        instance.opacity = object.opacity;
        instance.worldFromObject = worldFromObject;
        instances_.push_back(instance);
        for (const Triangle& t : object.mesh->triangles)
          triangles_.push_back({t[0] + firstVertex, t[1] + firstVertex, t[2] + firstVertex});
      }
    }
  }
}

void PreparedScene::setSize(int width, int height) {
  checkImageSize(width, height, "--size");
  width_ = width;
  height_ = height;
}

const Instance& PreparedScene::instanceOf(std::uint32_t triangle) const {
  HSR_CHECK(triangle < triangles_.size());
  const auto after = std::upper_bound(instances_.begin(), instances_.end(), triangle,
                                      [](std::uint32_t t, const Instance& i) { return t < i.firstTriangle; });
  return *(after - 1);
}

Aabb PreparedScene::bounds() const {
  Aabb box;
  for (const Instance& instance : instances_) box.grow(instance.box);
  return box;
}

RoundedPlane PreparedScene::planeUpToPlacement(std::uint32_t planeTriangle) const {
  const Triangle& t = triangles_[planeTriangle];
  return RoundedPlane(positions_[t[0]], positions_[t[1]], positions_[t[2]], instanceOf(planeTriangle).placementRounding);
}

bool PreparedScene::liesOn(const RoundedPlane& plane, std::uint32_t triangle) const {
  const double rounding = instanceOf(triangle).placementRounding;
  for (const std::uint32_t corner : triangles_[triangle])
    if (!plane.holds(positions_[corner], rounding)) return false;
  return true;
}

dvec3 PreparedScene::faceNormal(std::uint32_t triangle) const {
  const Triangle& t = triangles_[triangle];
  const dvec3 n = glm::cross(positions_[t[1]] - positions_[t[0]], positions_[t[2]] - positions_[t[0]]);
  const double length = glm::length(n);
  return length > 0 ? n / length : dvec3(0);
}

const std::vector<std::array<dvec3, 3>>& PreparedScene::cornerNormals(Stats& stats) const {
  std::call_once(normalsBuilt_, [&] {
    PhaseTimer timer(stats, "normals");
    const std::size_t faces = triangles_.size();
    cornerNormals_.assign(faces, {dvec3(0), dvec3(0), dvec3(0)});
    // Step 1: the normals the mesh file gave, moved to world space by the inverse
    // transpose of the copy's placement (which keeps them perpendicular to the surface
    // under non-uniform scaling).
    std::int64_t fromMesh = 0;
    for (const Instance& instance : instances_) {
      const Mesh& mesh = *scene_->objects[instance.object].mesh;
      if (mesh.cornerNormals.empty()) continue;
      const dmat3 normalMatrix = glm::transpose(glm::inverse(dmat3(instance.worldFromObject)));
      for (std::uint32_t t = 0; t < instance.triangleCount; ++t)
        for (int k = 0; k < 3; ++k) {
          const dvec3 given = normalMatrix * mesh.cornerNormals[t][k];
          if (glm::length(given) == 0) continue;
          cornerNormals_[instance.firstTriangle + t][k] = glm::normalize(given);
          ++fromMesh;
        }
    }
    if (fromMesh == std::int64_t(3 * faces)) {
      stats.add("normals from the mesh", fromMesh);
      return;
    }
    // Step 2: every other corner: each face's contribution at a vertex is its unit normal
    // weighted by its angle there, so the result does not depend on how the surface
    // around the vertex was triangulated.
    std::vector<dvec3> unitNormal(faces);
    std::vector<std::array<double, 3>> cornerAngle(faces);
    for (std::size_t f = 0; f < faces; ++f) {
      unitNormal[f] = faceNormal(static_cast<std::uint32_t>(f));
      const Triangle& t = triangles_[f];
      for (int k = 0; k < 3; ++k) {
        const dvec3 e1 = positions_[t[(k + 1) % 3]] - positions_[t[k]], e2 = positions_[t[(k + 2) % 3]] - positions_[t[k]];
        cornerAngle[f][k] = std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
      }
    }
    const VertexTriangles around = buildVertexTriangles(positions_.size(), triangles_);

    const double creaseCosine = std::cos(kCreaseDegrees * std::numbers::pi / 180);
    std::int64_t computed = 0;
    for (std::size_t f = 0; f < faces; ++f)
      for (int k = 0; k < 3; ++k) {
        if (glm::length(cornerNormals_[f][k]) > 0) continue;  // given by the mesh
        const std::uint32_t v = triangles_[f][k];
        dvec3 sum(0);
        for (const std::uint32_t other : around.around(v)) {
          if (glm::dot(unitNormal[other], unitNormal[f]) < creaseCosine) continue;
          const int corner = triangles_[other][0] == v ? 0 : triangles_[other][1] == v ? 1 : 2;
          sum += unitNormal[other] * cornerAngle[other][corner];
        }
        const double length = glm::length(sum);
        cornerNormals_[f][k] = length > 0 ? sum / length : unitNormal[f];
        ++computed;
      }
    stats.add("normals computed", computed);
    if (fromMesh > 0) stats.add("normals from the mesh", fromMesh);
  });
  return cornerNormals_;
}

const Bvh& PreparedScene::triangleBvh(Stats& stats) const {
  std::call_once(bvhBuilt_, [&] {
    PhaseTimer timer(stats, "bvh build");
    std::vector<Aabb> boxes(triangles_.size());
    for (std::size_t i = 0; i < triangles_.size(); ++i)
      for (std::uint32_t v : triangles_[i]) boxes[i].grow(positions_[v]);
    triangleBvh_ = Bvh(boxes);
    stats.add("bvh nodes built", static_cast<std::int64_t>(triangleBvh_.nodes().size()));
    leafTriangles_.reserve(triangles_.size());
    for (const std::uint32_t triangle : triangleBvh_.order()) {
      const Triangle& t = triangles_[triangle];
      leafTriangles_.push_back({positions_[t[0]], positions_[t[1]], positions_[t[2]], triangle + 1});
    }
  });
  return triangleBvh_;
}

const Bvh& PreparedScene::objectBvh(Stats& stats) const {
  std::call_once(objectBvhBuilt_, [&] {
    PhaseTimer timer(stats, "object bvh build");
    std::vector<Aabb> boxes;
    boxes.reserve(instances_.size());
    for (const Instance& instance : instances_) boxes.push_back(instance.box);
    objectBvh_ = Bvh(boxes);
    stats.add("object bvh nodes built", static_cast<std::int64_t>(objectBvh_.nodes().size()));
  });
  return objectBvh_;
}

const EdgeAdjacency& PreparedScene::edgeAdjacency(Stats& stats) const {
  std::call_once(adjacencyBuilt_, [&] {
    PhaseTimer timer(stats, "edge adjacency");
    edgeAdjacency_ = buildEdgeAdjacency(positions_.size(), triangles_);
    stats.add("mesh edges built", static_cast<std::int64_t>(edgeAdjacency_.edges.size()));
  });
  return edgeAdjacency_;
}

const std::vector<std::uint32_t>& PreparedScene::distinctPoints(Stats& stats) const {
  std::call_once(pointsBuilt_, [&] {
    PhaseTimer timer(stats, "distinct points");
    const auto hash = [](const dvec3& p) {
      const std::hash<double> h;
      return h(p.x) ^ (h(p.y) * 0x9e3779b97f4a7c15ull) ^ (h(p.z) * 0xc2b2ae3d27d4eb4full);
    };
    std::unordered_map<dvec3, std::uint32_t, decltype(hash)> firstAt(positions_.size(), hash);
    distinctPoints_.resize(positions_.size());
    for (std::uint32_t v = 0; v < positions_.size(); ++v) distinctPoints_[v] = firstAt.try_emplace(positions_[v], v).first->second;
  });
  return distinctPoints_;
}

const SurfaceIntersections& PreparedScene::surfaceIntersections(Stats& stats) const {
  std::call_once(intersectionsBuilt_, [&] { surfaceIntersections_ = findSurfaceIntersections(*this, stats); });
  return surfaceIntersections_;
}

const std::vector<PreparedScene::LeafTriangle>& PreparedScene::leafTriangles(Stats& stats) const {
  triangleBvh(stats);
  return leafTriangles_;
}

}  // namespace hsr
