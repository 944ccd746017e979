#include "renderer/rays/bvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numeric>

#include "renderer/util/error.hpp"
#include "renderer/util/memory.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr {

double Aabb::halfArea() const {
  if (empty()) return 0;
  const dvec3 size = hi - lo;
  return size.x * size.y + size.y * size.z + size.z * size.x;
}

namespace {

// The largest float at most x, and the smallest at least x. Beyond the float range (no
// scene reaches it, but adversarial tests do) they are the largest float or an infinity,
// never an overflowing conversion.
float floatBelow(double x) {
  constexpr float kMax = std::numeric_limits<float>::max(), kInfinity = std::numeric_limits<float>::infinity();
  if (x >= double(kMax)) return kMax;
  if (x < -double(kMax)) return -kInfinity;
  const float f = static_cast<float>(x);
  return double(f) > x ? std::nextafter(f, -kInfinity) : f;
}
float floatAbove(double x) { return -floatBelow(-x); }

// Rounds a double box outward to floats, so the float box contains the double one.
void storeBounds(const Aabb& box, BvhNode& node) {
  for (int axis = 0; axis < 3; ++axis) {
    node.bounds[0][axis] = floatBelow(box.lo[axis]);
    node.bounds[1][axis] = floatAbove(box.hi[axis]);
  }
}

// The binned SAH build. Every decision (a node's bounds, its split, the partition of its
// primitives) depends only on the primitives under the node, so subtrees can be built
// apart; and min, max and counting give the same result in any order, so a node's
// binning can be shared among threads. The tree is therefore the same for any thread
// count (Bvh::Bvh below lays it out as one thread would).
class Builder {
 public:
  // The centroids are written on the threads, each part by the thread that computes it:
  // memory is slow to touch the first time (about 3 ms a megabyte on this machine kind,
  // page faults), and faults on two threads take half the time.
  Builder(std::span<const Aabb> boxes, std::vector<std::uint32_t>& order, int threads)
      : boxes_(boxes), centroids_(uninitializedArray<dvec3>(boxes.size())), order_(order) {
    parallelForEach(boxes.size(), kPrimitivesPerPart, threads, [&](std::size_t i) { centroids_[i] = boxes[i].center(); });
  }

  // What is decided at a node: its bounds, and either a leaf or where its primitives
  // divide (order_ is partitioned in place: [begin, middle) go left).
  struct Decision {
    Aabb bounds;
    bool leaf = false;
    std::uint32_t middle = 0;
    int axis = 0;
  };

  // The textbook recursion: decide the node, then build its children. Children are
  // placed as a pair at the end of `nodes`, the left subtree wholly before the right.
  // Returns the subtree's depth.
  int build(std::vector<BvhNode>& nodes, std::uint32_t nodeIndex, std::uint32_t begin, std::uint32_t end, int depth) {
    const Decision decision = decide(begin, end, depth, 1);
    storeBounds(decision.bounds, nodes[nodeIndex]);
    if (decision.leaf) return makeLeaf(nodes[nodeIndex], begin, end - begin);
    const auto children = static_cast<std::uint32_t>(nodes.size());
    nodes.resize(nodes.size() + 2);
    makeInterior(nodes[nodeIndex], children, decision.axis);
    const int left = build(nodes, children, begin, decision.middle, depth + 1);
    const int right = build(nodes, children + 1, decision.middle, end, depth + 1);
    return 1 + std::max(left, right);
  }

  Decision decide(std::uint32_t begin, std::uint32_t end, int depth, int threads) {
    Decision decision;
    Aabb centroidBounds;
    boundsOf(begin, end, threads, decision.bounds, centroidBounds);
    const std::uint32_t count = end - begin;

    // Past kSahDepth levels (only adversarial inputs get there) split at the median
    // instead, so the depth, and with it every traversal stack, stays bounded.
    const Binning binning(centroidBounds);
    const Split split = depth < Bvh::kSahDepth ? bestSplit(begin, end, decision.bounds, binning, threads) : Split{};
    const double leafCost = Bvh::kIntersectionCost * decision.bounds.halfArea() * count;
    if (count == 1 || (count <= Bvh::kMaxLeafSize && leafCost <= split.cost)) {
      decision.leaf = true;
      return decision;
    }
    const auto first = order_.begin() + begin, last = order_.begin() + end;
    if (split.axis < 0) {
      // No SAH split (all centroids coincide, or too deep): halve the list along the
      // widest centroid extent; ties keep id order, so the build is deterministic.
      const dvec3 extent = centroidBounds.hi - centroidBounds.lo;
      const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
      decision.middle = begin + count / 2;
      std::stable_sort(first, last, [&](std::uint32_t p, std::uint32_t q) { return centroids_[p][axis] < centroids_[q][axis]; });
    } else {
      decision.middle = stablePartition(begin, end, [&](std::uint32_t primitive) {
        return binning.bin(centroids_[primitive], split.axis) < split.bin;
      });
    }
    decision.axis = std::max(split.axis, 0);
    return decision;
  }

