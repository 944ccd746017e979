// The exact reference's search for the nearest hit of one ray (renderer/reference/reference.cpp,
// and its packets, reference_packets.cpp): each triangle decided in double precision
// where its error bounds allow and exactly where they do not, and the nearest of the
// hits decided exactly where their depths lie within each other's bounds.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "renderer/reference/bounded_woop.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/error.hpp"

namespace hsr::reference_search {

using woop::Decided;
using woop::ShearedRay;
using woop::WoopBounds;
using woop::WoopTerms;
using woop::insideWithBounds;
using woop::woopBounds;
using woop::woopTerms;

enum class Certainty { no, yes, unsure };
inline Certainty certainty(const Decided<double>& decided) { return decided.no ? Certainty::no : decided.yes ? Certainty::yes : Certainty::unsure; }

// Everything one ray needs: its shear, the view distance of the point at parameter t
// with its error bound (woop::ViewDistance), and the exact test where the bounds leave a
// decision open.
class RayQuery {
 public:
  RayQuery(const Ray& ray, const CameraTransform& camera)
      : ray_(ray),
        camera_(camera),
        shear_(ray),
        view_(camera, {ray.origin.x, ray.origin.y, ray.origin.z}, {ray.direction.x, ray.direction.y, ray.direction.z}) {}

  const ShearedRay<double>& shear() const { return shear_; }
  double distance(double t) const { return view_.originDistance + t * view_.slope; }
  // Is the hit at t (within tBound) between the near and far planes?
  Certainty inRange(double t, double tBound) const { return certainty(view_.inRange(t, tBound)); }

  // The exact hit parameter of a triangle, or nothing when the ray misses it or meets
  // it outside [near, far]: where the hit's view distance t s + o (s the direction's and
  // o the origin's distance along the view axis) lies between them, which with t = n / m
  // and m > 0 is near m <= n s + o m <= far m.
  std::optional<woop::ExactParameter> exactHit(const dvec3& a, const dvec3& b, const dvec3& c) const {
    const woop::ExactTerms terms = woop::exactTerms(ray_, a, b, c);
    if (!woop::inside(terms)) return std::nullopt;
    using woop::Exact;
    Exact slope, originDistance;
    for (int i = 0; i < 3; ++i) {
      slope += Exact(ray_.direction[i]) * camera_.forward()[i];
      originDistance += (Exact(ray_.origin[i]) - camera_.camera().eye[i]) * camera_.forward()[i];
    }
    const Exact& n = terms.t.numerator;
    const Exact& m = terms.t.denominator;
    const Exact distanceTimesM = n * slope + originDistance * m;
    if (distanceTimesM < Exact(view_.near) * m || distanceTimesM > Exact(view_.far) * m) return std::nullopt;
    return terms.t;
  }

