// How far rounding can move what the object-space tests measure, so that the few
// tolerances the suite keeps are relative to the magnitude of their operands, with a
// reason, rather than absolute numbers.
//
// Every sign that decides visibility is exact (renderer/geometry/predicates). What rounding still
// touches is the input to those signs: a model's faces that are coplanar as modelled are
// coplanar in world space only up to the rounding of their placement
// (Instance::placementRounding) and of the file they came from (Mesh::statedRounding).
// heightUncertainty bounds how far that rounding can move a point's height above a
// plane; RoundedPlane says whether a point lies on a plane up to that rounding.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/geometry/predicates.hpp"
#include "renderer/util/math.hpp"

namespace hsr {

// u = 2^-53, the unit roundoff of double precision: one rounding moves a value x by at
// most u |x|.
inline constexpr double kUnitRoundoff = 0x1p-53;

// Higham's gamma_n = n u / (1 - n u): n roundings in a row (a sum of n products, say)
// move the result by at most gamma_n times the sum of the terms' magnitudes.
constexpr double roundingGamma(int n) { return n * kUnitRoundoff / (1 - n * kUnitRoundoff); }

// How much the height of v above the plane through a, b and c can differ from the same
// height for the unrounded points, when each coordinate of a, b and c may be off by up to
// planeRounding and each of v's by pointRounding, plus the rounding of computing the
// height in double precision. First order, doubled for the rest:
//   - v moving by d changes the height by at most |d|;
//   - a corner moving by d along the normal moves the plane under v by the corner's
//     barycentric weight at v's foot times d, so the plane's corners count with the sum
//     of |weights|, which is 1 over the triangle and grows with v's distance from it;
//   - computing n . (v - a) / |n| rounds by a few ulps of |v - a| / sin(corner angle).
// Infinite for a triangle with no plane (zero area).
inline double heightUncertainty(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& v, double planeRounding,
                                double pointRounding) {
  const dvec3 n = glm::cross(b - a, c - a);
  const double nn = glm::dot(n, n);
  if (!(nn > 0)) return std::numeric_limits<double>::infinity();
  const double weights = std::abs(glm::dot(glm::cross(b - v, c - v), n)) + std::abs(glm::dot(glm::cross(c - v, a - v), n)) +
                         std::abs(glm::dot(glm::cross(a - v, b - v), n));
  const double lever = weights / nn;
  const double arithmetic = 8 * kUnitRoundoff * glm::length(v - a) * glm::length(b - a) * glm::length(c - a) / std::sqrt(nn);
  return 2 * std::sqrt(3.0) * (pointRounding + planeRounding * lever) + arithmetic;
}

// A triangle's plane, ready to say of many points whether they lie on it up to the
// rounding their coordinates carry, in two senses:
//   holds: within kRoundings times that rounding (the plane's and the point's), measured
//     by the exact height (ExactPredicates::orient3dValue). Tight, for shortcuts that skip
//     exact work: the painter's "coplanar, do not split" and Appel's "touching, not
//     crossing". Eight: a lever of up to three for the plane's corners, doubled for what
//     first order leaves out. No more: a plane through a sliver is known only roughly,
//     and taking points farther out as on it would leave a polygon that crosses the plane
//     unsplit, painted in the wrong order over pixels the rounding cannot explain.
//   couldHold: within heightUncertainty, the lever of the point's distance from the
//     triangle included. Generous, for accepting what was meant: Roberts takes a body as
//     convex when every vertex could lie on or inside every face plane.
class RoundedPlane {
 public:
  static constexpr double kRoundings = 8;

  // Each coordinate of a, b and c may be off by up to `rounding`.
  RoundedPlane(const dvec3& a, const dvec3& b, const dvec3& c, double rounding)
      : a_(a), b_(b), c_(c), rounding_(rounding), normalLength_(glm::length(glm::cross(b - a, c - a))) {}

  // False for a triangle with no plane.
  bool holds(const dvec3& v, double pointRounding) const {
    ExactPredicates exact;
    return holdsHeight(exact.orient3dValue(a_, b_, c_, v), pointRounding);
  }
  // The same for a point whose ExactPredicates::orient3dValue against the triangle's
  // corners the caller has already (a signed height times |(b - a) x (c - a)|).
  bool holdsHeight(double orient3dValue, double pointRounding) const {
    return normalLength_ > 0 && std::abs(orient3dValue) <= kRoundings * (rounding_ + pointRounding) * normalLength_;
  }
  bool couldHold(const dvec3& v, double pointRounding) const {
    return normalLength_ > 0 &&
           std::abs(glm::dot(glm::cross(b_ - a_, c_ - a_), v - a_)) <= heightUncertainty(a_, b_, c_, v, rounding_, pointRounding) * normalLength_;
  }

 private:
  dvec3 a_, b_, c_;
  double rounding_, normalLength_;
};

}  // namespace hsr
