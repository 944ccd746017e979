#include "renderer/rays/wide_bvh.hpp"

#include <algorithm>
#include <limits>

namespace hsr {
namespace {

// Half the surface area of a binary node's float box: which child to open first.
double halfArea(const BvhNode& node) {
  const double x = double(node.bounds[1][0]) - node.bounds[0][0], y = double(node.bounds[1][1]) - node.bounds[0][1],
               z = double(node.bounds[1][2]) - node.bounds[0][2];
  return x * y + y * z + z * x;
}

}  // namespace

WideBvh::WideBvh(const Bvh& binary) {
  if (binary.empty()) return;
  nodes_.reserve(binary.nodes().size() / 2 + 1);
  nodes_.emplace_back();
  collapse(0, binary, 0);
}

// Fills wide node `wide` with the binary subtree under `node`: start from its children
// (or itself, a leaf root), and open the inner child of largest area, replacing it by
// its two children, until there are four or only leaves are left. The largest box is
// the one a ray is likeliest to meet, so its children are worth testing side by side.
void WideBvh::collapse(std::uint32_t wide, const Bvh& binary, std::uint32_t node) {
  const std::vector<BvhNode>& tree = binary.nodes();
  std::vector<std::uint32_t> children;
  if (tree[node].leaf()) children = {node};
  else children = {tree[node].index, tree[node].index + 1};
  while (children.size() < WideBvhNode::kWidth) {
    auto largest = children.end();
    for (auto child = children.begin(); child != children.end(); ++child)
      if (!tree[*child].leaf() && (largest == children.end() || halfArea(tree[*child]) > halfArea(tree[*largest]))) largest = child;
    if (largest == children.end()) break;
    const std::uint32_t opened = *largest;
    *largest = tree[opened].index;
    children.insert(largest + 1, tree[opened].index + 1);
  }

  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  WideBvhNode filled{};
  for (int axis = 0; axis < 3; ++axis) std::fill_n(filled.low[axis], WideBvhNode::kWidth, kInfinity), std::fill_n(filled.high[axis], WideBvhNode::kWidth, -kInfinity);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> inner;  // (wide child, binary node) to fill next
  for (std::size_t slot = 0; slot < children.size(); ++slot) {
    const BvhNode& child = tree[children[slot]];
    for (int axis = 0; axis < 3; ++axis) filled.low[axis][slot] = child.bounds[0][axis], filled.high[axis][slot] = child.bounds[1][axis];
    if (child.leaf()) {
      filled.index[slot] = child.index;
      filled.count[slot] = child.count;
    } else {
      filled.index[slot] = static_cast<std::uint32_t>(nodes_.size());
      nodes_.emplace_back();
      inner.emplace_back(filled.index[slot], children[slot]);
    }
  }
  filled.children = static_cast<std::uint8_t>(children.size());
  nodes_[wide] = filled;
  for (const auto& [child, below] : inner) collapse(child, binary, below);
}

}  // namespace hsr
