// The BVH with eight children to a node, for the fast paths' traversals (ray casting's
// and the reference's): the binary BVH (renderer/rays/bvh.hpp) collapsed, each node taking
// the largest of its descendants until it holds eight, so a ray tests eight boxes in
// two vector operations per slab and visits about a third as many nodes (Wald, Benthin
// and Boulos 2008, "Getting rid of packets"; Dammertz, Hanika and Keller 2008, "Shallow
// bounding volume hierarchies"). Eight rather than four: on this suite's scenes the
// wider node took ray casting's single rays from 0.65-0.70 of Embree's throughput to
// 0.77-0.80 (bench/embree_peer, before the rays' set-up was vectorized too).
//
// The leaves are the binary BVH's own, so slots index Bvh::order() and
// PreparedScene::leafTriangles() as before, and the boxes are the binary nodes' float
// boxes, rounded outward from the exact ones: a box test can only be more generous than
// the exact one, as with the binary tree.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/rays/bvh.hpp"
#include "renderer/util/simd.hpp"

namespace hsr {

struct alignas(64) WideBvhNode {
  static constexpr int kWidth = 8;
  // Per axis, the children's boxes side by side: low[axis][child], high[axis][child].
  // The children come first; the lanes after them hold an empty box (low +inf, high
  // -inf) that no ray meets.
  float low[3][kWidth], high[3][kWidth];
  std::uint32_t index[kWidth];  // an inner child: its node; a leaf child: its first slot in Bvh::order()
  std::uint16_t count[kWidth];  // a leaf child: its primitives; an inner child or none: 0
  std::uint8_t children;        // how many (1 to kWidth)
  bool leaf(int child) const { return count[child] != 0; }
};

class WideBvh {
 public:
  WideBvh() = default;
  // The same nodes in the same places for any thread count.
  explicit WideBvh(const Bvh& binary, int threads = 1);

  const std::vector<WideBvhNode>& nodes() const { return nodes_; }  // nodes()[0] is the root
  bool empty() const { return nodes_.empty(); }
  // At most the binary tree's depth: a traversal stack of (kWidth - 1) Bvh::kMaxDepth + 1
  // entries (all but one child pushed per level) never overflows.
  static constexpr int kStackSize = (WideBvhNode::kWidth - 1) * Bvh::kMaxDepth + 1;

 private:
  struct Subtree {  // a binary subtree below the levels filled on one thread
    std::uint32_t node;                 // its binary root
    std::uint32_t size = 0;             // how many wide nodes it becomes
    std::uint32_t wide = 0, firstBelow = 0;  // its wide root's place, and its descendants' first
  };
  static void findSubtrees(const std::vector<BvhNode>& tree, std::uint32_t node, int depth, std::uint32_t& upperNodes,
                           std::vector<Subtree>& subtrees);
  std::uint32_t fill(std::uint32_t wide, const std::vector<BvhNode>& tree, std::uint32_t node, std::uint32_t next, int depth,
                     std::vector<Subtree>& subtrees, std::size_t& nextSubtree);
  std::vector<WideBvhNode> nodes_;
};

// RayBoxTest (renderer/rays/bvh.hpp) for a wide node's children at once, a child per lane,
// four lanes to a vector: the same slab values as RayBoxTest::entry, so the same entries.
struct WideRayBoxTest {
  explicit WideRayBoxTest(const RayBoxTest& ray) : ray_(ray) {}

  // Writes each child's entry parameter into entries[child] and returns a bit per child
  // the ray meets within [0, tMax] (bit i: child i). The entries of children it misses
  // are not written.
  HSR_AVX2 int entries(const WideBvhNode& node, double tMax, double* entries) const {
    int met = 0;
    for (int first = 0; first < node.children; first += 4) {
      // Each axis's slab alone, then their intersection: the largest entry and the
      // smallest exit (exact, so the order they are taken in does not matter).
      Double4 tNear[3], tFar[3];
      Mask4 outside = {};
      for (int axis = 0; axis < 3; ++axis) {
        const float* low = node.low[axis] + first;
        const float* high = node.high[axis] + first;
        const double origin = ray_.origin[axis];
        if (ray_.parallel[axis]) {
          outside |= (origin < widened(low)) | (origin > widened(high));
          tNear[axis] = lanesOf(0), tFar[axis] = lanesOf(tMax);
          continue;
        }
        // Only the planes the ray needs are widened to doubles (widening both and choosing
        // lanes after cost 10-15% of the traversal).
        const bool highFirst = ray_.nearSide[axis] == 1;
        tNear[axis] = (widened(highFirst ? high : low) - origin) * ray_.inverseDirection[axis];
        tFar[axis] = (widened(highFirst ? low : high) - origin) * ray_.inverseDirection[axis] * RayBoxTest::kWiden;
      }
      const Double4 tEnter = larger(larger(tNear[0], tNear[1]), larger(tNear[2], lanesOf(0)));
      const Double4 tExit = smaller(smaller(tFar[0], tFar[1]), smaller(tFar[2], lanesOf(tMax)));
      __builtin_memcpy(entries + first, &tEnter, sizeof tEnter);
      met |= laneBits((tEnter <= tExit) & ~outside) << first;
    }
    return met;
  }

 private:
  const RayBoxTest& ray_;
};

}  // namespace hsr
