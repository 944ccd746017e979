// Building and walking the BSP tree (bsp.hpp).
//
// Build, for a list of polygons (at first the scene's triangles):
//   1. choose a splitting plane among the list's triangles (knob `splitter`);
//   2. put each polygon in the plane's node (coplanar), the positive list, the negative
//      list, or, when it straddles the plane, split it and put one piece in each;
//   3. build each non-empty list into a subtree the same way.
// An explicit stack replaces recursion: a poor splitter on a large scene makes a tree
// as deep as the scene has triangles.
//
// The side tests are exact (renderer/geometry/predicates). The one tolerance: a polygon whose
// every vertex lies on the plane within a few times the rounding of the placements
// (RoundedPlane::holds, renderer/geometry/rounding.hpp: relative to the coordinates' magnitude)
// is coplanar with it, because faces coplanar in the model are coplanar only up to that
// rounding, and splitting them by rounding noise would cost slivers. Far from the origin
// the bound grows with the coordinates (at 1e5 it is about 1e-10), so planes half a
// micrometre apart there stay apart.
#include "algorithms/painter/bsp.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "renderer/util/error.hpp"

namespace hsr::painter {
namespace {

constexpr std::size_t kSplitSample = 256;  // least-splits: polygons a candidate plane is tried on

struct BuildPolygon {
  std::uint32_t triangle;
  std::vector<dvec3> vertices;
  std::vector<Cut> cuts;
  double rounding;  // its instance's placementRounding
};

enum class Side { positive, negative, straddles, coplanar };

// splitmix64: the same choices on every platform.
struct Random {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
};

class Builder {
 public:
  Builder(const PreparedScene& scene, const Knobs& knobs) : scene_(scene), knobs_(knobs), random_{knobs.seed} {}

  const dvec3& corner(std::uint32_t triangle, int k) const { return scene_.positions()[scene_.triangles()[triangle][k]]; }

  // A triangle whose corners are exactly collinear has no plane to split by.
  bool hasPlane(std::uint32_t triangle) {
    const dvec3 &a = corner(triangle, 0), &b = corner(triangle, 1), &c = corner(triangle, 2);
    const auto xz = [](const dvec3& p) { return dvec3(p.x, p.z, 0); };
    const auto yz = [](const dvec3& p) { return dvec3(p.y, p.z, 0); };
    return predicates.orient2d(a, b, c) != 0 || predicates.orient2d(xz(a), xz(b), xz(c)) != 0 ||
           predicates.orient2d(yz(a), yz(b), yz(c)) != 0;
  }

  // A triangle's plane, with what its tests need computed once.
  struct SplittingPlane {
    std::uint32_t triangle;
    dvec3 a, b, c;         // its corners
    RoundedPlane rounded;  // for the coplanar test
  };
  SplittingPlane splittingPlane(std::uint32_t triangle) const {
    return {triangle, corner(triangle, 0), corner(triangle, 1), corner(triangle, 2), scene_.planeUpToPlacement(triangle)};
  }

  // Step 2's test: the exact side of each vertex, from the exact height (its sign, and
  // its value accurate to a few ulps for placing a split); a polygon whose every vertex
  // lies on the plane up to the placements' rounding counts as coplanar. Fills sides and
  // heights for a split.
  Side classify(const BuildPolygon& polygon, const SplittingPlane& plane, std::vector<int>* sides = nullptr,
                std::vector<double>* heights = nullptr) {
    ++classifications;
    if (polygon.triangle == plane.triangle) return Side::coplanar;
    bool anyPositive = false, anyNegative = false, onThePlane = true;
    for (const dvec3& v : polygon.vertices) {
      const double height = predicates.orient3dValue(plane.a, plane.b, plane.c, v);
      anyPositive |= height > 0;
      anyNegative |= height < 0;
      onThePlane &= plane.rounded.holdsHeight(height, polygon.rounding);
      if (sides) sides->push_back(height > 0 ? 1 : height < 0 ? -1 : 0);
      if (heights) heights->push_back(height);
    }
    if (onThePlane) return Side::coplanar;
    if (anyPositive && anyNegative) return Side::straddles;
    return anyPositive ? Side::positive : Side::negative;
  }

