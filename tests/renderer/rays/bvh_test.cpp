// The BVH's structural promises: every primitive in exactly one leaf, every node's
// float box containing everything below it, and a bounded depth on any input.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "renderer/rays/bvh.hpp"
#include "renderer/rays/wide_bvh.hpp"

namespace hsr {
namespace {

bool contains(const BvhNode& node, const Aabb& box) {
  for (int axis = 0; axis < 3; ++axis)
    if (double(node.bounds[0][axis]) > box.lo[axis] || double(node.bounds[1][axis]) < box.hi[axis]) return false;
  return true;
}

// Checks the subtree under `index` and returns the union of its primitives' boxes.
Aabb checkSubtree(const Bvh& bvh, std::span<const Aabb> boxes, std::uint32_t index, std::vector<int>& seen) {
  const BvhNode& node = bvh.nodes()[index];
  Aabb below;
  if (node.leaf()) {
    EXPECT_LE(node.count, Bvh::kMaxLeafSize);
    for (std::uint32_t slot = node.index; slot < node.index + node.count; ++slot) {
      const std::uint32_t primitive = bvh.order()[slot];
      ++seen[primitive];
      below.grow(boxes[primitive]);
    }
  } else {
    below.grow(checkSubtree(bvh, boxes, node.index, seen));
    below.grow(checkSubtree(bvh, boxes, node.index + 1, seen));
  }
  EXPECT_TRUE(contains(node, below)) << "node " << index;
  return below;
}

std::vector<Aabb> randomTriangleBoxes(std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> position(-100, 100), size(0, 3);
  std::vector<Aabb> boxes(count);
  for (Aabb& box : boxes)
    for (int corner = 0; corner < 3; ++corner) box.grow(dvec3(position(random), position(random), position(random)) * 0.01 + size(random));
  return boxes;
}

TEST(Bvh, EveryPrimitiveInOneLeafAndEveryBoxContainsItsChildren) {
  for (const std::size_t count : {1u, 2u, 9u, 1000u, 20000u}) {
    const std::vector<Aabb> boxes = randomTriangleBoxes(count, 7);
    const Bvh bvh(boxes);
    std::vector<int> seen(count, 0);
    checkSubtree(bvh, boxes, 0, seen);
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(count));
    EXPECT_LE(bvh.depth(), Bvh::kMaxDepth);
  }
}

// The parallel build makes the tree the one-thread build makes, node for node and in
// the same places: large random inputs (the top decided in parallel, then subtrees),
// many identical boxes (split by count, a sort, at the top), and inputs too small to
// share (the root is the only subtree).
TEST(Bvh, EveryThreadCountBuildsTheSameNodesInTheSamePlaces) {
  std::vector<std::vector<Aabb>> inputs = {randomTriangleBoxes(200000, 11), randomTriangleBoxes(30000, 12),
                                           std::vector<Aabb>(50000, Aabb{dvec3(0), dvec3(1)}), randomTriangleBoxes(500, 13)};
  for (const std::vector<Aabb>& boxes : inputs) {
    const Bvh one(boxes, 1);
    for (const int threads : {2, 3, 4, 7}) {
      const Bvh many(boxes, threads);
      ASSERT_EQ(many.nodes().size(), one.nodes().size()) << boxes.size() << " boxes, " << threads << " threads";
      EXPECT_EQ(std::memcmp(many.nodes().data(), one.nodes().data(), one.nodes().size() * sizeof(BvhNode)), 0)
          << boxes.size() << " boxes, " << threads << " threads";
      EXPECT_EQ(many.order(), one.order());
      EXPECT_EQ(many.depth(), one.depth());
    }
  }
}

TEST(Bvh, DepthStaysBoundedWhenTheSahWouldPeelOnePrimitiveAtATime) {
  // Centroids spaced geometrically: each binned split can only cut off the largest few.
  std::vector<Aabb> boxes(3000);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const double x = std::pow(2.0, double(i) / 16);
    boxes[i].grow(dvec3(x, 0, 0));
    boxes[i].grow(dvec3(x * 1.001, 1, 1));
  }
  const Bvh bvh(boxes);
  std::vector<int> seen(boxes.size(), 0);
  checkSubtree(bvh, boxes, 0, seen);
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(boxes.size()));
  EXPECT_LE(bvh.depth(), Bvh::kMaxDepth);
  EXPECT_GT(bvh.depth(), 12);  // the input really is adversarial: a balanced tree would be ~9 deep
}

