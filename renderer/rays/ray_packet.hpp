// Eight rays traced through the wide BVH (renderer/rays/wide_bvh.hpp) together, a ray per
// lane: coherent ray tracing (Wald, Slusallek, Benthin and Wagner 2001) with the packet
// culled as a whole by interval bounds over its rays (Wald, Boulos and Shirley 2007, "Ray
// tracing deformable scenes using dynamic bounding volume hierarchies"). Neighbouring
// primary rays meet nearly the same boxes, so a node is fetched and ordered once for
// eight rays instead of once per ray.
//
// At every inner node the packet's interval bounds decide, per child, whether any of its
// rays can meet the child's box: each ray's slab parameters lie between the bounds'
// (rounding is monotonic, so the bounds computed by the same operations hold for the
// rounded values too). Only at a leaf is each ray's own box test run (RayBoxTest's, the
// same values), and the leaf handed over with the rays whose test met it: every ray
// sees exactly the leaves its own traversal would reach, and possibly some it would
// have skipped for being beyond its nearest hit.
//
// The bounds need all eight rays to run the same way along each axis: travelTogether()
// says whether they do (a ray parallel to an axis's slabs, or two running opposite ways,
// is traced alone by the caller).
#pragma once

#include <array>
#include <cstdint>
#include <limits>

#include "renderer/geometry/camera.hpp"
#include "renderer/rays/bvh.hpp"
#include "renderer/rays/wide_bvh.hpp"
#include "renderer/util/simd.hpp"

namespace hsr {

struct RayPacket {
  static constexpr int kRays = 8, kHalves = 2;

  // Ray r is lane r % 4 of half r / 4 (a vector of four).
  Double4 origin[3][kHalves], direction[3][kHalves], inverse[3][kHalves];
  int nearSide[3];  // per axis, the side of a box every ray meets first (RayBoxTest::nearSide)
  double originLow[3], originHigh[3], inverseLow[3], inverseHigh[3];  // per axis, over the rays
  bool sharedOrigin;  // every ray leaves one point (a perspective camera's primary rays)
  // The rays' directions lie close together: on each axis their components span at most
  // kCloseDirections of the first ray's length. (Primary rays of neighbouring pixels
  // span about 0.011 at 1280 x 720 and 60 degrees, 0.045 at 320 wide, 0.22 at 64.)
  bool closeDirections;
  static constexpr double kCloseDirections = 0.05;