  // Step 1: the splitting plane for a list (an index into it), or none when no triangle
  // in it has a plane.
  std::optional<std::size_t> chooseSplitter(const std::vector<std::uint32_t>& list) {
    std::vector<std::size_t> candidates;
    const std::size_t wanted = knobs_.splitter == Splitter::leastSplits ? std::size_t(knobs_.candidates) : 1;
    for (std::size_t attempt = 0; attempt < list.size() && candidates.size() < wanted; ++attempt) {
      // first: the list's first triangle with a plane; random, least-splits: random ones.
      const std::size_t at = knobs_.splitter == Splitter::first ? attempt : std::size_t(random_.next() % list.size());
      if (hasPlane(polygons[list[at]].triangle)) candidates.push_back(at);
    }
    if (candidates.empty()) {
      for (std::size_t at = 0; at < list.size(); ++at)
        if (hasPlane(polygons[list[at]].triangle)) return at;
      return std::nullopt;
    }
    if (candidates.size() == 1) return candidates.front();
    // least-splits: the candidate whose plane straddles the fewest polygons of the list,
    // counted over at most kSplitSample of them, evenly spaced (near the root, counting
    // the whole list for every candidate would cost candidates x triangles per node).
    const std::size_t stride = (list.size() + kSplitSample - 1) / kSplitSample;
    std::size_t best = candidates.front(), fewest = list.size() + 1;
    for (const std::size_t candidate : candidates) {
      const SplittingPlane plane = splittingPlane(polygons[list[candidate]].triangle);
      std::size_t straddling = 0;
      for (std::size_t i = 0; i < list.size() && straddling < fewest; i += stride)
        straddling += classify(polygons[list[i]], plane) == Side::straddles;
      if (straddling < fewest) best = candidate, fewest = straddling;
    }
    return best;
  }

  std::vector<BuildPolygon> polygons;
  ExactPredicates predicates;
  std::int64_t classifications = 0, splits = 0;

 private:
  const PreparedScene& scene_;
  const Knobs& knobs_;
  Random random_;
};

}  // namespace

BspTree::BspTree(const PreparedScene& scene, const Knobs& knobs, Stats& stats) {
  PhaseTimer timer(stats, "bsp build");
  Builder builder(scene, knobs);
  std::vector<std::uint32_t> all;
  for (std::uint32_t t = 0; t < scene.triangleCount(); ++t) {
    const auto& corners = scene.triangles()[t];
    builder.polygons.push_back({t,
                                {scene.positions()[corners[0]], scene.positions()[corners[1]], scene.positions()[corners[2]]},
                                {},
                                scene.instanceOf(t).placementRounding});
    all.push_back(t);
  }
  struct Task {
    std::vector<std::uint32_t> list;
    std::int32_t parent;  // -1: the root
    bool positiveSide;    // which of the parent's subtrees this is
    int depth;
  };
  std::vector<Task> stack;
  if (!all.empty()) stack.push_back({std::move(all), -1, false, 1});
  while (!stack.empty()) {
    Task task = std::move(stack.back());
    stack.pop_back();
    const auto index = static_cast<std::int32_t>(nodes_.size());
    nodes_.emplace_back();
    if (task.parent >= 0) {
      Node& parent = nodes_[std::size_t(task.parent)];
      (task.positiveSide ? parent.positive : parent.negative) = index;
    }
    depth_ = std::max(depth_, task.depth);
    Node node;
    node.firstFragment = static_cast<std::uint32_t>(fragments_.size());
    std::vector<std::uint32_t> positive, negative;
    const auto keep = [&](std::uint32_t polygon) {
      const BuildPolygon& p = builder.polygons[polygon];
      fragments_.push_back({p.triangle, static_cast<std::uint32_t>(cuts_.size()), static_cast<std::uint32_t>(p.cuts.size())});
      cuts_.insert(cuts_.end(), p.cuts.begin(), p.cuts.end());
    };
    const std::optional<std::size_t> splitter = builder.chooseSplitter(task.list);
    if (!splitter) {
      // Only zero-area triangles: they cover no area, so any order is right.
      for (const std::uint32_t polygon : task.list) keep(polygon);
    } else {
      node.plane = builder.polygons[task.list[*splitter]].triangle;
      const auto plane = builder.splittingPlane(node.plane);
      // Step 2: distribute the list.
      for (const std::uint32_t polygon : task.list) {
        std::vector<int> sides;
        std::vector<double> heights;
        switch (builder.classify(builder.polygons[polygon], plane, &sides, &heights)) {
          case Side::coplanar: keep(polygon); break;
          case Side::positive: positive.push_back(polygon); break;
          case Side::negative: negative.push_back(polygon); break;
          case Side::straddles: {
            // A bad splitter on an adversarial scene splits quadratically often: stop
            // before memory runs out, naming the knob, rather than after.
            if (double(builder.splits) >= knobs.splitLimit)
              throw InputError("painter bsp: the tree needs more than " + std::to_string(builder.splits) +
                               " splits (--knob split-limit=" + std::to_string(static_cast<long long>(knobs.splitLimit)) +
                               "); raise the limit, or try --knob splitter=least-splits with more --knob candidates");
            ++builder.splits;
            BuildPolygon& source = builder.polygons[polygon];
            SplitPolygon pieces = splitPolygon(source.vertices, sides, heights);
            BuildPolygon below{source.triangle, std::move(pieces.negative), source.cuts, source.rounding};
            below.cuts.push_back({node.plane, false});
            source.vertices = std::move(pieces.positive);
            source.cuts.push_back({node.plane, true});
            positive.push_back(polygon);
            negative.push_back(static_cast<std::uint32_t>(builder.polygons.size()));
            builder.polygons.push_back(std::move(below));
            break;
          }
        }
      }
    }
    node.fragmentCount = static_cast<std::uint32_t>(fragments_.size()) - node.firstFragment;
    nodes_[std::size_t(index)] = node;
    // Step 3: the subtrees, built when popped.
    if (!negative.empty()) stack.push_back({std::move(negative), index, false, task.depth + 1});
    if (!positive.empty()) stack.push_back({std::move(positive), index, true, task.depth + 1});
  }
  stats.add("bsp nodes", static_cast<std::int64_t>(nodes_.size()));
  stats.add("bsp depth", depth_);
  stats.add("bsp splits", builder.splits);
  stats.add("bsp fragments", static_cast<std::int64_t>(fragments_.size()));
  stats.add("bsp classifications", builder.classifications);
  stats.add("predicate evaluations", builder.predicates.evaluations);
  stats.add("predicate exact fall-backs", builder.predicates.exactFallbacks);
}

}  // namespace hsr::painter

