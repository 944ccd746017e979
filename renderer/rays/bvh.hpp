// A bounding volume hierarchy over boxes (triangles or whole objects), built with the
// surface area heuristic over binned centroids (Wald 2007), shared by the exact
// reference, ray casting and the culling stages.
//
// Nodes are 32 bytes with float bounds rounded outward from the double boxes, so a box
// test against a node can only be more generous than the exact one: traversal may
// visit a node it did not need, never skip one it needed.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "renderer/util/math.hpp"

namespace hsr {

struct Aabb {
  dvec3 lo{std::numeric_limits<double>::infinity()};
  dvec3 hi{-std::numeric_limits<double>::infinity()};

  void grow(const dvec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  void grow(const Aabb& box) { lo = glm::min(lo, box.lo), hi = glm::max(hi, box.hi); }
  bool empty() const { return lo.x > hi.x; }
  dvec3 center() const { return (lo + hi) * 0.5; }
  // Half the surface area: the SAH only needs areas up to a common factor.
  double halfArea() const;
};

struct BvhNode {
  float bounds[2][3];    // [0]: the low corner, [1]: the high corner, rounded outward
  std::uint32_t index;   // interior: first child (the second is index + 1); leaf: first slot in order()
  std::uint16_t count;   // primitives in a leaf; 0 for an interior node
  std::uint16_t axis;    // interior: the split axis, so traversal can visit the nearer child first
  bool leaf() const { return count != 0; }
  Aabb box() const { return {dvec3(bounds[0][0], bounds[0][1], bounds[0][2]), dvec3(bounds[1][0], bounds[1][1], bounds[1][2])}; }
};

class Bvh {
 public:
  static constexpr int kBins = 16;        // centroid bins per axis for the SAH sweep
  static constexpr int kMaxLeafSize = 8;  // a larger node is always split
  // Relative costs of visiting a node and testing a primitive (the SAH's C_trav, C_isect).
  // Depth limit of SAH splitting; below it nodes are halved, so depth() <= kSahDepth + 32.
  static constexpr int kSahDepth = 48;
  static constexpr int kMaxDepth = kSahDepth + 32;
  static constexpr double kTraversalCost = 1.0, kIntersectionCost = 1.0;

  Bvh() = default;
  // boxes[i] bounds primitive i; the node order() lists primitives leaf by leaf. Built on
  // `threads` threads (0: all cores), with the same nodes and order for any count.
  explicit Bvh(std::span<const Aabb> boxes, int threads = 1);

  const std::vector<BvhNode>& nodes() const { return nodes_; }       // nodes()[0] is the root

  // Calls visit(primitive, slot in order()) for each primitive of every leaf reached through nodes that
  // all pass keep(node): a conservative query (a box, a ray, a projected rectangle).
  template <typename Keep, typename Visit>
  void visitPrimitives(Keep&& keep, Visit&& visit) const {
    if (empty()) return;
    std::vector<std::uint32_t> stack = {0};
    while (!stack.empty()) {
      const BvhNode& node = nodes_[stack.back()];
      stack.pop_back();
      if (!keep(node)) continue;
      if (!node.leaf()) {
        stack.push_back(node.index);
        stack.push_back(node.index + 1);
        continue;
      }
      for (std::uint32_t slot = node.index; slot < node.index + node.count; ++slot) visit(order_[slot], slot);
    }
  }
  // Calls visit(a, slot of a, b, slot of b) once for each unordered pair of distinct
  // primitives whose leaves are reached by pairs of nodes that all pass overlap(node,
  // node): the tree queried against itself, for the pairs of boxes that may touch.
  template <typename Overlap, typename Visit>
  void visitPairs(Overlap&& overlap, Visit&& visit) const {
    if (empty()) return;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> stack = {{0, 0}};  // disjoint subtrees, or a node and itself
    while (!stack.empty()) {
      const auto [i, j] = stack.back();
      stack.pop_back();
      const BvhNode &a = nodes_[i], &b = nodes_[j];
      if (i != j && !overlap(a, b)) continue;
      if (a.leaf() && b.leaf()) {
        for (std::uint32_t slotA = a.index; slotA < a.index + a.count; ++slotA)
          for (std::uint32_t slotB = i == j ? slotA + 1 : b.index; slotB < b.index + b.count; ++slotB)
            visit(order_[slotA], slotA, order_[slotB], slotB);
      } else if (i == j) {  // a node against itself: each child against itself, and the two against each other
        stack.push_back({a.index, a.index});
        stack.push_back({a.index + 1, a.index + 1});
        stack.push_back({a.index, a.index + 1});
      } else if (!a.leaf()) {
        stack.push_back({a.index, j});
        stack.push_back({a.index + 1, j});
      } else {
        stack.push_back({i, b.index});
        stack.push_back({i, b.index + 1});
      }
    }
  }
  const std::vector<std::uint32_t>& order() const { return order_; }  // primitive ids by leaf
  int depth() const { return depth_; }                                // root alone = 1
  bool empty() const { return order_.empty(); }

