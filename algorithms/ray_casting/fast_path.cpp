// The bvh variant's fast paths (fast_path.hpp says what they compute and why it is the
// textbook's answer). Only the functions marked HSR_AVX2 use AVX2 (renderer/util/simd.hpp).
#include "algorithms/ray_casting/fast_path.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <utility>

#include "algorithms/ray_casting/watertight.hpp"
#include "renderer/rays/ray_packet.hpp"
#include "renderer/rays/wide_bvh.hpp"
#include "renderer/util/simd.hpp"

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

WideBvhTracer::WideBvhTracer(const PreparedScene& scene, Stats& stats, int threads)
    : bvh_(scene.wideTriangleBvh(stats, threads)), triangles_(scene.leafTriangles(stats)) {}

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

PacketTracer::PacketTracer(const PreparedScene& scene, Stats& stats, int threads)
    : single_(scene, stats, threads), bvh_(scene.wideTriangleBvh(stats, threads)), triangles_(scene.leafTriangles(stats)) {}

void PacketTracer::traceRun(const CameraTransform& camera, int y, int x0, int count, std::uint32_t* ids, float* depths,
                            Counters& counters, double* costs) const {
  for (int first = 0; first < count; first += RayPacket::kRays) {
    const int rays = std::min(RayPacket::kRays, count - first);
    if (tracePacket(camera, y, x0 + first, rays, ids + first, depths + first, counters, costs ? costs + first : nullptr)) continue;
    std::array<PixelRay, RayPacket::kRays> pixels;
    setUpPixelRays(camera, y, x0 + first, rays, pixels.data());
    for (int ray = 0; ray < rays; ++ray) {
      const double before = counters.cost();
      const Hit hit = single_.trace(pixels[ray], counters);
      ids[first + ray] = hit.id;
      depths[first + ray] = frameDepth(hit.id, pixels[ray].distance(hit.t));
      if (costs) costs[first + ray] = counters.cost() - before;
    }
  }
}

// One packet of pixels x .. x + count - 1, when their rays can travel together: the
// single-ray path's answer for each ray, by the same watertight test and the same rule
// (offer, watertight.hpp) in lanes.
HSR_AVX2 bool PacketTracer::tracePacket(const CameraTransform& camera, int y, int x, int count, std::uint32_t* ids, float* depths,
                                        Counters& counters, double* costs) const {
  // The rays set up four to a half, as setUpPixelRays sets them up; a packet of fewer
  // than eight repeats its last pixel in the lanes after it.
  FourPixelRays pixels[RayPacket::kHalves] = {
      FourPixelRays(camera, double(x) + smaller(Double4{0, 1, 2, 3}, lanesOf(count - 1)) + conventions::kPixelCenterOffset, y),
      FourPixelRays(camera, double(x) + smaller(Double4{4, 5, 6, 7}, lanesOf(count - 1)) + conventions::kPixelCenterOffset, y)};
  const FourRays rays[RayPacket::kHalves] = {pixels[0].rays, pixels[1].rays};
  if (!RayPacket::travelTogether(rays)) return false;
  const Double4 inverses[RayPacket::kHalves][3] = {{pixels[0].inverseDirection[0], pixels[0].inverseDirection[1], pixels[0].inverseDirection[2]},
                                                   {pixels[1].inverseDirection[0], pixels[1].inverseDirection[1], pixels[1].inverseDirection[2]}};
  const RayPacket packet(rays, inverses);
  const std::array<int, 3> axes = WatertightRay<double>::permutation(dvec3(rays[0].direction[0][0], rays[0].direction[1][0], rays[0].direction[2][0]));

  // Per half of four rays: the watertight test's set-up (WatertightRay's constructor)
  // and each ray's nearest hit so far, lane by lane.
  std::array<WatertightRay<Double4>, RayPacket::kHalves> ray = {WatertightRay<Double4>(axes), WatertightRay<Double4>(axes)};
  Double4 nearestT[RayPacket::kHalves], reach[RayPacket::kHalves];
  Mask4 nearestId[RayPacket::kHalves] = {};  // conventions::kBackgroundId in every lane
  for (int half = 0; half < RayPacket::kHalves; ++half) {
    for (int axis = 0; axis < 3; ++axis) ray[half].origin[axis] = packet.origin[axis][half];
    ray[half].shearZ = packet.inverse[ray[half].kz][half];
    ray[half].shearX = packet.direction[ray[half].kx][half] * ray[half].shearZ;
    ray[half].shearY = packet.direction[ray[half].ky][half] * ray[half].shearZ;
    nearestT[half] = pixels[half].tFar;
    reach[half] = nearestT[half] * kReachWidening;
  }
  const std::int64_t visited = visitLeaves(bvh_, packet, (1 << count) - 1, reach, [&](std::uint32_t first, std::uint16_t leafCount, int met, const LeafBox&) HSR_AVX2 {
    counters.triangleTests += std::int64_t(leafCount) * std::popcount(unsigned(met));
    for (int half = 0; half < RayPacket::kHalves; ++half) {
      if (raysInHalf(met, half) == 0) continue;
      const Mask4 lanes = laneMask4(raysInHalf(met, half));
      for (std::uint32_t slot = first; slot < first + leafCount; ++slot) {
        const PreparedScene::LeafTriangle& triangle = triangles_[slot];
        // WatertightRay::hit and offer, lane by lane: inside (or on an edge) with det != 0,
        // t within [tNear, nearest t], and nearer, or as near with a lower id.
        const ScaledBarycentrics<Double4> b = ray[half].barycentrics(triangle.a, triangle.b, triangle.c);
        const Mask4 outside = ((b.u < 0) | (b.v < 0) | (b.w < 0)) & ((b.u > 0) | (b.v > 0) | (b.w > 0));
        const Double4 det = b.u + b.v + b.w;
        const Mask4 crossed = lanes & ~outside & (det != 0);
        if (laneBits(crossed) == 0) continue;
        Double4 t;
        ray[half].hitParameter(b, crossed ? det : lanesOf(1), t);  // other lanes divide by 1, never by 0
        const std::int64_t id = triangle.id;
        const Mask4 nearer = crossed & (t >= pixels[half].tNear) & (t <= nearestT[half]) &
                             ((nearestId[half] == 0) | (t < nearestT[half]) | (id < nearestId[half]));
        nearestT[half] = nearer ? t : nearestT[half];
        nearestId[half] = nearer ? id : nearestId[half];
      }
      reach[half] = nearestT[half] * kReachWidening;
    }
  });
  counters.nodesVisited += visited;
  for (int r = 0; r < count; ++r) {
    const int half = r / 4, lane = r % 4;
    ids[r] = static_cast<std::uint32_t>(nearestId[half][lane]);
    depths[r] = frameDepth(ids[r], pixels[half].startDistance[lane] + nearestT[half][lane] * pixels[half].slope[lane]);
    if (costs) costs[r] = double(visited);
  }
  return true;
}

}  // namespace hsr::ray_casting