  // Eight rays, four to a half, with their directions' inverses (inverseOf).
  HSR_AVX2 RayPacket(const FourRays (&rays)[kHalves], const Double4 (&inverses)[kHalves][3]);
  // Whether eight rays can travel as one packet: on every axis their directions'
  // components are all positive or all negative, and their largest components lie on one
  // axis (the axis a watertight ray-triangle test shears along: the packet's users set
  // that test up once for all its rays).
  HSR_AVX2 static bool travelTogether(const FourRays (&rays)[kHalves]);
};

// The rays of `rays` (a bit per ray) in half h, as bits 0..3.
inline int raysInHalf(int rays, int half) { return rays >> (4 * half) & 0xF; }

// A leaf's box: child `lane` of node `parent`.
struct LeafBox {
  const WideBvhNode& parent;
  int lane;
  double low(int axis) const { return parent.low[axis][lane]; }
  double high(int axis) const { return parent.high[axis][lane]; }
};

// A wide node's child waiting on a packet traversal's stack: an inner node, or a leaf's
// run of slots (with where its box is: the parent node and the lane); the rays that may
// meet it (a bit per ray), and the least parameter at which one of them can enter it.
struct PacketPending {
  std::uint32_t index;   // WideBvhNode::index
  std::uint16_t count;   // WideBvhNode::count: 0 for an inner node
  std::uint8_t lane;     // its lane in its parent
  std::uint8_t rays;
  std::uint32_t parent;  // its parent node
  double entry;
};

// The least entry parameter of any of the packet's rays into each of a node's children
// (lanes first .. first + 3) and a bit per child some ray may meet within [0, tMax].
HSR_AVX2 inline int packetMayMeet(const WideBvhNode& node, int first, const RayPacket& packet, double tMax, double* entries) {
  Double4 enter = lanesOf(0), exit = lanesOf(tMax);
  for (int axis = 0; axis < 3; ++axis) {
    const bool highFirst = packet.nearSide[axis] == 1;
    const Double4 nearPlane = widened((highFirst ? node.high[axis] : node.low[axis]) + first);
    const Double4 farPlane = widened((highFirst ? node.low[axis] : node.high[axis]) + first);
    // A ray's near parameter (nearPlane - o) * inv lies between the products over the
    // corners of the origin's and the inverse's intervals; so does its far one.
    const double inverseLow = packet.inverseLow[axis], inverseHigh = packet.inverseHigh[axis];
    Double4 nearLeast, farMost;
    const auto corners = [&](double origin, bool firstCorner) HSR_AVX2 {
      const Double4 toNear = nearPlane - origin, toFar = farPlane - origin;
      const Double4 least = smaller(toNear * inverseLow, toNear * inverseHigh), most = larger(toFar * inverseLow, toFar * inverseHigh);
      nearLeast = firstCorner ? least : smaller(nearLeast, least);
      farMost = firstCorner ? most : larger(farMost, most);
    };
    corners(packet.originLow[axis], true);
    if (!packet.sharedOrigin) corners(packet.originHigh[axis], false);
    enter = larger(enter, nearLeast);
    exit = smaller(exit, farMost * RayBoxTest::kWiden);
  }
  __builtin_memcpy(entries + first, &enter, sizeof enter);
  return laneBits(enter <= exit) << first;
}

// RayBoxTest::entry for the packet's rays in `rays` against child `lane` of `node`, each
// to its own reach: the rays that meet the box (a bit per ray).
HSR_AVX2 inline int raysMeeting(const WideBvhNode& node, int lane, const RayPacket& packet, const Double4 (&reach)[RayPacket::kHalves], int rays) {
  int met = 0;
  for (int half = 0; half < RayPacket::kHalves; ++half) {
    if (raysInHalf(rays, half) == 0) continue;
    Double4 enter = lanesOf(0), exit = reach[half];
    for (int axis = 0; axis < 3; ++axis) {
      const bool highFirst = packet.nearSide[axis] == 1;
      const double nearPlane = highFirst ? node.high[axis][lane] : node.low[axis][lane];
      const double farPlane = highFirst ? node.low[axis][lane] : node.high[axis][lane];
      const Double4 tNear = (nearPlane - packet.origin[axis][half]) * packet.inverse[axis][half];
      const Double4 tFar = (farPlane - packet.origin[axis][half]) * packet.inverse[axis][half] * RayBoxTest::kWiden;
      enter = tNear > enter ? tNear : enter;
      exit = tFar < exit ? tFar : exit;
    }
    met |= laneBits(enter <= exit) << (4 * half);
  }
  return met & rays;
}

// Calls leaf(first slot, count, rays, box) for every leaf some ray of the packet
// reaches, in about nearest-first order, with the rays (a bit per ray, within `active`)
// whose own box test meets the leaf's box within their reach, and the box (a LeafBox).
// leaf() may shrink reach (a ray's nearest hit so far, as the single-ray traversals
// widen it; ray r in lane r % 4 of half r / 4), and the traversal then skips what lies
// beyond every active ray's reach. Returns the inner nodes visited.
//
// At an inner node, the interval bounds cull the children no ray can meet. When the
// rays' directions spread (a small image, a wide view), an inner child the bounds keep
// is then tested ray by ray too (the rays that met its parent), and goes on the stack
// with the rays that meet it: on the bunny at 64 x 48 the bounds alone let a packet
// visit eight times the nodes. When they lie close (primary rays of a large image) the
// bounds alone are tight, and testing ray by ray would cost more than it culls (8% of
// the reference's time on counters at 1280 x 720).
template <typename Leaf>
HSR_AVX2 std::int64_t visitLeaves(const WideBvh& bvh, const RayPacket& packet, int active, const Double4 (&reach)[RayPacket::kHalves],
                                  Leaf&& leaf) {
  if (bvh.empty()) return 0;
  const auto farthestReach = [&]() HSR_AVX2 {
    const Double4 zero = lanesOf(0);
    const Double4 farther = larger(laneMask4(raysInHalf(active, 0)) ? reach[0] : zero, laneMask4(raysInHalf(active, 1)) ? reach[1] : zero);
    return std::max(std::max(farther[0], farther[1]), std::max(farther[2], farther[3]));
  };
  double farthest = farthestReach();
  const std::vector<WideBvhNode>& nodes = bvh.nodes();
  std::array<PacketPending, WideBvh::kStackSize> stack;
  int size = 0;
  std::int64_t visited = 0;
  PacketPending current{0, 0, 0, std::uint8_t(active), 0, 0};
  while (true) {
    if (current.count != 0) {
      const int rays = raysMeeting(nodes[current.parent], current.lane, packet, reach, current.rays);
      if (rays != 0) {
        leaf(current.index, current.count, rays, LeafBox{nodes[current.parent], current.lane});
        farthest = farthestReach();
      }
    } else {
      const std::uint32_t parent = current.index;
      const int parentRays = current.rays;
      const WideBvhNode& node = nodes[parent];
      ++visited;
      double entries[WideBvhNode::kWidth];
      int met = 0;
      for (int first = 0; first < node.children; first += 4) met |= packetMayMeet(node, first, packet, farthest, entries);
      std::uint8_t childRays[WideBvhNode::kWidth];  // when the directions spread: the rays meeting each inner child
      if (!packet.closeDirections)
        for (int bits = met; bits != 0; bits &= bits - 1) {
          const int lane = __builtin_ctz(unsigned(bits));
          childRays[lane] = std::uint8_t(node.leaf(lane) ? parentRays : raysMeeting(node, lane, packet, reach, parentRays));
          if (childRays[lane] == 0) met &= ~(1 << lane);
        }
      if (met != 0) {
        // As the single-ray traversal: the nearest child goes on, the others are stacked
        // farthest first.
        const auto child = [&](int lane) {
          const std::uint8_t rays = packet.closeDirections ? std::uint8_t(parentRays) : childRays[lane];
          return PacketPending{node.index[lane], node.count[lane], std::uint8_t(lane), rays, parent, entries[lane]};
        };
        current = child(__builtin_ctz(unsigned(met)));
        const int firstStacked = size;
        for (met &= met - 1; met != 0; met &= met - 1) {
          PacketPending next = child(__builtin_ctz(unsigned(met)));
          if (next.entry < current.entry) std::swap(next, current);
          int at = size++;
          for (; at > firstStacked && stack[at - 1].entry < next.entry; --at) stack[at] = stack[at - 1];
          stack[at] = next;
        }
        continue;
      }
    }
    do {
      if (size == 0) return visited;
      current = stack[--size];
    } while (current.entry > farthest);
  }
}

}  // namespace hsr