 private:
  std::vector<BvhNode> nodes_;
  std::vector<std::uint32_t> order_;
  int depth_ = 0;
};

// The slab test of a ray against node boxes, made conservative: the far distance of
// every slab is widened by 2 gamma(3) (Ize 2013, "Robust BVH ray traversal"), which
// covers the rounding of the subtraction and the multiplication.
struct RayBoxTest {
  dvec3 origin, inverseDirection;
  int nearSide[3];     // per axis, the corner (0 low, 1 high) whose slab plane the ray meets first
  bool parallel[3];    // per axis, the ray runs parallel to the slab's planes (a zero component)

  // The factor far distances are widened by: 1 + 2 gamma(3).
  static constexpr double kWiden = 1 + 2 * (3 * 0x1p-53 / (1 - 3 * 0x1p-53));

  // Along an axis the ray does not move on, it is inside the (closed) slab for every t
  // or for none: that axis is tested by the origin alone, with no division by zero.
  RayBoxTest(const dvec3& rayOrigin, const dvec3& direction) : RayBoxTest(rayOrigin, direction, inverseOf(direction)) {}
  // With the direction's inverse already computed (inverseOf, or its vector form).
  RayBoxTest(const dvec3& rayOrigin, const dvec3& direction, const dvec3& inverse) : origin(rayOrigin), inverseDirection(inverse) {
    for (int axis = 0; axis < 3; ++axis) {
      parallel[axis] = direction[axis] == 0;
      nearSide[axis] = std::signbit(direction[axis]) ? 1 : 0;
    }
  }

  // The entry parameter of the ray into the node's box when the box is met within
  // [0, tMax]; +infinity otherwise.
  double entry(const BvhNode& node, double tMax) const {
    double tEnter = 0, tExit = tMax;
    for (int axis = 0; axis < 3; ++axis) {
      if (parallel[axis]) {
        if (origin[axis] < double(node.bounds[0][axis]) || origin[axis] > double(node.bounds[1][axis]))
          return std::numeric_limits<double>::infinity();
        continue;
      }
      const double tNear = (double(node.bounds[nearSide[axis]][axis]) - origin[axis]) * inverseDirection[axis];
      const double tFar = (double(node.bounds[1 - nearSide[axis]][axis]) - origin[axis]) * inverseDirection[axis];
      tEnter = tNear > tEnter ? tNear : tEnter;
      tExit = tFar * kWiden < tExit ? tFar * kWiden : tExit;
    }
    return tEnter <= tExit ? tEnter : std::numeric_limits<double>::infinity();
  }

  // entry() for the two children of an interior node at once, one per lane of a
  // two-double vector: the same operations in the same order, so the same results.
  std::array<double, 2> childEntries(const BvhNode* children, double tMax) const {
    using Pair = double __attribute__((vector_size(16)));
    constexpr double miss = std::numeric_limits<double>::infinity();
    Pair tEnter = {0, 0}, tExit = {tMax, tMax};
    bool inside[2] = {true, true};
    for (int axis = 0; axis < 3; ++axis) {
      if (parallel[axis]) {
        for (int child = 0; child < 2; ++child)
          inside[child] = inside[child] && origin[axis] >= double(children[child].bounds[0][axis]) &&
                          origin[axis] <= double(children[child].bounds[1][axis]);
        continue;
      }
      const int near = nearSide[axis], far = 1 - near;
      const Pair nearPlane = {children[0].bounds[near][axis], children[1].bounds[near][axis]};
      const Pair farPlane = {children[0].bounds[far][axis], children[1].bounds[far][axis]};
      const Pair tNear = (nearPlane - origin[axis]) * inverseDirection[axis];
      const Pair tFar = (farPlane - origin[axis]) * inverseDirection[axis] * kWiden;
      tEnter = tNear > tEnter ? tNear : tEnter;
      tExit = tFar < tExit ? tFar : tExit;
    }
    return {inside[0] && tEnter[0] <= tExit[0] ? tEnter[0] : miss, inside[1] && tEnter[1] <= tExit[1] ? tEnter[1] : miss};
  }
};

}  // namespace hsr
