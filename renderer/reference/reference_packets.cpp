// The exact reference's fast path: primary rays traced eight at a time through the wide
// BVH (renderer/rays/ray_packet.hpp), each ray's triangles decided by the same bounded test
// in four lanes at once (renderer/reference/bounded_woop.hpp) and by the same exact fall-back
// where the bounds leave a decision open, each ray keeping its own candidates and
// horizon (renderer/reference/nearest_hit.hpp). A ray sees every leaf its own traversal would
// reach, in about the same nearest-first order, and offers each triangle with its own
// horizon at the time: so the ids, depths and ambiguous pixels come out the textbook
// traversal's, and so do the rays that needed exact work, since a triangle the bounds
// leave open is decided only at the end of a ray's search, whatever the order it was met
// in (tests/renderer/reference/reference_test.cpp compares them on every shipped scene
// and on random ones).
#include <bit>
#include <optional>

#include "renderer/rays/ray_packet.hpp"
#include "renderer/reference/nearest_hit.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/simd.hpp"

namespace hsr {

using namespace reference_search;

namespace {

// The rays through pixels x .. x + count - 1 of row y (the last repeated in the lanes
// after it), as rayThroughPixel gives them, with what every test of a triangle against
// them needs set up once: per half, RayQuery's set-up in lanes, the shear and the view
// distance. Only for rays that can travel together (RayPacket::travelTogether).
struct PacketRays {
  static constexpr int kHalves = RayPacket::kHalves;
  FourRays rays[kHalves];
  Double4 inverses[kHalves][3];
  std::array<int, 3> axes;
  std::optional<ShearedRay<Double4>> shear[kHalves];
  std::optional<woop::ViewDistance<Double4>> view[kHalves];

  HSR_AVX2 bool setUp(const CameraTransform& camera, int y, int x, int count) {
    for (int half = 0; half < kHalves; ++half)
      rays[half] = camera.raysThroughPixels(
          double(x) + smaller(Double4{0, 1, 2, 3} + double(4 * half), lanesOf(count - 1)) + conventions::kPixelCenterOffset, conventions::pixelCenter(y));
    if (!RayPacket::travelTogether(rays)) return false;
    axes = ShearedRay<double>::axesOf(ray(0).direction);
    for (int half = 0; half < kHalves; ++half) inverses[half][axes[2]] = inverseOf(rays[half].direction[axes[2]]);
    const auto lanes = [&](const Double4(&values)[3]) HSR_AVX2 { return std::array<Double4, 3>{values[0], values[1], values[2]}; };
    // No direction has a zero component here (travelTogether), so inverseOf is 1 / d.
    for (int half = 0; half < kHalves; ++half) {
      shear[half].emplace(axes, lanes(rays[half].origin), lanes(rays[half].direction), inverses[half][axes[2]]);
      view[half].emplace(camera, lanes(rays[half].origin), lanes(rays[half].direction));
    }
    return true;
  }

  // The inverses of the directions' other components, which only a traversal needs.
  HSR_AVX2 void invertAcross() {
    for (int half = 0; half < kHalves; ++half)
      for (int axis : {axes[0], axes[1]}) inverses[half][axis] = inverseOf(rays[half].direction[axis]);
  }

  HSR_AVX2 Ray ray(int r) const {
    Ray single;
    for (int axis = 0; axis < 3; ++axis)
      single.origin[axis] = rays[r / 4].origin[axis][r % 4], single.direction[axis] = rays[r / 4].direction[axis][r % 4];
    return single;
  }

