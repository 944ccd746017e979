// The bvh variant's fast paths (fast_path.hpp says what they compute and why it is the
// textbook's answer). Only the functions marked HSR_AVX2 use AVX2 (renderer/simd.hpp).
#include "algorithms/ray_casting/fast_path.hpp"

#include <array>
#include <utility>

#include "algorithms/ray_casting/watertight.hpp"
#include "renderer/simd.hpp"
#include "renderer/wide_bvh.hpp"

namespace hsr::ray_casting {
namespace {

// A child waiting on the traversal stack: an inner node, or a leaf's run of slots, with
// the parameter where the ray enters its box.
struct Pending {
  std::uint32_t index;  // WideBvhNode::index
  std::uint16_t count;  // WideBvhNode::count: 0 for an inner node
  double entry;
};

}  // namespace

WideBvhTracer::WideBvhTracer(const PreparedScene& scene, Stats& stats)
    : bvh_(scene.wideTriangleBvh(stats)), triangles_(scene.leafTriangles(stats)) {}

HSR_AVX2 Hit WideBvhTracer::trace(const PixelRay& pixel, Counters& counters) const {
  Hit nearest{conventions::kBackgroundId, pixel.tFar};
  if (bvh_.empty()) return nearest;
  const RayBoxTest boxes(pixel.ray.origin, pixel.ray.direction, pixel.inverseDirection);
  const WideRayBoxTest children(boxes);
  const WatertightRay<double> ray(pixel.ray, pixel.inverseDirection);
  const std::vector<WideBvhNode>& nodes = bvh_.nodes();
  std::array<Pending, WideBvh::kStackSize> stack;
  int size = 0;
  Pending current{0, 0, 0};
  while (true) {
    if (current.count != 0) {
      counters.triangleTests += current.count;
      for (std::uint32_t slot = current.index; slot < current.index + current.count; ++slot) offer(ray, triangles_[slot], pixel, nearest);
    } else {
      // Ordered traversal: enter the nearest child the ray meets, stack the others
      // farthest first so that they come off the stack nearest first.
      const WideBvhNode& node = nodes[current.index];
      ++counters.nodesVisited;
      double entries[WideBvhNode::kWidth];
      int hit = children.entries(node, reachOf(nearest), entries);
      if (hit != 0) {
        const auto child = [&](int lane) { return Pending{node.index[lane], node.count[lane], entries[lane]}; };
        current = child(__builtin_ctz(unsigned(hit)));
        // Each further child met: the nearer of it and the current one goes on, the
        // farther is stacked, ordered among the ones stacked from this node.
        const int first = size;
        for (hit &= hit - 1; hit != 0; hit &= hit - 1) {
          Pending next = child(__builtin_ctz(unsigned(hit)));
          if (next.entry < current.entry) std::swap(next, current);
          int at = size++;
          for (; at > first && stack[at - 1].entry < next.entry; --at) stack[at] = stack[at - 1];
          stack[at] = next;
        }
        continue;
      }
    }
    // Pop until a child that still starts before the nearest hit.
    do {
      if (size == 0) return nearest;
      current = stack[--size];
    } while (current.entry > reachOf(nearest));
  }
}

}  // namespace hsr::ray_casting