  // std::stable_partition of order_[begin, end), without its temporary buffer: one
  // allocation a node, which threads building subtrees at once contend for (two threads
  // took 1.45 times one thread's time a subtree). The primitives that go left move up in
  // place; the others wait in a buffer each thread keeps. Returns the first right one.
  template <typename GoesLeft>
  std::uint32_t stablePartition(std::uint32_t begin, std::uint32_t end, GoesLeft&& goesLeft) {
    thread_local std::vector<std::uint32_t> right;
    right.clear();
    std::uint32_t left = begin;
    for (std::uint32_t i = begin; i < end; ++i) {
      const std::uint32_t primitive = order_[i];
      if (goesLeft(primitive)) order_[left++] = primitive;
      else right.push_back(primitive);
    }
    std::copy(right.begin(), right.end(), order_.begin() + left);
    return left;
  }

  static int makeLeaf(BvhNode& node, std::uint32_t begin, std::uint32_t count) {
    HSR_CHECK(count <= Bvh::kMaxLeafSize);
    node.index = begin;
    node.count = static_cast<std::uint16_t>(count);
    node.axis = 0;
    return 1;
  }
  static void makeInterior(BvhNode& node, std::uint32_t children, int axis) {
    node.index = children;
    node.count = 0;
    node.axis = static_cast<std::uint16_t>(axis);
  }

 private:
  struct Split {
    int axis = -1;  // -1: no split plane exists (all centroids equal)
    int bin = 0;    // primitives in bins [0, bin) go left
    double cost = std::numeric_limits<double>::infinity();
  };

  // The bin of a centroid along an axis: kBins equal slices of the centroid bounds.
  struct Binning {
    dvec3 lo, scale;  // bin = floor((c - lo) * scale), clamped
    explicit Binning(const Aabb& centroidBounds) : lo(centroidBounds.lo) {
      const dvec3 extent = centroidBounds.hi - centroidBounds.lo;
      // An extent too small for kBins / extent to be finite (subnormal: the fuzzer found
      // one) is no extent: the division would overflow, and 0 * infinity would make a bin
      // of NaN. The bound keeps a factor 2 from the overflow so rounding cannot reach it.
      constexpr double kSmallestExtent = 2 * Bvh::kBins / std::numeric_limits<double>::max();
      for (int axis = 0; axis < 3; ++axis) scale[axis] = extent[axis] > kSmallestExtent ? Bvh::kBins / extent[axis] : 0;
    }
    int bin(const dvec3& centroid, int axis) const {
      return std::clamp(static_cast<int>((centroid[axis] - lo[axis]) * scale[axis]), 0, Bvh::kBins - 1);
    }
  };

  // A large node's primitives are shared among the threads in parts of this many.
  static constexpr std::size_t kPrimitivesPerPart = 16384;
  static std::size_t partsOf(std::size_t count, int threads) {
    return threads > 1 ? std::max<std::size_t>(1, count / kPrimitivesPerPart) : 1;
  }

  // A loop over a node's primitives [begin, end), in parts, each part into its own
  // partial result, which are then merged in part order. Only min, max and counts are
  // merged, so any parts give the same result.
  template <typename Partial, typename Accumulate, typename Merge>
  Partial reduce(std::uint32_t begin, std::uint32_t end, int threads, Accumulate&& accumulate, Merge&& merge) const {
    const std::size_t parts = partsOf(end - begin, threads);
    if (parts == 1) {  // a small node, or one thread: no partials, so no allocation a node
      Partial whole{};
      for (std::uint32_t i = begin; i < end; ++i) accumulate(whole, order_[i]);
      return whole;
    }
    std::vector<Partial> partials(parts);
    parallelFor(parts, threads, [&](std::size_t part, int) {
      const auto [from, to] = partRange(end - begin, parts, part);
      for (std::size_t i = begin + from; i < begin + to; ++i) accumulate(partials[part], order_[i]);
    });
    for (std::size_t part = 1; part < parts; ++part) merge(partials[0], partials[part]);
    return partials[0];
  }

  void boundsOf(std::uint32_t begin, std::uint32_t end, int threads, Aabb& bounds, Aabb& centroidBounds) const {
    using Both = std::array<Aabb, 2>;
    const Both both = reduce<Both>(
        begin, end, threads,
        [&](Both& partial, std::uint32_t primitive) {
          partial[0].grow(boxes_[primitive]);
          partial[1].grow(centroids_[primitive]);
        },
        [](Both& into, const Both& from) {
          into[0].grow(from[0]);
          into[1].grow(from[1]);
        });
    bounds = both[0], centroidBounds = both[1];
  }