 private:
  Ray ray_;
  const CameraTransform& camera_;
  ShearedRay<double> shear_;
  woop::ViewDistance<double> view_;
};

// One triangle against the ray, between the near and far planes: the hit's parameter t
// within +-bound, decided in double precision where the error bounds allow and exactly
// where they do not (`exact`, set whenever the exact test ran, hit or not). Or, from
// boundedHitInDouble, `undecided`: the bounds left it open, and a hit, if there is one,
// lies at t within +-bound.
struct BoundedHit {
  double t = 0, bound = 0;
  bool hit = false, exact = false, undecided = false;
};

// The exact test, where the bounds left the decision open.
inline BoundedHit exactBoundedHit(RayQuery& query, const PreparedScene::LeafTriangle& tri, SurfaceReference::Counters& counters) {
  ++counters.exactTriangleTests;
  const std::optional<woop::ExactParameter> exact = query.exactHit(tri.a, tri.b, tri.c);
  if (!exact) return {0, 0, false, true};
  const double rounded = exact->truncated();
  return {rounded, 2 * kUnitRoundoff * std::abs(rounded), true, true};
}

// The test in double precision alone. A hit whose t - bound lies beyond `beyond` is
// dropped (the nearest hit's search passes its horizon), whether or not the bounds
// decided it; an open decision comes back undecided, for the exact test.
inline BoundedHit boundedHitInDouble(const RayQuery& query, const PreparedScene::LeafTriangle& tri, double beyond,
                                     SurfaceReference::Counters& counters) {
  ++counters.triangleTests;
  const WoopTerms<double> terms = woopTerms(query.shear(), tri.a, tri.b, tri.c);
  const WoopBounds<double> bounds = woopBounds(query.shear(), tri.a, tri.b, tri.c, terms);
  const double t = bounds.t;
  Certainty hit = certainty(insideWithBounds(terms, bounds));
  if (hit == Certainty::no || t - bounds.tBound > beyond) return {};
  if (hit == Certainty::yes) {
    hit = query.inRange(t, bounds.tBound);
    if (hit == Certainty::no) return {};
    if (hit == Certainty::yes) return {t, bounds.tBound, true, false};
  }
  // A center on an edge, a grazing ray, or a hit on the near or far plane.
  return {t, bounds.tBound, false, false, true};
}

// The same, decided: exactly where the bounds left it open.
inline BoundedHit boundedHit(RayQuery& query, const PreparedScene::LeafTriangle& tri, double beyond, SurfaceReference::Counters& counters) {
  const BoundedHit hit = boundedHitInDouble(query, tri, beyond, counters);
  return hit.undecided ? exactBoundedHit(query, tri, counters) : hit;
}

// Candidates for the nearest hit: every hit whose interval [t - bound, t + bound] can
// still reach below the horizon, the smallest upper end t + bound seen so far. Usually
// one or two, held in place; more (coplanar faces overlapping) spill to the heap.
//
// A triangle the double-precision test left undecided waits, and is decided exactly
// only at the end, if its interval still reaches below the horizon then. Decided when
// met, whether it needed exact work would depend on the order the ray met its
// candidates (met before the wall in front of it, a ceiling's edge is decided exactly;
// met after, it is dropped), and the textbook traversal and the packets meet them in
// different orders. At the end, the horizon is the same whatever the order: so are
// the rays that need exact arithmetic.
class NearestHitSearch {
 public:
  // A node is skipped once its entry lies beyond the horizon, widened by the rounding of
  // the entry itself.
  static constexpr double kEntryWidening = 1 + 4 * kUnitRoundoff;

  double horizon() const { return horizon_; }
  bool usedExact() const { return usedExact_; }

  // A triangle's bounded hit (or miss, or undecided), slot its index in
  // PreparedScene::leafTriangles.
  HSR_INLINE void offer(const BoundedHit& hit, std::uint32_t slot) {
    if (hit.undecided) {
      if (hit.t - hit.bound <= horizon_) rare().undecided.push_back({hit.t, hit.bound, slot});
      return;
    }
    usedExact_ = usedExact_ || hit.exact;
    // A hit starting beyond the horizon can never be the nearest (the horizon only falls).
    if (!hit.hit || hit.t - hit.bound > horizon_) return;
    const bool lowered = hit.t + hit.bound < horizon_;
    if (lowered) horizon_ = hit.t + hit.bound;
    const Candidate candidate{hit.t, hit.bound, slot};
    if (!spilling_ && count_ < kInPlace) {
      inPlace_[std::size_t(count_++)] = candidate;
    } else {
      if (!spilling_) rare().spilled.assign(inPlace_.begin(), inPlace_.end()), spilling_ = true;
      rare_->spilled.push_back(candidate);
    }
    if (lowered) eraseBeyondHorizon();
  }

