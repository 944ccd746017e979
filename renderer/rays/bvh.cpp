#include "renderer/rays/bvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "renderer/util/error.hpp"

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

class Builder {
 public:
  Builder(std::span<const Aabb> boxes, std::vector<BvhNode>& nodes, std::vector<std::uint32_t>& order)
      : boxes_(boxes), nodes_(nodes), order_(order) {
    centroids_.reserve(boxes.size());
    for (const Aabb& box : boxes) centroids_.push_back(box.center());
  }

  int build(std::uint32_t nodeIndex, std::uint32_t begin, std::uint32_t end, int depth) {
    Aabb bounds, centroidBounds;
    for (std::uint32_t i = begin; i < end; ++i) {
      bounds.grow(boxes_[order_[i]]);
      centroidBounds.grow(centroids_[order_[i]]);
    }
    storeBounds(bounds, nodes_[nodeIndex]);
    const std::uint32_t count = end - begin;

    // Past kSahDepth levels (only adversarial inputs get there) split at the median
    // instead, so the depth, and with it every traversal stack, stays bounded.
    const Binning binning(centroidBounds);
    const Split split = depth < Bvh::kSahDepth ? bestSplit(begin, end, bounds, binning) : Split{};
    const double leafCost = Bvh::kIntersectionCost * bounds.halfArea() * count;
    if (count == 1 || (count <= Bvh::kMaxLeafSize && leafCost <= split.cost)) return makeLeaf(nodeIndex, begin, count);

    std::uint32_t middle;
    if (split.axis < 0) {
      // No SAH split (all centroids coincide, or too deep): halve the list along the
      // widest centroid extent; ties keep id order, so the build is deterministic.
      const dvec3 extent = centroidBounds.hi - centroidBounds.lo;
      const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
      middle = begin + count / 2;
      std::stable_sort(order_.begin() + begin, order_.begin() + end, [&](std::uint32_t p, std::uint32_t q) {
        return centroids_[p][axis] < centroids_[q][axis];
      });
    } else {
      const auto first = order_.begin() + begin, last = order_.begin() + end;
      middle = begin + static_cast<std::uint32_t>(
                           std::stable_partition(first, last, [&](std::uint32_t primitive) {
                             return binning.bin(centroids_[primitive], split.axis) < split.bin;
                           }) - first);
    }
    const auto children = static_cast<std::uint32_t>(nodes_.size());
    nodes_.resize(nodes_.size() + 2);
    BvhNode& node = nodes_[nodeIndex];
    node.index = children;
    node.count = 0;
    node.axis = static_cast<std::uint16_t>(std::max(split.axis, 0));
    const int left = build(children, begin, middle, depth + 1);
    const int right = build(children + 1, middle, end, depth + 1);
    return 1 + std::max(left, right);
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

  // The SAH: cost(split) = C_trav A(node) + C_isect (A(left) N(left) + A(right) N(right)),
  // in units where a leaf costs C_isect A(node) N; evaluated at the kBins - 1 bin
  // boundaries of each axis, with one pass over the primitives filling all three axes.
  Split bestSplit(std::uint32_t begin, std::uint32_t end, const Aabb& bounds, const Binning& binning) const {
    std::array<std::array<Aabb, Bvh::kBins>, 3> binBox;
    std::array<std::array<std::uint32_t, Bvh::kBins>, 3> binCount{};
    for (std::uint32_t i = begin; i < end; ++i) {
      const std::uint32_t primitive = order_[i];
      for (int axis = 0; axis < 3; ++axis) {
        const int bin = binning.bin(centroids_[primitive], axis);
        binBox[axis][bin].grow(boxes_[primitive]);
        ++binCount[axis][bin];
      }
    }
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
      if (binning.scale[axis] == 0) continue;
      // Sweep from the right to know A(right) N(right) at each boundary, then from the left.
      std::array<double, Bvh::kBins> rightCost{};
      Aabb right;
      std::uint32_t rightCount = 0;
      for (int bin = Bvh::kBins - 1; bin > 0; --bin) {
        right.grow(binBox[axis][bin]);
        rightCount += binCount[axis][bin];
        rightCost[bin] = right.halfArea() * rightCount;
      }
      Aabb left;
      std::uint32_t leftCount = 0;
      for (int bin = 1; bin < Bvh::kBins; ++bin) {
        left.grow(binBox[axis][bin - 1]);
        leftCount += binCount[axis][bin - 1];
        if (leftCount == 0 || leftCount == end - begin) continue;
        const double cost = Bvh::kTraversalCost * bounds.halfArea() +
                            Bvh::kIntersectionCost * (left.halfArea() * leftCount + rightCost[bin]);
        if (cost < best.cost) best = {axis, bin, cost};
      }
    }
    return best;
  }

  int makeLeaf(std::uint32_t nodeIndex, std::uint32_t begin, std::uint32_t count) {
    HSR_CHECK(count <= Bvh::kMaxLeafSize);
    nodes_[nodeIndex].index = begin;
    nodes_[nodeIndex].count = static_cast<std::uint16_t>(count);
    nodes_[nodeIndex].axis = 0;
    return 1;
  }

  std::span<const Aabb> boxes_;
  std::vector<dvec3> centroids_;
  std::vector<BvhNode>& nodes_;
  std::vector<std::uint32_t>& order_;
};

}  // namespace

Bvh::Bvh(std::span<const Aabb> boxes) {
  if (boxes.empty()) return;
  HSR_CHECK(boxes.size() < std::numeric_limits<std::uint32_t>::max());
  order_.resize(boxes.size());
  for (std::uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  nodes_.reserve(2 * boxes.size());
  nodes_.resize(1);
  depth_ = Builder(boxes, nodes_, order_).build(0, 0, static_cast<std::uint32_t>(boxes.size()), 1);
}

}  // namespace hsr