TEST(Bvh, IdenticalBoxesAreSplitByCount) {
  const std::vector<Aabb> boxes(100, Aabb{dvec3(0), dvec3(1)});
  const Bvh bvh(boxes);
  std::vector<int> seen(boxes.size(), 0);
  checkSubtree(bvh, boxes, 0, seen);
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), 100);
}

// Centroids a subnormal distance apart: kBins over that extent is infinite, and a bin
// computed as 0 * infinity would be NaN (undefined when made an int: the render fuzz
// target found it; the sanitizer run of this test fails without the guard).
TEST(Bvh, CentroidsASubnormalDistanceApartAreSplitByCount) {
  std::vector<Aabb> boxes;
  for (int i = 0; i < 40; ++i) boxes.push_back(Aabb{dvec3(i % 2 ? 1e-310 : 0, 0, 0), dvec3(i % 2 ? 1e-310 : 0, 1, 1)});
  const Bvh bvh(boxes);
  std::vector<int> seen(boxes.size(), 0);
  checkSubtree(bvh, boxes, 0, seen);
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), 40);
}

TEST(Bvh, BoxTestNeverMissesABoxTheRayMeets) {
  // Rays aimed at random points inside random boxes, including axis-parallel rays
  // (zero direction components): the conservative slab test must report every one.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0, 1), position(-10, 10);
  for (int trial = 0; trial < 20000; ++trial) {
    Aabb box;
    box.grow(dvec3(position(random), position(random), position(random)));
    box.grow(box.lo + dvec3(unit(random), unit(random), unit(random)) * (trial % 3 == 0 ? 0.0 : 2.0));
    BvhNode node{};
    for (int axis = 0; axis < 3; ++axis) node.bounds[0][axis] = float(box.lo[axis]), node.bounds[1][axis] = float(box.hi[axis]);
    // Keep the float box inside the double one: then a hit on the float box is certain.
    const Aabb floatBox = node.box();
    const dvec3 target = floatBox.lo + (floatBox.hi - floatBox.lo) * dvec3(unit(random), unit(random), unit(random));
    dvec3 origin(position(random) * 3, position(random) * 3, position(random) * 3);
    if (trial % 2) origin[trial % 3] = target[trial % 3];  // an axis-parallel ray
    const RayBoxTest test(origin, target - origin);
    EXPECT_LE(test.entry(node, 1.0), 1.0) << "trial " << trial;
  }
}

// Checks the wide subtree under `index`: every child's box contains its primitives, and
// counts each primitive's leaves.
void checkWideSubtree(const WideBvh& wide, const Bvh& binary, std::span<const Aabb> boxes, std::uint32_t index, std::vector<int>& seen) {
  const WideBvhNode& node = wide.nodes()[index];
  ASSERT_GE(node.children, 1);
  ASSERT_LE(node.children, WideBvhNode::kWidth);
  for (int child = 0; child < WideBvhNode::kWidth; ++child) {
    if (child >= node.children) {  // absent: a box no ray meets
      for (int axis = 0; axis < 3; ++axis) {
        EXPECT_EQ(node.low[axis][child], std::numeric_limits<float>::infinity());
        EXPECT_EQ(node.high[axis][child], -std::numeric_limits<float>::infinity());
      }
      continue;
    }
    Aabb below;
    std::vector<int> under(seen.size(), 0);
    if (node.leaf(child)) {
      EXPECT_LE(node.count[child], Bvh::kMaxLeafSize);
      for (std::uint32_t slot = node.index[child]; slot < node.index[child] + node.count[child]; ++slot) ++under[binary.order()[slot]];
    } else {
      checkWideSubtree(wide, binary, boxes, node.index[child], under);
    }
    for (std::size_t primitive = 0; primitive < under.size(); ++primitive)
      if (under[primitive] != 0) below.grow(boxes[primitive]), seen[primitive] += under[primitive];
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_LE(double(node.low[axis][child]), below.lo[axis]) << "node " << index << " child " << child;
      EXPECT_GE(double(node.high[axis][child]), below.hi[axis]) << "node " << index << " child " << child;
    }
  }
}

