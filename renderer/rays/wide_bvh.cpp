#include "renderer/rays/wide_bvh.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include "renderer/util/parallel.hpp"

namespace hsr {
namespace {

// Half the surface area of a binary node's float box: which child to open first.
double halfArea(const BvhNode& node) {
  const double x = double(node.bounds[1][0]) - node.bounds[0][0], y = double(node.bounds[1][1]) - node.bounds[0][1],
               z = double(node.bounds[1][2]) - node.bounds[0][2];
  return x * y + y * z + z * x;
}

// Step 1 of filling a wide node: start from the binary node's children (or itself, a
// leaf root), and open the inner child of largest area, replacing it by its two
// children, until there are eight or only leaves are left. The largest box is the one a
// ray is likeliest to meet, so its children are worth testing side by side.
struct Opened {
  std::array<std::uint32_t, WideBvhNode::kWidth> children{};  // binary nodes, in order
  std::size_t count = 0;
};

Opened openLargest(const std::vector<BvhNode>& tree, std::uint32_t node) {
  Opened opened;
  auto& children = opened.children;
  std::size_t& count = opened.count;
  if (tree[node].leaf()) children[count++] = node;
  else children[count++] = tree[node].index, children[count++] = tree[node].index + 1;
  while (count < WideBvhNode::kWidth) {
    std::size_t largest = count;
    for (std::size_t child = 0; child < count; ++child)
      if (!tree[children[child]].leaf() && (largest == count || halfArea(tree[children[child]]) > halfArea(tree[children[largest]])))
        largest = child;
    if (largest == count) break;
    const std::uint32_t split = children[largest];
    std::copy_backward(children.begin() + std::ptrdiff_t(largest) + 1, children.begin() + std::ptrdiff_t(count),
                       children.begin() + std::ptrdiff_t(count) + 1);
    children[largest] = tree[split].index, children[largest + 1] = tree[split].index + 1;
    ++count;
  }
  return opened;
}

// How many wide nodes the binary subtree under `node` becomes.
std::uint32_t wideNodesUnder(const std::vector<BvhNode>& tree, std::uint32_t node) {
  const Opened opened = openLargest(tree, node);
  std::uint32_t count = 1;
  for (std::size_t slot = 0; slot < opened.count; ++slot)
    if (!tree[opened.children[slot]].leaf()) count += wideNodesUnder(tree, opened.children[slot]);
  return count;
}

// Wide levels above this depth are filled on one thread; the subtrees below, up to
// 8^3 of them, side by side.
constexpr int kSharedDepth = 3;

}  // namespace

// The one-thread collapse fills a node, numbers its inner children next, and then fills
// each child's subtree in turn. With each subtree's size known in advance, a subtree's
// numbers are known before the subtrees before it are filled, so the subtrees below
// kSharedDepth are filled side by side and every node lands where one thread puts it.
WideBvh::WideBvh(const Bvh& binary, int threads) {
  if (binary.empty()) return;
  const std::vector<BvhNode>& tree = binary.nodes();
  // The subtrees at kSharedDepth in the order the collapse reaches them, and their sizes.
  std::vector<Subtree> subtrees;
  std::uint32_t upperNodes = 0;
  findSubtrees(tree, 0, 0, upperNodes, subtrees);
  parallelFor(subtrees.size(), threads, [&](std::size_t k, int) { subtrees[k].size = wideNodesUnder(tree, subtrees[k].node); });
  std::uint32_t total = upperNodes;
  for (const Subtree& subtree : subtrees) total += subtree.size;
  nodes_.resize(total);
  std::size_t nextSubtree = 0;
  fill(0, tree, 0, 1, 0, subtrees, nextSubtree);
  parallelFor(subtrees.size(), threads, [&](std::size_t k, int) {
    std::size_t none = 0;
    fill(subtrees[k].wide, tree, subtrees[k].node, subtrees[k].firstBelow, -1, subtrees, none);
  });
}

void WideBvh::findSubtrees(const std::vector<BvhNode>& tree, std::uint32_t node, int depth, std::uint32_t& upperNodes,
                           std::vector<Subtree>& subtrees) {
  if (depth == kSharedDepth) {
    subtrees.push_back({node});
    return;
  }
  ++upperNodes;
  const Opened opened = openLargest(tree, node);
  for (std::size_t slot = 0; slot < opened.count; ++slot)
    if (!tree[opened.children[slot]].leaf()) findSubtrees(tree, opened.children[slot], depth + 1, upperNodes, subtrees);
}

// Fills wide node `wide` with the binary subtree under `node`, numbering its descendants
// from `next` on, and returns the number after them. `depth` counts wide levels from the
// root (-1: inside a subtree below kSharedDepth); at kSharedDepth a subtree is not filled
// but its place is written into the next of `subtrees`.
std::uint32_t WideBvh::fill(std::uint32_t wide, const std::vector<BvhNode>& tree, std::uint32_t node, std::uint32_t next,
                            int depth, std::vector<Subtree>& subtrees, std::size_t& nextSubtree) {
  if (depth == kSharedDepth) {
    Subtree& subtree = subtrees[nextSubtree++];
    subtree.wide = wide, subtree.firstBelow = next;
    return next + subtree.size - 1;
  }
  const Opened opened = openLargest(tree, node);
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  WideBvhNode filled{};
  for (int axis = 0; axis < 3; ++axis) std::fill_n(filled.low[axis], WideBvhNode::kWidth, kInfinity), std::fill_n(filled.high[axis], WideBvhNode::kWidth, -kInfinity);
  std::array<std::uint32_t, WideBvhNode::kWidth> inner;  // the binary nodes of the inner children, numbered from `next`
  std::size_t innerCount = 0;
  for (std::size_t slot = 0; slot < opened.count; ++slot) {
    const BvhNode& child = tree[opened.children[slot]];
    for (int axis = 0; axis < 3; ++axis) filled.low[axis][slot] = child.bounds[0][axis], filled.high[axis][slot] = child.bounds[1][axis];
    if (child.leaf()) {
      filled.index[slot] = child.index;
      filled.count[slot] = child.count;
    } else {
      filled.index[slot] = next + std::uint32_t(innerCount);
      inner[innerCount++] = opened.children[slot];
    }
  }
  filled.children = static_cast<std::uint8_t>(opened.count);
  nodes_[wide] = filled;
  std::uint32_t free = next + std::uint32_t(innerCount);
  for (std::size_t k = 0; k < innerCount; ++k)
    free = fill(next + std::uint32_t(k), tree, inner[k], free, depth < 0 ? -1 : depth + 1, subtrees, nextSubtree);
  return free;
}

}  // namespace hsr