  // The nearest hit among the candidates: the one candidate, or the exact nearest of
  // several (every exact tie kept: the pixel is ambiguous, the lowest id recorded).
  // distance(t) is the ray's view distance at t; query() gives its RayQuery, asked for
  // only when the exact comparison is needed. `tied`, when given, receives the winner and
  // every triangle exactly tied with it, ascending (hsr why's certified answers).
  template <typename Distance, typename Query>
  ReferenceHit nearest(const std::vector<PreparedScene::LeafTriangle>& triangles, SurfaceReference::Counters& counters, Distance&& distance,
                       Query&& query, std::vector<std::uint32_t>* tied = nullptr) {
    decideUndecided(triangles, counters, query);
    ReferenceHit result;
    result.usedExact = usedExact_;
    eraseBeyondHorizon();
    const Candidate* first = spilling_ ? rare_->spilled.data() : inPlace_.data();
    const std::size_t count = spilling_ ? rare_->spilled.size() : std::size_t(count_);
    if (tied) tied->clear();
    if (count == 0) return result;
    std::uint32_t winner = triangles[first->slot].id;
    double winnerT = first->t;
    if (tied) tied->push_back(winner);
    if (count > 1) {
      // Depths too close for their bounds: compare exactly, and keep every exact tie.
      ++counters.exactComparisons;
      result.usedExact = true;
      auto&& exactQuery = query();
      std::optional<woop::ExactParameter> nearestT;
      int ties = 0;
      for (const Candidate* candidate = first; candidate != first + count; ++candidate) {
        const PreparedScene::LeafTriangle& tri = triangles[candidate->slot];
        const std::optional<woop::ExactParameter> t = exactQuery.exactHit(tri.a, tri.b, tri.c);
        HSR_CHECK(t.has_value());
        if (!nearestT || *t < *nearestT) {
          nearestT = t;
          winner = tri.id;
          ties = 1;
          if (tied) tied->assign(1, tri.id);
        } else if (*t == *nearestT) {
          winner = std::min(winner, tri.id);
          ++ties;
          if (tied) tied->push_back(tri.id);
        }
      }
      winnerT = nearestT->truncated();
      result.ambiguous = ties > 1;
      if (tied) std::sort(tied->begin(), tied->end());
    }
    result.id = winner;
    result.distance = distance(winnerT);
    return result;
  }

 private:
  struct Candidate {
    double t, bound;
    std::uint32_t slot;
  };
  // The undecided triangles whose interval reaches below the horizon, decided exactly,
  // nearest interval first (ties by slot: the same order for any traversal), each
  // lowering the horizon for the next.
  template <typename Query>
  void decideUndecided(const std::vector<PreparedScene::LeafTriangle>& triangles, SurfaceReference::Counters& counters, Query&& query) {
    if (!rare_ || rare_->undecided.empty()) return;
    std::vector<Candidate>& undecided = rare_->undecided;
    std::erase_if(undecided, [&](const Candidate& c) { return beyondHorizon(c); });
    if (undecided.empty()) return;
    std::sort(undecided.begin(), undecided.end(),
              [](const Candidate& a, const Candidate& b) { return std::pair(a.t - a.bound, a.slot) < std::pair(b.t - b.bound, b.slot); });
    auto&& exactQuery = query();
    for (const Candidate& candidate : undecided)
      if (!beyondHorizon(candidate)) offer(exactBoundedHit(exactQuery, triangles[candidate.slot], counters), candidate.slot);
    undecided.clear();
  }

  // Whether a candidate's interval starts beyond the horizon: it can never be the nearest.
  bool beyondHorizon(const Candidate& c) const { return c.t - c.bound > horizon_; }

  HSR_INLINE void eraseBeyondHorizon() {
    const auto beyond = [&](const Candidate& c) { return beyondHorizon(c); };
    if (spilling_) std::erase_if(rare_->spilled, beyond);
    else if (count_ > 1) count_ = int(std::remove_if(inPlace_.begin(), inPlace_.begin() + count_, beyond) - inPlace_.begin());
  }

  static constexpr int kInPlace = 8;
  double horizon_ = std::numeric_limits<double>::infinity();
  bool usedExact_ = false;
  std::array<Candidate, kInPlace> inPlace_;
  int count_ = 0;
  bool spilling_ = false;  // once more than kInPlace were held at once, they all live in rare_->spilled
  // What few rays need, apart, so that a search is cheap to make and drop (a packet makes
  // eight, and most rays hold one candidate and no undecided triangle).
  struct Rare {
    std::vector<Candidate> spilled;
    std::vector<Candidate> undecided;  // left open by the bounds, decided at the end
  };
  Rare& rare() {
    if (!rare_) rare_ = std::make_unique<Rare>();
    return *rare_;
  }
  std::unique_ptr<Rare> rare_;
};

}  // namespace hsr::reference_search
