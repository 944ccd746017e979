// The spatial hierarchy over the objects that the query methods walk (queries.hpp):
// a query of a node's box answers for everything below it, so one hidden node culls a
// whole part of the scene with one query.
//
//   bvh  the scene's object BVH (renderer/rays/bvh.hpp: the surface area heuristic over the
//        objects' boxes): each object in exactly one leaf, boxes that may overlap.
//   kd   a k-d tree: each cell split in half across its longest side until it holds at
//        most kLeafObjects objects; an object reaching across a split is listed in
//        every cell it reaches. A node's box is its cell cut down to the boxes of the
//        objects listed in it (what lies in the cell can be no larger), so the boxes of
//        siblings never overlap.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/rays/bvh.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::culling::occlusion {

enum class HierarchyKind { bvh, kd };

struct HierarchyNode {
  Aabb box;
  std::int32_t parent = -1;                        // -1: the root
  std::uint32_t firstChild = 0, childCount = 0;    // children are consecutive nodes
  std::uint32_t firstObject = 0, objectCount = 0;  // a leaf's objects: objects()[first, first + count)
  bool leaf() const { return childCount == 0; }
};

class ObjectHierarchy {
 public:
  static constexpr std::uint32_t kLeafObjects = 4;  // the k-d tree's leaf size
  static constexpr int kMaxKdDepth = 24;

  // Counts "queries: hierarchy nodes built".
  ObjectHierarchy(const PreparedScene& scene, HierarchyKind kind, Stats& stats);

  HierarchyKind kind() const { return kind_; }
  const std::vector<HierarchyNode>& nodes() const { return nodes_; }  // nodes()[0] is the root (none: no objects)
  // The objects (instance indices) leaf by leaf; an object may be listed by several k-d leaves.
  const std::vector<std::uint32_t>& objects() const { return objects_; }

 private:
  void fromBvh(const Bvh& bvh);
  void buildKd(const PreparedScene& scene);

  HierarchyKind kind_;
  std::vector<HierarchyNode> nodes_;
  std::vector<std::uint32_t> objects_;
};

}  // namespace hsr::culling::occlusion