TEST(WideBvh, EveryPrimitiveInOneLeafAndEveryBoxContainsItsChildren) {
  for (const std::size_t count : {1u, 2u, 9u, 1000u, 20000u}) {
    const std::vector<Aabb> boxes = randomTriangleBoxes(count, 7);
    const Bvh binary(boxes);
    const WideBvh wide(binary);
    std::vector<int> seen(count, 0);
    checkWideSubtree(wide, binary, boxes, 0, seen);
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(count)) << count << " primitives";
    // Collapsing keeps the binary tree's leaves and needs at most one wide node per
    // binary inner node, usually far fewer.
    if (count > 100) {
      EXPECT_LT(wide.nodes().size(), binary.nodes().size() / 4) << count << " primitives";
    }
  }
}

// The collapse fills the subtrees below its top levels side by side, each numbered from
// the sizes known in advance: every thread count gives the one-thread nodes, byte for
// byte, numbered depth first (a node's inner children next to each other, after it).
TEST(WideBvh, EveryThreadCountCollapsesToTheSameNodesInTheSamePlaces) {
  for (const std::size_t count : {1u, 9u, 1000u, 60000u}) {
    const std::vector<Aabb> boxes = randomTriangleBoxes(count, 11);
    const Bvh binary(boxes);
    const WideBvh one(binary, 1);
    for (std::size_t index = 0; index < one.nodes().size(); ++index) {
      const WideBvhNode& node = one.nodes()[index];
      std::uint32_t expected = 0;
      for (int child = 0; child < node.children; ++child) {
        if (node.leaf(child)) continue;
        if (expected != 0) {
          EXPECT_EQ(node.index[child], expected) << "node " << index << ": its inner children side by side";
        }
        EXPECT_GT(node.index[child], index) << "node " << index;
        expected = node.index[child] + 1;
      }
    }
    for (const int threads : {2, 3, 4, 7}) {
      const WideBvh many(binary, threads);
      ASSERT_EQ(many.nodes().size(), one.nodes().size()) << count << " primitives, " << threads << " threads";
      for (std::size_t index = 0; index < one.nodes().size(); ++index) {
        const WideBvhNode &a = one.nodes()[index], &b = many.nodes()[index];  // field by field: the padding is no one's
        ASSERT_TRUE(std::memcmp(a.low, b.low, sizeof a.low) == 0 && std::memcmp(a.high, b.high, sizeof a.high) == 0 &&
                    std::memcmp(a.index, b.index, sizeof a.index) == 0 && std::memcmp(a.count, b.count, sizeof a.count) == 0 &&
                    a.children == b.children)
            << count << " primitives, " << threads << " threads: node " << index;
      }
    }
  }
}

TEST(WideBvh, ChildBoxTestsGiveTheBinaryBoxTestsEntries) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: the wide box test is never run here";
  const std::vector<Aabb> boxes = randomTriangleBoxes(3000, 5);
  const Bvh binary(boxes);
  const WideBvh wide(binary);
  std::mt19937 random(9);
  std::uniform_real_distribution<double> position(-3, 3);
  for (int trial = 0; trial < 2000; ++trial) {
    dvec3 origin(position(random), position(random), position(random)), direction(position(random), position(random), position(random));
    if (trial % 4 == 0) direction[trial % 3] = 0;  // parallel to one axis's slabs
    const RayBoxTest ray(origin, direction);
    const WideRayBoxTest children(ray);
    const double tMax = trial % 2 ? 1e30 : 0.5;
    for (const WideBvhNode& node : wide.nodes()) {
      double entries[WideBvhNode::kWidth];
      const int met = children.entries(node, tMax, entries);
      for (int child = 0; child < node.children; ++child) {
        BvhNode single{};
        for (int axis = 0; axis < 3; ++axis) single.bounds[0][axis] = node.low[axis][child], single.bounds[1][axis] = node.high[axis][child];
        const double expected = ray.entry(single, tMax);
        ASSERT_EQ(bool(met >> child & 1), expected < std::numeric_limits<double>::infinity()) << "trial " << trial;
        if (met >> child & 1) {
          ASSERT_EQ(entries[child], expected) << "trial " << trial;
        }
      }
      EXPECT_EQ(met >> node.children, 0);
    }
  }
}

}  // namespace
}  // namespace hsr
