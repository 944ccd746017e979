#include "renderer/scene/prepare.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <unordered_map>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/util/error.hpp"
#include "renderer/util/memory.hpp"
#include "renderer/util/parallel.hpp"
#include "renderer/util/portable_math.hpp"

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
        instance.normalFromObject = glm::transpose(glm::inverse(dmat3(worldFromObject)));
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

std::string PreparedScene::instanceName(const Instance& instance) const {
  const SceneObject& object = scene_->objects[instance.object];
  std::string name = "\"" + object.name + "\"";
  if (object.instancing.copyCount() > 1) name += " copy " + std::to_string(instance.copy);
  return name;
}

std::string PreparedScene::triangleName(std::uint32_t triangle) const {
  return "triangle " + std::to_string(triangle) + " of " + instanceName(instanceOf(triangle));
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

const VertexTriangles& PreparedScene::trianglesAroundVertices(Stats& stats, int threads) const {
  std::call_once(aroundBuilt_, [&] {
    PhaseTimer timer(stats, "vertex triangles");
    trianglesAroundVertices_ = buildVertexTriangles(positions_.size(), triangles_, threads);
    faceStates_ = std::make_unique<std::atomic<std::uint8_t>[]>(triangles_.size());  // all kFaceAbsent
    faceGeometries_ = uninitializedArray<FaceGeometry>(triangles_.size());  // written before it is read
  });
  return trianglesAroundVertices_;
}

PreparedScene::FaceGeometry PreparedScene::faceGeometry(std::uint32_t triangle) const {
  std::atomic<std::uint8_t>& state = faceStates_[triangle];
  if (state.load(std::memory_order_acquire) == kFaceWritten) return faceGeometries_[triangle];
  FaceGeometry computed{faceNormal(triangle), {}};
  const Triangle& t = triangles_[triangle];
  for (std::size_t corner = 0; corner < 3; ++corner) {
    const dvec3 e1 = positions_[t[(corner + 1) % 3]] - positions_[t[corner]], e2 = positions_[t[(corner + 2) % 3]] - positions_[t[corner]];
    computed.angles[corner] = portable::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
  }
  // Only the thread that claims the entry writes it; one that finds it claimed keeps its
  // own copy, which has the same bits.
  std::uint8_t absent = kFaceAbsent;
  if (state.compare_exchange_strong(absent, kFaceBeingWritten, std::memory_order_relaxed)) {
    faceGeometries_[triangle] = computed;
    state.store(kFaceWritten, std::memory_order_release);
  }
  return computed;
}

int PreparedScene::cornerNormals(std::uint32_t triangle, const VertexTriangles& around, std::array<dvec3, 3>& normals) const {
  const Instance& instance = instanceOf(triangle);
  const Mesh& mesh = *scene_->objects[instance.object].mesh;
  const dvec3 face = faceGeometry(triangle).normal;
  static const double creaseCosine = portable::cos(kCreaseDegrees * std::numbers::pi / 180);
  int fromMesh = 0;
  for (int k = 0; k < 3; ++k) {
    // Step 1: the normal the mesh file gave at this corner, if any.
    if (!mesh.cornerNormals.empty()) {
      const dvec3 given = instance.normalFromObject * mesh.cornerNormals[triangle - instance.firstTriangle][std::size_t(k)];
      if (glm::length(given) > 0) {
        normals[std::size_t(k)] = glm::normalize(given);
        ++fromMesh;
        continue;
      }
    }
    // Step 2: each neighbouring face within the crease angle contributes its unit normal
    // weighted by its angle at the vertex, so the result does not depend on how the
    // surface around the vertex was triangulated.
    const std::uint32_t v = triangles_[triangle][std::size_t(k)];
    dvec3 sum(0);
    for (const std::uint32_t other : around.around(v)) {
      const FaceGeometry neighbour = faceGeometry(other);
      if (glm::dot(neighbour.normal, face) < creaseCosine) continue;
      const Triangle& t = triangles_[other];
      sum += neighbour.normal * neighbour.angles[t[0] == v ? 0 : t[1] == v ? 1 : 2];
    }
    const double length = glm::length(sum);
    normals[std::size_t(k)] = length > 0 ? sum / length : face;
  }
  return fromMesh;
}

const Bvh& PreparedScene::triangleBvh(Stats& stats, int threads) const {
  std::call_once(bvhBuilt_, [&] {
    PhaseTimer timer(stats, "bvh build");
    // Each triangle's box, and after the build its corners in leaf order, on the threads:
    // every item writes only its own slot.
    constexpr std::size_t kChunk = 16384;
    std::vector<Aabb> boxes(triangles_.size());
    parallelForEach(triangles_.size(), kChunk, threads, [&](std::size_t i) {
      for (std::uint32_t v : triangles_[i]) boxes[i].grow(positions_[v]);
    });
    triangleBvh_ = Bvh(boxes, threads);
    stats.add("bvh nodes built", static_cast<std::int64_t>(triangleBvh_.nodes().size()));
    leafTriangles_.resize(triangles_.size());
    parallelForEach(triangles_.size(), kChunk, threads, [&](std::size_t slot) { leafTriangles_[slot] = leafTriangle(triangleBvh_.order()[slot]); });
  });
  return triangleBvh_;
}

const WideBvh& PreparedScene::wideTriangleBvh(Stats& stats, int threads) const {
  const Bvh& binary = triangleBvh(stats, threads);
  std::call_once(wideBvhBuilt_, [&] {
    PhaseTimer timer(stats, "wide bvh build");
    wideTriangleBvh_ = WideBvh(binary, threads);
    stats.add("wide bvh nodes built", static_cast<std::int64_t>(wideTriangleBvh_.nodes().size()));
  });
  return wideTriangleBvh_;
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

PreparedScene::DerivedSlot& PreparedScene::derivedSlot(std::type_index type) const {
  std::lock_guard lock(derivedMutex_);
  std::unique_ptr<DerivedSlot>& slot = derived_[type];
  if (!slot) slot = std::make_unique<DerivedSlot>();
  return *slot;
}

const std::vector<PreparedScene::LeafTriangle>& PreparedScene::leafTriangles(Stats& stats) const {
  triangleBvh(stats);
  return leafTriangles_;
}

}  // namespace hsr