  // Each ray's view distance along it, out of the lanes: originDistance + t slope.
  HSR_AVX2 void viewDistances(double (&originDistance)[RayPacket::kRays], double (&slope)[RayPacket::kRays]) const {
    for (int half = 0; half < kHalves; ++half) {
      __builtin_memcpy(originDistance + 4 * half, &view[half]->originDistance, sizeof(Double4));
      __builtin_memcpy(slope + 4 * half, &view[half]->slope, sizeof(Double4));
    }
  }
};

}  // namespace

HSR_AVX2 bool SurfaceReference::tracePacket(const CameraTransform& camera, int y, int x, int count, ReferenceHit* hits,
                                            Counters& counters) const {
  constexpr int kHalves = RayPacket::kHalves;
  PacketRays set;
  if (!set.setUp(camera, y, x, count)) return false;
  set.invertAcross();
  const RayPacket packet(set.rays, set.inverses);
  std::array<NearestHitSearch, RayPacket::kRays> search;
  // A ray's RayQuery is made afresh for each exact decision: they are rare, and a packet
  // holding eight would spend more clearing them than they save.
  const auto query = [&](int r) { return RayQuery(set.ray(r), camera); };
  Double4 horizon[kHalves] = {lanesOf(std::numeric_limits<double>::infinity()), lanesOf(std::numeric_limits<double>::infinity())};
  Double4 reach[kHalves] = {horizon[0], horizon[1]};

  const auto leaf = [&](std::uint32_t first, std::uint16_t leafCount, int met, const LeafBox& box) HSR_AVX2 {
    for (int half = 0; half < kHalves; ++half) {
      const int active = raysInHalf(met, half);
      if (active == 0) continue;
      const ShearedRay<Double4>& shear = *set.shear[half];
      const WoopBounds<Double4> boxBounds = woop::edgeBoundsOverBox(shear, dvec3(box.low(0), box.low(1), box.low(2)),
                                                                    dvec3(box.high(0), box.high(1), box.high(2)));
      counters.triangleTests += std::popcount(unsigned(active)) * leafCount;
      for (std::uint32_t slot = first; slot < first + leafCount; ++slot) {
        const PackedTriangle& tri = triangles_[slot];
        // boundedHitInDouble, lane by lane: surely missed or beyond the horizon, a sure
        // hit between the near and far planes, or left undecided for the exact test.
        // Most rays miss most triangles, which the box's bounds already show.
        const WoopTerms<Double4> terms = woopTerms(shear, tri.a, tri.b, tri.c);
        if ((active & ~laneBits(insideWithBounds(terms, boxBounds).no)) == 0) continue;
        const WoopBounds<Double4> bounds = woopBounds(shear, tri.a, tri.b, tri.c, terms);
        const Decided<Double4> inside = insideWithBounds(terms, bounds);
        const Decided<Double4> inRange = set.view[half]->inRange(bounds.t, bounds.tBound);
        const Mask4 beyond = bounds.t - bounds.tBound > horizon[half];
        const int sure = active & laneBits(inside.yes & ~beyond & inRange.yes);
        const int missed = laneBits(inside.no | beyond | (inside.yes & inRange.no));
        const int undecided = active & ~missed & ~sure;
        for (int bits = sure | undecided; bits != 0; bits &= bits - 1) {
          const int lane = std::countr_zero(unsigned(bits)), r = 4 * half + lane;
          search[r].offer({bounds.t[lane], bounds.tBound[lane], (sure >> lane & 1) != 0, false, (undecided >> lane & 1) != 0}, slot);
        }
        // The searches' horizons, as offer() lowers them: a sure hit takes its upper end
        // t + bound where that is lower (a hit beyond the horizon was missed above, and
        // an undecided one lowers nothing until it is decided). In lanes, not lane by
        // lane: the next triangle reads the horizons as a vector.
        horizon[half] = laneMask4(sure) ? smaller(horizon[half], bounds.t + bounds.tBound) : horizon[half];
      }
      reach[half] = horizon[half] * NearestHitSearch::kEntryWidening;
    }
  };
  counters.nodesVisited += visitLeaves(*wideBvh_, packet, (1 << count) - 1, reach, leaf);
  double originDistance[RayPacket::kRays], slope[RayPacket::kRays];
  set.viewDistances(originDistance, slope);
  for (int r = 0; r < count; ++r)
    hits[r] = search[r].nearest(triangles_, counters, [&](double t) { return originDistance[r] + t * slope[r]; }, [&] { return query(r); });
  return true;
}

HSR_AVX2 bool SurfaceReference::candidateRun(const CameraTransform& camera, int y, int x, int count, const PackedTriangle& candidate,
                                             ReferenceHit* hits, Counters& counters) const {
  PacketRays set;
  if (!set.setUp(camera, y, x, count)) return false;
  // tracePacket's test of one triangle, for its one candidate: every ray must meet it
  // surely, between the near and far planes; the hit's parameter is then the one the
  // search records.
  double t[RayPacket::kRays];
  for (int half = 0; half * 4 < count; ++half) {
    const WoopTerms<Double4> terms = woopTerms(*set.shear[half], candidate.a, candidate.b, candidate.c);
    const WoopBounds<Double4> bounds = woopBounds(*set.shear[half], candidate.a, candidate.b, candidate.c, terms);
    const Mask4 sure = insideWithBounds(terms, bounds).yes & set.view[half]->inRange(bounds.t, bounds.tBound).yes;
    const int wanted = raysInHalf((1 << count) - 1, half);
    counters.triangleTests += std::popcount(unsigned(wanted));
    if ((laneBits(sure) & wanted) != wanted) return false;
    __builtin_memcpy(t + 4 * half, &bounds.t, sizeof(Double4));
  }
  double originDistance[RayPacket::kRays], slope[RayPacket::kRays];
  set.viewDistances(originDistance, slope);
  for (int r = 0; r < count; ++r) hits[r] = {candidate.id, originDistance[r] + t[r] * slope[r], false, false};
  return true;
}

}  // namespace hsr