  // The SAH: cost(split) = C_trav A(node) + C_isect (A(left) N(left) + A(right) N(right)),
  // in units where a leaf costs C_isect A(node) N; evaluated at the kBins - 1 bin
  // boundaries of each axis, with one pass over the primitives filling all three axes.
  Split bestSplit(std::uint32_t begin, std::uint32_t end, const Aabb& bounds, const Binning& binning, int threads) const {
    struct Bins {
      std::array<std::array<Aabb, Bvh::kBins>, 3> box;
      std::array<std::array<std::uint32_t, Bvh::kBins>, 3> count{};
    };
    const Bins bins = reduce<Bins>(
        begin, end, threads,
        [&](Bins& partial, std::uint32_t primitive) {
          for (int axis = 0; axis < 3; ++axis) {
            const int bin = binning.bin(centroids_[primitive], axis);
            partial.box[axis][bin].grow(boxes_[primitive]);
            ++partial.count[axis][bin];
          }
        },
        [](Bins& into, const Bins& from) {
          for (int axis = 0; axis < 3; ++axis)
            for (int bin = 0; bin < Bvh::kBins; ++bin) {
              into.box[axis][bin].grow(from.box[axis][bin]);
              into.count[axis][bin] += from.count[axis][bin];
            }
        });
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
      if (binning.scale[axis] == 0) continue;
      // Sweep from the right to know A(right) N(right) at each boundary, then from the left.
      std::array<double, Bvh::kBins> rightCost{};
      Aabb right;
      std::uint32_t rightCount = 0;
      for (int bin = Bvh::kBins - 1; bin > 0; --bin) {
        right.grow(bins.box[axis][bin]);
        rightCount += bins.count[axis][bin];
        rightCost[bin] = right.halfArea() * rightCount;
      }
      Aabb left;
      std::uint32_t leftCount = 0;
      for (int bin = 1; bin < Bvh::kBins; ++bin) {
        left.grow(bins.box[axis][bin - 1]);
        leftCount += bins.count[axis][bin - 1];
        if (leftCount == 0 || leftCount == end - begin) continue;
        const double cost = Bvh::kTraversalCost * bounds.halfArea() +
                            Bvh::kIntersectionCost * (left.halfArea() * leftCount + rightCost[bin]);
        if (cost < best.cost) best = {axis, bin, cost};
      }
    }
    return best;
  }

  std::span<const Aabb> boxes_;
  std::unique_ptr<dvec3[]> centroids_;
  std::vector<std::uint32_t>& order_;
};

// The parallel build: the top of the tree decided node by node, each node's loops shared
// among the threads, down to subtrees small enough to be many; those are built whole,
// one per thread at a time, each into nodes of its own; then every node is placed where
// the one-thread build puts it, so the tree and its layout are the same bits.
class ParallelBuild {
 public:
  ParallelBuild(Builder& builder, std::size_t primitives, int threads)
      : builder_(builder), threads_(threads),
        // About four subtrees a thread, so that uneven ones even out.
        subtreeSize_(std::max<std::size_t>(4096, primitives / (4 * std::size_t(threads)))) {}

  int run(std::uint32_t primitives, std::vector<BvhNode>& nodes) {
    decideTop(primitives);
    std::vector<int> depths(subtrees_.size());
    // The largest first, so that the last to start are short.
    std::vector<std::size_t> largestFirst(subtrees_.size());
    std::iota(largestFirst.begin(), largestFirst.end(), std::size_t(0));
    std::stable_sort(largestFirst.begin(), largestFirst.end(), [&](std::size_t p, std::size_t q) {
      return subtrees_[p].end - subtrees_[p].begin > subtrees_[q].end - subtrees_[q].begin;
    });
    parallelFor(subtrees_.size(), threads_, [&](std::size_t item, int) {
      const std::size_t k = largestFirst[item];
      Subtree& subtree = subtrees_[k];
      subtree.nodes.reserve(2 * std::size_t(subtree.end - subtree.begin));  // a binary tree's most
      subtree.nodes.resize(1);
      depths[k] = builder_.build(subtree.nodes, 0, subtree.begin, subtree.end, subtree.depth);
    });
    // Where the one-thread build places each node: a walk in its order over the top,
    // copying each subtree's nodes as one block (its own layout is already that order).
    nodes.resize(1);
    const int depth = place(0, 0, nodes, depths);
    parallelFor(subtrees_.size(), threads_, [&](std::size_t k, int) { copySubtree(subtrees_[k], nodes); });
    return depth;
  }

