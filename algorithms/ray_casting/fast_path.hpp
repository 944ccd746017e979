// The bvh variant's fast paths, beside its textbook traversal (ray_casting.cpp), over the
// BVH with four children to a node (renderer/rays/wide_bvh.hpp), with AVX2:
//
//   simd    one ray at a time; a node's four child boxes tested at once, a child per
//           lane, the nearest hit child entered and the others stacked farthest first.
//   packet  eight neighbouring rays of a row at a time (Wald, Slusallek, Benthin and
//           Wagner 2001, "Interactive rendering with coherent ray tracing"): a node is
//           fetched once for the eight, its child boxes tested against every ray still
//           active, a ray per lane, and a leaf's triangles tested against the rays whose
//           own box test reached it, four rays to a vector.
//
// Both find, for every ray, the textbook's answer: the nearest hit by the same watertight
// test (watertight.hpp) over the same triangles (a box test only decides which are
// tried, and is at least as generous as the textbook's), ties to the lower id. So the
// ids and depths are the textbook's bit for bit (tests/ray_casting/fast_path_test.cpp
// checks every shipped scene, hard case and random scene). Their counters are their
// own: "bvh nodes visited" counts wide nodes (and, for packets, a node fetched once for
// the eight rays).
#pragma once

#include "algorithms/ray_casting/cast.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::ray_casting {

class WideBvhTracer {
 public:
  using Counters = TraversalCounters;
  WideBvhTracer(const PreparedScene& scene, Stats& stats, int threads = 1);  // threads: the wide BVH's build, if first
  Hit trace(const PixelRay& pixel, Counters& counters) const;

 private:
  const WideBvh& bvh_;
  const std::vector<PreparedScene::LeafTriangle>& triangles_;
};

class PacketTracer {
 public:
  using Counters = TraversalCounters;
  PacketTracer(const PreparedScene& scene, Stats& stats, int threads = 1);
  // Pixels x0 .. x0 + count - 1 of row y (castRays, cast.hpp) in packets of eight
  // neighbours; a packet whose rays cannot travel together (RayPacket::travelTogether)
  // is traced ray by ray by the simd path. costs[i], when asked for, is the inner nodes
  // visited by pixel i's packet.
  void traceRun(const CameraTransform& camera, int y, int x0, int count, std::uint32_t* ids, float* depths, Counters& counters,
                double* costs) const;

 private:
  bool tracePacket(const CameraTransform& camera, int y, int x, int count, std::uint32_t* ids, float* depths, Counters& counters,
                   double* costs) const;
  WideBvhTracer single_;
  const WideBvh& bvh_;
  const std::vector<PreparedScene::LeafTriangle>& triangles_;
};

}  // namespace hsr::ray_casting
