// The BSP tree of Fuchs, Kedem and Naylor (1980): the painter's order for every eye at
// once. Each node holds a plane (a triangle's) and the fragments lying in it; its two
// subtrees hold what lies on either side, with every fragment that straddles the plane
// split in two. Seen from any eye, everything on the eye's side of a plane may hide the
// plane's fragments and whatever lies beyond, never the reverse; so drawing the far
// subtree, then the node, then the near subtree is back to front.
//
// The tree is built once per scene in world space (the expensive part, and the only
// one that splits); each view only walks it (cheap).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "algorithms/painter/order.hpp"

namespace hsr::painter {

class BspTree {
 public:
  // Phase "bsp build"; counters "bsp nodes", "bsp depth", "bsp splits", "bsp fragments",
  // "bsp classifications".
  BspTree(const PreparedScene& scene, const Knobs& knobs, Stats& stats);

  // The fragments back to front as the geometry's camera sees them, as pieces of the
  // geometry's screen triangles. The scene must hold the triangles the tree was built
  // from (any camera). Phase "bsp traversal", counter "bsp nodes visited".
  PaintOrder backToFront(const PreparedScene& scene, const ScreenGeometry& geometry, Stats& stats) const;

  // The tree's top `levels` levels as a Graphviz graph, for the steps: each node its
  // plane's triangle and how many fragments lie in it (red when some are pieces of a
  // split), each subtree edge marked far or near as the camera sees the node's plane (the
  // walk draws far, node, near), deeper subtrees summed up in one box.
  std::string diagram(const PreparedScene& scene, const CameraTransform& camera, int levels) const;

  std::size_t nodeCount() const { return nodes_.size(); }
  std::size_t fragmentCount() const { return fragments_.size(); }
  int depth() const { return depth_; }

 private:
  static constexpr std::uint32_t kNoPlane = ~0u;  // a node of zero-area triangles only
  struct Fragment {
    std::uint32_t triangle, firstCut, cutCount;
  };
  struct Node {
    std::uint32_t plane = kNoPlane;  // the global triangle whose plane this is
    std::uint32_t firstFragment = 0, fragmentCount = 0;
    std::int32_t positive = -1, negative = -1;  // subtrees (-1: empty) on each side of the plane
  };
  // A node's two subtrees as the camera sees its plane (-1: empty): the walk paints the
  // far one, the node, then the near one.
  struct Sides {
    std::int32_t far, near;
  };
  static Sides sidesSeenFrom(const PreparedScene& scene, const CameraTransform& camera, const Node& node, ExactPredicates& predicates);

  std::vector<Node> nodes_;  // nodes_[0] is the root
  std::vector<Fragment> fragments_;
  std::vector<Cut> cuts_;
  int depth_ = 0;
};

}  // namespace hsr::painter
