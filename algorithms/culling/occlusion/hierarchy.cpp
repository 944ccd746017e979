// The object hierarchies of the query methods (hierarchy.hpp).
#include "algorithms/culling/occlusion/hierarchy.hpp"

#include <algorithm>
#include <numeric>

namespace hsr::culling::occlusion {

ObjectHierarchy::ObjectHierarchy(const PreparedScene& scene, HierarchyKind kind, Stats& stats) : kind_(kind) {
  if (kind == HierarchyKind::bvh)
    fromBvh(scene.objectBvh(stats));
  else
    buildKd(scene);
  stats.add("queries: hierarchy nodes built", static_cast<std::int64_t>(nodes_.size()));
}

void ObjectHierarchy::fromBvh(const Bvh& bvh) {
  if (bvh.empty()) return;
  nodes_.resize(bvh.nodes().size());
  objects_ = bvh.order();
  for (std::size_t i = 0; i < bvh.nodes().size(); ++i) {
    const BvhNode& from = bvh.nodes()[i];
    HierarchyNode& node = nodes_[i];
    node.box = from.box();
    if (from.leaf()) {
      node.firstObject = from.index, node.objectCount = from.count;
      continue;
    }
    node.firstChild = from.index, node.childCount = 2;
    nodes_[from.index].parent = nodes_[from.index + 1].parent = std::int32_t(i);
  }
}

void ObjectHierarchy::buildKd(const PreparedScene& scene) {
  const std::vector<Instance>& instances = scene.instances();
  if (instances.empty()) return;
  struct Cell {
    std::uint32_t node;
    Aabb region;
    std::vector<std::uint32_t> objects;
    int depth;
  };
  std::vector<std::uint32_t> all(instances.size());
  std::iota(all.begin(), all.end(), 0u);
  Aabb bounds;
  for (const Instance& instance : instances) bounds.grow(instance.box);
  nodes_.emplace_back();
  std::vector<Cell> pending = {{0, bounds, std::move(all), 0}};
  while (!pending.empty()) {
    Cell cell = std::move(pending.back());
    pending.pop_back();
    // The node's box: its cell, cut down to the boxes of what it lists.
    Aabb contents;
    for (const std::uint32_t object : cell.objects) contents.grow(instances[object].box);
    HierarchyNode& node = nodes_[cell.node];
    node.box.lo = glm::max(contents.lo, cell.region.lo);
    node.box.hi = glm::min(contents.hi, cell.region.hi);
    const auto makeLeaf = [&] {
      node.firstObject = static_cast<std::uint32_t>(objects_.size());
      node.objectCount = static_cast<std::uint32_t>(cell.objects.size());
      objects_.insert(objects_.end(), cell.objects.begin(), cell.objects.end());
    };
    if (cell.objects.size() <= kLeafObjects || cell.depth >= kMaxKdDepth) {
      makeLeaf();
      continue;
    }
    // Halve the cell across its longest side. An object touching the split plane goes
    // to the side it reaches into (both when it lies in the plane or crosses it).
    const dvec3 size = cell.region.hi - cell.region.lo;
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
    const double split = 0.5 * (cell.region.lo[axis] + cell.region.hi[axis]);
    std::vector<std::uint32_t> below, above;
    for (const std::uint32_t object : cell.objects) {
      if (instances[object].box.lo[axis] <= split) below.push_back(object);
      if (instances[object].box.hi[axis] >= split) above.push_back(object);
    }
    // A split that leaves every object on both sides divides nothing.
    if (below.size() == cell.objects.size() && above.size() == cell.objects.size()) {
      makeLeaf();
      continue;
    }
    Aabb lower = cell.region, upper = cell.region;
    lower.hi[axis] = split, upper.lo[axis] = split;
    // Everything on one side: the same node again, over the half that holds it (an
    // empty cell would be a node that can never be seen).
    if (below.empty() || above.empty()) {
      pending.push_back({cell.node, below.empty() ? upper : lower, std::move(cell.objects), cell.depth + 1});
      continue;
    }
    const auto first = static_cast<std::uint32_t>(nodes_.size());
    node.firstChild = first, node.childCount = 2;
    nodes_.resize(nodes_.size() + 2);  // `node` may dangle from here on
    nodes_[first].parent = nodes_[first + 1].parent = std::int32_t(cell.node);
    pending.push_back({first + 1, upper, std::move(above), cell.depth + 1});
    pending.push_back({first, lower, std::move(below), cell.depth + 1});
  }
}

}  // namespace hsr::culling::occlusion
