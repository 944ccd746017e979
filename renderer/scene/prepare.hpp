// PreparedScene: the scene flattened into world-space triangles with stable ids, plus
// the derived data some algorithms and effects need, built only on first use (and
// counted in Stats, so a scene that does not need them provably does not pay).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <typeindex>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/geometry/rounding.hpp"
#include "renderer/rays/bvh.hpp"
#include "renderer/rays/wide_bvh.hpp"
#include "renderer/scene/adjacency.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/util/stats.hpp"

namespace hsr {

// One copy of one scene object.
struct Instance {
  std::uint32_t object = 0;         // index into Scene::objects
  std::uint32_t copy = 0;           // index among the object's copies
  std::uint32_t firstTriangle = 0;  // global index of its first triangle
  std::uint32_t triangleCount = 0;
  std::uint32_t firstVertex = 0;    // its vertices are positions()[firstVertex, firstVertex + vertexCount)
  std::uint32_t vertexCount = 0;
  // World-space bounds of its vertices, for the culling stages: the box is exact; the
  // sphere is centered on the box and its radius rounded up, so both contain every vertex.
  Aabb box;
  dvec3 sphereCenter{0};
  double sphereRadius = 0;
  vec3 color{0.8f};
  double opacity = 1;
  dmat4 worldFromObject{1.0};  // the copy's placement: its triangles are the object's mesh moved by it
  // Bounds on how far each world coordinate of its vertices lies from the exact
  // placement of the model (renderer/geometry/rounding.hpp uses them):
  //   placementRounding: the rounding of computing worldFromObject * p in double, at most
  //     gamma_4 (sum_j |M_ij p_j| + |t_i|), the largest over its vertices and axes;
  //   statedRounding: the mesh file's own (Mesh::statedRounding) carried to world units
  //     by the placement's linear part (its largest row sum of magnitudes).
  double placementRounding = 0;
  double statedRounding = 0;
  // The inverse transpose of the placement's linear part: it carries a mesh file's
  // normals to world space and keeps them perpendicular under non-uniform scaling.
  dmat3 normalFromObject{1.0};
};

class PreparedScene {
 public:
  explicit PreparedScene(const Scene& scene);
  // The whole scene repeated once per transform (world from scene copy), copy by copy:
  // how hsr sweep --scale triangles grows a scene by instancing. `objectMotion` moves
  // every object copy about its own origin (where the object's transform put it, before
  // its copy's placement): how hsr study culling-combos turns each object about its own
  // vertical axis.
  PreparedScene(const Scene& scene, const std::vector<dmat4>& sceneCopies, const dmat4& objectMotion = dmat4(1.0));

