#include "renderer/predicates.hpp"

#include <cmath>
#include <limits>

#include <gmpxx.h>

namespace hsr {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon() / 2;  // 2^-53: half an ulp of 1
// Shewchuk's bounds on the rounding error of the double-precision determinants, as a
// multiple of the "permanent" (the same sum with every term made non-negative).
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;

int signOf(const mpq_class& value) { return sgn(value); }

}  // namespace

int ExactPredicates::orient2d(const dvec3& a, const dvec3& b, const dvec3& c) {
  ++evaluations;
  const double left = (b.x - a.x) * (c.y - a.y), right = (b.y - a.y) * (c.x - a.x);
  const double det = left - right;
  if (std::abs(det) > kOrient2dBound * (std::abs(left) + std::abs(right))) return det > 0 ? 1 : -1;
  ++exactFallbacks;
  const mpq_class exact = (mpq_class(b.x) - a.x) * (mpq_class(c.y) - a.y) - (mpq_class(b.y) - a.y) * (mpq_class(c.x) - a.x);
  return signOf(exact);
}

int ExactPredicates::orient3d(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d) {
  return orient3dOfVectors(a, b, c, d, true);
}

int ExactPredicates::facing(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& direction) {
  return orient3dOfVectors(a, b, c, direction, false);
}

// det[b - a, c - a, w], where w is d - a for a point d, or d itself for a direction.
// A direction carries no rounding of its own, so the orient3d bound covers both.
int ExactPredicates::orient3dOfVectors(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d, bool dIsPoint) {
  ++evaluations;
  const dvec3 u = b - a, v = c - a, w = dIsPoint ? d - a : d;
  const double m0 = v.y * w.z, m1 = v.z * w.y, m2 = v.x * w.z, m3 = v.z * w.x, m4 = v.x * w.y, m5 = v.y * w.x;
  const double det = u.x * (m0 - m1) - u.y * (m2 - m3) + u.z * (m4 - m5);
  const double permanent = std::abs(u.x) * (std::abs(m0) + std::abs(m1)) + std::abs(u.y) * (std::abs(m2) + std::abs(m3)) +
                           std::abs(u.z) * (std::abs(m4) + std::abs(m5));
  if (std::abs(det) > kOrient3dBound * permanent) return det > 0 ? 1 : -1;
  ++exactFallbacks;
  mpq_class eu[3], ev[3], ew[3];
  for (int i = 0; i < 3; ++i) {
    eu[i] = mpq_class(b[i]) - a[i];
    ev[i] = mpq_class(c[i]) - a[i];
    ew[i] = dIsPoint ? mpq_class(d[i]) - a[i] : mpq_class(d[i]);
  }
  const mpq_class exact = eu[0] * (ev[1] * ew[2] - ev[2] * ew[1]) - eu[1] * (ev[0] * ew[2] - ev[2] * ew[0]) +
                          eu[2] * (ev[0] * ew[1] - ev[1] * ew[0]);
  return signOf(exact);
}

}  // namespace hsr