 private:
  struct Subtree {
    std::uint32_t begin, end;
    int depth;
    std::vector<BvhNode> nodes;  // [0] is the subtree's root
    std::uint32_t root = 0, base = 0;  // where its root and its other nodes go in the final layout
  };
  struct TopNode {
    BvhNode node;
    int subtree = -1;  // >= 0: the node is that subtree's root, built whole
  };

  // The top, level by level: a level of four nodes a thread or more decides them side
  // by side, one a thread; a smaller one (the first few levels) decides each node with
  // its loops shared among the threads, which balances nodes of uneven sizes. Nodes small
  // enough become subtrees.
  void decideTop(std::uint32_t primitives) {
    struct Pending {
      std::uint32_t index, begin, end;
      int depth;
    };
    top_.resize(1);
    std::vector<Pending> level = {{0, 0, primitives, 1}};
    while (!level.empty()) {
      std::vector<Builder::Decision> decisions(level.size());
      const bool sideBySide = level.size() >= 4 * std::size_t(threads_);
      parallelFor(level.size(), sideBySide ? threads_ : 1, [&](std::size_t k, int) {
        decisions[k] = builder_.decide(level[k].begin, level[k].end, level[k].depth, sideBySide ? 1 : threads_);
      });
      std::vector<Pending> next;
      for (std::size_t k = 0; k < level.size(); ++k) {
        const auto [index, begin, end, depth] = level[k];
        const Builder::Decision& decision = decisions[k];
        storeBounds(decision.bounds, top_[index].node);
        if (decision.leaf) {
          Builder::makeLeaf(top_[index].node, begin, end - begin);
          continue;
        }
        const auto children = static_cast<std::uint32_t>(top_.size());
        top_.resize(top_.size() + 2);
        Builder::makeInterior(top_[index].node, children, decision.axis);
        const Pending halves[2] = {{children, begin, decision.middle, depth + 1}, {children + 1, decision.middle, end, depth + 1}};
        for (const Pending& half : halves) {
          if (half.end - half.begin > subtreeSize_) {
            next.push_back(half);
          } else {
            top_[half.index].subtree = static_cast<int>(subtrees_.size());
            subtrees_.push_back({half.begin, half.end, half.depth, {}});
          }
        }
      }
      level = std::move(next);
    }
  }

  // Places top node `index` at nodes[at] and makes room for its descendants after it,
  // in the order build() would: a subtree's nodes other than its root get a block,
  // filled afterwards, in parallel. Returns the depth below and including the node.
  int place(std::uint32_t index, std::uint32_t at, std::vector<BvhNode>& nodes, const std::vector<int>& depths) {
    const TopNode& top = top_[index];
    if (top.subtree >= 0) {
      Subtree& subtree = subtrees_[std::size_t(top.subtree)];
      subtree.root = at;
      subtree.base = static_cast<std::uint32_t>(nodes.size());
      nodes.resize(nodes.size() + subtree.nodes.size() - 1);
      return depths[std::size_t(top.subtree)];
    }
    nodes[at] = top.node;
    if (top.node.leaf()) return 1;
    const auto children = static_cast<std::uint32_t>(nodes.size());
    nodes.resize(nodes.size() + 2);
    nodes[at].index = children;
    const int left = place(top.node.index, children, nodes, depths);
    const int right = place(top.node.index + 1, children + 1, nodes, depths);
    return 1 + std::max(left, right);
  }

  // A subtree's node k > 0 goes to base + k - 1, so its children's indices move by the same.
  static void copySubtree(const Subtree& subtree, std::vector<BvhNode>& nodes) {
    for (std::size_t k = 0; k < subtree.nodes.size(); ++k) {
      BvhNode node = subtree.nodes[k];
      if (!node.leaf()) node.index = subtree.base + node.index - 1;
      nodes[k == 0 ? subtree.root : subtree.base + k - 1] = node;
    }
  }

  Builder& builder_;
  int threads_;
  std::size_t subtreeSize_;
  std::vector<TopNode> top_;
  std::vector<Subtree> subtrees_;
};

}  // namespace

Bvh::Bvh(std::span<const Aabb> boxes, int threads) {
  if (boxes.empty()) return;
  HSR_CHECK(boxes.size() < std::numeric_limits<std::uint32_t>::max());
  order_.resize(boxes.size());
  for (std::uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  nodes_.reserve(2 * boxes.size());
  Builder builder(boxes, order_, threads);
  const auto primitives = static_cast<std::uint32_t>(boxes.size());
  if (const int workers = resolveThreadCount(threads); workers > 1) {
    depth_ = ParallelBuild(builder, primitives, workers).run(primitives, nodes_);
  } else {
    nodes_.resize(1);
    depth_ = builder.build(nodes_, 0, 0, primitives, 1);
  }
}

}  // namespace hsr