  const Scene& scene() const { return *scene_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // The scene's camera at the image size: the view every algorithm renders. Made afresh
  // from the Scene's camera, which a walkthrough moves from frame to frame.
  CameraTransform camera() const { return CameraTransform(scene_->camera, width_, height_); }
  // Render at another resolution than the scene file asks for (--size).
  void setSize(int width, int height);

  // #V world-space positions in double precision and #T triangles indexing them,
  // in global id order (conventions.hpp).
  const std::vector<dvec3>& positions() const { return positions_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<Instance>& instances() const { return instances_; }
  std::size_t triangleCount() const { return triangles_.size(); }

  // The world-space box around every instance (empty for a scene with no triangles).
  Aabb bounds() const;

  // The instance that owns a triangle (binary search over firstTriangle).
  const Instance& instanceOf(std::uint32_t triangle) const;
  // A triangle as a person would name it in a caption or a message: its global index
  // (the id image's value - 1) and its object, `triangle 7 of "lamp"`, with the copy
  // when the object has several (`triangle 7 of "tree" copy 3`).
  std::string triangleName(std::uint32_t triangle) const;
  // An instance as the same names have it: `"lamp"`, or `"tree" copy 3`.
  std::string instanceName(const Instance& instance) const;

  // Coplanarity up to the placements' rounding (Instance::placementRounding,
  // rounding.hpp): planeUpToPlacement(p) is triangle p's plane, and liesOn says whether
  // every corner of `triangle` lies on it within what that rounding can move: true for
  // faces coplanar as modelled, false for any whose separation rounding cannot explain
  // and when the plane's triangle has no area.
  RoundedPlane planeUpToPlacement(std::uint32_t planeTriangle) const;
  bool liesOn(const RoundedPlane& plane, std::uint32_t triangle) const;

  // Unit face normal (b - a) x (c - a); zero for a degenerate triangle.
  dvec3 faceNormal(std::uint32_t triangle) const;
  // The triangles around each vertex, built on first use (phase "vertex triangles"):
  // what corner normals average over.
  const VertexTriangles& trianglesAroundVertices(Stats& stats, int threads) const;
  // A triangle's unit normal (faceNormal) and its angle at each corner, what a corner
  // normal weighs its neighbours by. Computed the first time any corner normal needs it
  // and kept: each triangle is a neighbour of every triangle sharing one of its vertices,
  // about eighteen asks on a closed mesh. Safe from any thread once
  // trianglesAroundVertices has been built.
  struct FaceGeometry {
    dvec3 normal;
    std::array<double, 3> angles;
  };
  FaceGeometry faceGeometry(std::uint32_t triangle) const;
  // One triangle's three unit corner normals: the mesh file's own where it gave one (OBJ
  // vn, carried by Instance::normalFromObject), and elsewhere the angle-weighted average
  // of the face normals around the corner's vertex that lie within kCreaseDegrees of this
  // face's, so smooth surfaces shade smoothly and a cube keeps its edges. Computed on
  // demand, for the triangles shading sees (renderer/shading/shading counts them: "normals from
  // the mesh", "normals computed"); returns how many of the three the mesh gave.
  static constexpr double kCreaseDegrees = 40;
  int cornerNormals(std::uint32_t triangle, const VertexTriangles& around, std::array<dvec3, 3>& normals) const;

  // A BVH over the triangles (primitive i = global triangle i), built on first use
  // (phase "bvh build", counter "bvh nodes built"), on `threads` threads (0: all cores):
  // the tree is the same for any count, so a render asks first with its own.
  const Bvh& triangleBvh(Stats& stats, int threads = 1) const;

  // The triangles' corners in the BVH's leaf order (slot i holds triangleBvh().order()[i]),
  // so a ray tracer reads a leaf as one contiguous run; built with the BVH.
  struct LeafTriangle {
    dvec3 a, b, c;
    std::uint32_t id;  // global triangle index + 1
  };
  const std::vector<LeafTriangle>& leafTriangles(Stats& stats) const;
  // One triangle's entry, by its global index.
  LeafTriangle leafTriangle(std::uint32_t triangle) const {
    const Triangle& corners = triangles_[triangle];
    return {positions_[corners[0]], positions_[corners[1]], positions_[corners[2]], triangle + 1};
  }

  // triangleBvh() with eight children to a node (renderer/rays/wide_bvh.hpp), for the fast
  // paths' traversals; its leaves are the same slots. Built on first use (phase "wide
  // bvh build", counter "wide bvh nodes built").
  const WideBvh& wideTriangleBvh(Stats& stats, int threads = 1) const;

  // A BVH over the instances' boxes (primitive i = instances()[i]) for culling whole
  // objects hierarchically, built on first use (phase "object bvh build", counter
  // "object bvh nodes built").
  const Bvh& objectBvh(Stats& stats) const;

  // Edge and vertex adjacency for the line algorithms, built on first use (phase
  // "edge adjacency", counter "mesh edges built").
  const EdgeAdjacency& edgeAdjacency(Stats& stats) const;

  // Per vertex, the first vertex at exactly the same position: vertices of different
  // meshes at one place (solids touching at a corner or along an edge) are one point.
  // Built on first use (phase "distinct points").
  const std::vector<std::uint32_t>& distinctPoints(Stats& stats) const;

  // Data that code above this folder derives from the scene alone, the same for every
  // view (where the surfaces pass through one another: renderer/scene/intersections.hpp),
  // built by `build` the first time any thread asks and kept with the scene: one of each
  // type. The scene knows nothing of what it keeps.
  template <typename Data, typename Build>
  const Data& derived(Build&& build) const {
    DerivedSlot& slot = derivedSlot(std::type_index(typeid(Data)));
    std::call_once(slot.built, [&] { slot.data = std::make_shared<const Data>(build()); });
    return *static_cast<const Data*>(slot.data.get());
  }

 private:
  const Scene* scene_;
  int width_, height_;
  std::vector<dvec3> positions_;
  std::vector<Triangle> triangles_;
  std::vector<Instance> instances_;
  mutable std::once_flag aroundBuilt_;
  mutable VertexTriangles trianglesAroundVertices_;
  // faceGeometry's memo, made with trianglesAroundVertices_: per triangle, whether its
  // entry is absent, being written by the one thread that claimed it, or written.
  enum FaceState : std::uint8_t { kFaceAbsent, kFaceBeingWritten, kFaceWritten };
  mutable std::unique_ptr<std::atomic<std::uint8_t>[]> faceStates_;
  mutable std::unique_ptr<FaceGeometry[]> faceGeometries_;
  mutable std::once_flag bvhBuilt_;
  mutable Bvh triangleBvh_;
  mutable std::vector<LeafTriangle> leafTriangles_;
  mutable std::once_flag wideBvhBuilt_;
  mutable WideBvh wideTriangleBvh_;
  mutable std::once_flag objectBvhBuilt_;
  mutable Bvh objectBvh_;
  mutable std::once_flag adjacencyBuilt_;
  mutable EdgeAdjacency edgeAdjacency_;
  mutable std::once_flag pointsBuilt_;
  mutable std::vector<std::uint32_t> distinctPoints_;
  struct DerivedSlot {
    std::once_flag built;
    std::shared_ptr<const void> data;
  };
  DerivedSlot& derivedSlot(std::type_index type) const;  // made on first ask; never moves
  mutable std::mutex derivedMutex_;
  mutable std::map<std::type_index, std::unique_ptr<DerivedSlot>> derived_;
};

}  // namespace hsr