namespace hsr::painter {

PaintOrder BspTree::backToFront(const PreparedScene& scene, const ScreenGeometry& geometry, Stats& stats) const {
  PhaseTimer timer(stats, "bsp traversal");
  // Each triangle's screen triangles (several when clipping cut it into a fan) are a
  // run in the geometry, which is in triangle order.
  std::vector<std::uint32_t> firstScreen(scene.triangleCount() + 1, 0);
  for (const ScreenTriangle& tri : geometry.triangles) ++firstScreen[tri.triangle + 1];
  for (std::size_t t = 0; t < scene.triangleCount(); ++t) firstScreen[t + 1] += firstScreen[t];

  ExactPredicates predicates;
  PaintOrder order;
  std::vector<Cut> cuts;
  // Far side, node, near side: pushed in reverse. `expanded` marks a node whose
  // subtrees are already on the stack, so popping it again draws its own fragments.
  struct Visit {
    std::int32_t node;
    bool expanded;
  };
  std::vector<Visit> stack;
  if (!nodes_.empty()) stack.push_back({0, false});
  std::int64_t visited = 0;
  while (!stack.empty()) {
    const Visit visit = stack.back();
    stack.pop_back();
    const Node& node = nodes_[std::size_t(visit.node)];
    if (visit.expanded) {
      for (std::uint32_t f = node.firstFragment; f < node.firstFragment + node.fragmentCount; ++f) {
        const Fragment& fragment = fragments_[f];
        cuts.assign(cuts_.begin() + fragment.firstCut, cuts_.begin() + fragment.firstCut + fragment.cutCount);
        for (std::uint32_t s = firstScreen[fragment.triangle]; s < firstScreen[fragment.triangle + 1]; ++s) order.add(s, cuts);
      }
      continue;
    }
    ++visited;
    // BEGIN SOLUTION
    const Sides sides = sidesSeenFrom(scene, geometry.camera, node, predicates);
    if (sides.near >= 0) stack.push_back({sides.near, false});
    stack.push_back({visit.node, true});
    if (sides.far >= 0) stack.push_back({sides.far, false});
    // SKELETON
    // // Exercise 4: paint the node's far side, then the node, then its near side
    // // (sidesSeenFrom, below, says which is which; -1 for an empty side). The stack
    // // pops last in first out, so push the three in reverse: the near subtree
    // // ({subtree, false}), the node itself ({visit.node, true}: its fragments are
    // // painted when it comes off the stack again), then the far subtree.
    // (void)scene, (void)geometry;
    // END SOLUTION
  }
  stats.add("bsp nodes visited", visited);
  stats.add("predicate evaluations", predicates.evaluations);
  stats.add("predicate exact fall-backs", predicates.exactFallbacks);
  return order;
}

BspTree::Sides BspTree::sidesSeenFrom(const PreparedScene& scene, const CameraTransform& camera, const Node& node,
                                     ExactPredicates& predicates) {
  // BEGIN SOLUTION
  // The eye's side is the near side. On the plane itself the node's fragments are seen
  // edge-on, and either order of the subtrees is right; so is it for a node of zero-area
  // triangles only, which has no plane.
  const bool eyePositive = node.plane == kNoPlane || eyeSide(scene, camera, node.plane, predicates) >= 0;
  return eyePositive ? Sides{node.negative, node.positive} : Sides{node.positive, node.negative};
  // SKELETON
  // // Exercise 4: which of the node's subtrees lies on the eye's side of its plane (the
  // // near side) and which on the other (the far side)? eyeSide(scene, camera,
  // // node.plane, predicates) is >= 0 where the eye is on the plane's positive side,
  // // where the subtree node.positive lies (node.negative on the other; -1 for an empty
  // // one). A node of zero-area triangles only has no plane (node.plane == kNoPlane):
  // // either order is right there. What if the eye lies on the plane?
  // (void)scene, (void)camera, (void)node, (void)predicates;
  // return {-1, -1};
  // END SOLUTION
}

std::string BspTree::diagram(const PreparedScene& scene, const CameraTransform& camera, int levels) const {
  std::string graph = "digraph bsp {\n  node [shape=box, fontname=\"DejaVu Sans\", fontsize=11];\n  edge [fontname=\"DejaVu Sans\", fontsize=10];\n";
  if (nodes_.empty()) return graph + "  empty [label=\"no triangles\"];\n}\n";
  ExactPredicates predicates;
  const auto subtreeSize = [&](std::int32_t root) {
    std::size_t count = 0;
    std::vector<std::int32_t> pending = {root};
    while (!pending.empty()) {
      const Node& node = nodes_[std::size_t(pending.back())];
      pending.pop_back();
      ++count;
      for (const std::int32_t child : {node.positive, node.negative})
        if (child >= 0) pending.push_back(child);
    }
    return count;
  };
  struct Visit {
    std::int32_t node;
    int level;
  };
  std::vector<Visit> pending = {{0, 0}};
  while (!pending.empty()) {
    const auto [index, level] = pending.back();
    pending.pop_back();
    const Node& node = nodes_[std::size_t(index)];
    std::string name = "n";
    name += std::to_string(index);
    if (level == levels) {
      graph += "  " + name + " [label=\"" + std::to_string(subtreeSize(index)) + " more nodes\", style=dashed];\n";
      continue;
    }
    std::uint32_t split = 0;
    for (std::uint32_t f = node.firstFragment; f < node.firstFragment + node.fragmentCount; ++f) split += fragments_[f].cutCount > 0;
    graph += "  " + name + " [label=\"";
    graph += node.plane == kNoPlane ? "no plane (zero area)" : "plane of triangle " + std::to_string(node.plane);
    graph += "\\n" + std::to_string(node.fragmentCount) + " fragments";
    if (split) {
      graph += ", ";
      graph += std::to_string(split) + " split\", color=red, fontcolor=red";
    } else {
      graph += "\"";
    }
    graph += "];\n";
    const Sides sides = sidesSeenFrom(scene, camera, node, predicates);
    for (const auto& [child, far] : {std::pair{sides.far, true}, std::pair{sides.near, false}}) {
      if (child < 0) continue;
      graph += "  " + name + " -> n";
      graph += std::to_string(child) + " [label=\"" + (far ? "far" : "near") + "\"];\n";
      pending.push_back({child, level + 1});
    }
  }
  return graph + "}\n";
}

}  // namespace hsr::painter
