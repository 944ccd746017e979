// The exact reference's ray-triangle test (renderer/reference/reference.hpp): the
// watertight test of Woop, Benthin and Wald (2013), section 4, with a forward error bound
// on each of its values, written once for the arithmetics it runs in:
//   double     the reference's test of one ray;
//   Double4    four rays at once, a ray per lane (renderer/util/simd.hpp; the reference's
//              packets, reference_packets.cpp): the same operations in the same order,
//              so the same values as four single rays, bit for bit;
// and once more, exactly, for the fall-back where a bound leaves a decision open
// (exactTerms, below): the same formulas with the shear's division by the direction's
// dominant component carried as a common denominator, so that sums and products of
// doubles (renderer/geometry/exact.hpp) give the exact values of Woop's terms.
// A decision taken against a bound is a bool for one ray and a Mask4 for four lanes
// (Truth<Number>); `a ? b : c` chooses by it either way. No function here takes or
// returns a Double4 by value to or from AVX2 code: only structs and references cross;
// the small ones that return one are always inlined into their caller (a call left in an
// unoptimized build would pass it the baseline's way, and crash).
// The ones called per triangle are always inlined (HSR_INLINE): compiled as a function
// of their own, the four-lane form would get the baseline's two-lane instructions.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "renderer/geometry/camera.hpp"
#include "renderer/geometry/exact.hpp"
#include "renderer/geometry/rounding.hpp"
#include "renderer/util/simd.hpp"

namespace hsr::woop {

template <typename Number>
using Truth = decltype(std::declval<Number>() < std::declval<Number>());

HSR_INLINE double magnitudeOf(double x) { return std::abs(x); }
HSR_INLINE Double4 magnitudeOf(const Double4& x) { return Double4(Mask4(x) & 0x7FFF'FFFF'FFFF'FFFF); }  // the sign bit cleared

// Section 4's per-ray set-up: kz is the dominant axis of the direction, and the shear
// (sx, sy, sz) maps the ray onto the +z axis from the origin. Swapping kx and ky when the
// ray runs down kz keeps the winding.
template <typename Number>
struct ShearedRay {
  int kx, ky, kz;
  std::array<Number, 3> origin;
  Number sx, sy, sz;

  static std::array<int, 3> axesOf(const dvec3& direction) {
    const dvec3 size = glm::abs(direction);
    const int kz = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (direction[kz] < 0) std::swap(kx, ky);
    return {kx, ky, kz};
  }

  // Rays whose directions share the axes (axesOf): one, or four in lanes.
  ShearedRay(const std::array<int, 3>& axes, const std::array<Number, 3>& rayOrigin, const std::array<Number, 3>& direction)
      : ShearedRay(axes, rayOrigin, direction, 1.0 / direction[axes[2]]) {}
  // The same, given sz = 1 / direction[kz]: a packet's slab tests have the directions'
  // inverses already, which saves a division.
  ShearedRay(const std::array<int, 3>& axes, const std::array<Number, 3>& rayOrigin, const std::array<Number, 3>& direction,
             const Number& inverseDz)
      : kx(axes[0]),
        ky(axes[1]),
        kz(axes[2]),
        origin(rayOrigin),
        sx(direction[kx] / direction[kz]),
        sy(direction[ky] / direction[kz]),
        sz(inverseDz) {}
  explicit ShearedRay(const Ray& ray)
      : ShearedRay(axesOf(ray.direction), {Number(ray.origin[0]), Number(ray.origin[1]), Number(ray.origin[2])},
                   {Number(ray.direction[0]), Number(ray.direction[1]), Number(ray.direction[2])}) {}
};

// The test's values for one triangle (section 4, steps 2-5): u, v, w are the edge
// functions of the sheared triangle at the ray (the scaled barycentrics); the ray
// meets the triangle when they share a sign and det = u + v + w is not 0, at
// parameter t = scaledT / det.
template <typename Number>
struct WoopTerms {
  Number u, v, w, det, scaledT;
};

template <typename Number>
HSR_INLINE WoopTerms<Number> woopTerms(const ShearedRay<Number>& ray, const dvec3& a, const dvec3& b, const dvec3& c) {
  std::array<Number, 3> A, B, C;
  for (int i = 0; i < 3; ++i) {
    A[i] = a[i] - ray.origin[i];
    B[i] = b[i] - ray.origin[i];
    C[i] = c[i] - ray.origin[i];
  }
  const Number ax = A[ray.kx] - ray.sx * A[ray.kz], ay = A[ray.ky] - ray.sy * A[ray.kz];
  const Number bx = B[ray.kx] - ray.sx * B[ray.kz], by = B[ray.ky] - ray.sy * B[ray.kz];
  const Number cx = C[ray.kx] - ray.sx * C[ray.kz], cy = C[ray.ky] - ray.sy * C[ray.kz];
  WoopTerms<Number> terms;
  terms.u = cx * by - cy * bx;
  terms.v = ax * cy - ay * cx;
  terms.w = bx * ay - by * ax;
  terms.det = terms.u + terms.v + terms.w;
  terms.scaledT = terms.u * (ray.sz * A[ray.kz]) + terms.v * (ray.sz * B[ray.kz]) + terms.w * (ray.sz * C[ray.kz]);
  return terms;
}

// Forward error bounds of the double-precision terms against the exact values of the
// same formulas. Each sheared coordinate (a translation, a product with the rounded
// shear, a subtraction) is within 4u of its magnitude bound m = |x| + |s||z|; each
// edge function adds two products and a subtraction. The constants below round those
// counts up generously: a loose bound costs a rare extra exact test, a tight one is a bug.
// The error bounds of the edge functions u, v, w and of det; and the hit parameter
// t = scaledT / det with its bound tBound, computed only where |det| is surely above 0 (a
// ray surely not parallel to the triangle). Elsewhere no hit can be certain: t is 0 and
// tBound infinite, and nothing divides by zero.
template <typename Number>
struct WoopBounds {
  Number u, v, w, det;
  Number t, tBound;
};

template <typename Number>
HSR_INLINE WoopBounds<Number> woopBounds(const ShearedRay<Number>& ray, const dvec3& a, const dvec3& b, const dvec3& c, const WoopTerms<Number>& terms) {
  struct Magnitude {
    Number x, y, z;
  };
  const auto magnitude = [&](const dvec3& p) {
    std::array<Number, 3> q;
    for (int i = 0; i < 3; ++i) q[i] = p[i] - ray.origin[i];
    const Number along = magnitudeOf(q[ray.kz]);
    return Magnitude{magnitudeOf(q[ray.kx]) + magnitudeOf(ray.sx) * along, magnitudeOf(q[ray.ky]) + magnitudeOf(ray.sy) * along,
                     magnitudeOf(ray.sz) * along};
  };
  const Magnitude A = magnitude(a), B = magnitude(b), C = magnitude(c);
  constexpr double edge = 16 * kUnitRoundoff, sum = 4 * kUnitRoundoff;
  WoopBounds<Number> bounds;
  bounds.u = edge * (C.x * B.y + C.y * B.x);
  bounds.v = edge * (A.x * C.y + A.y * C.x);
  bounds.w = edge * (B.x * A.y + B.y * A.x);
  const Number absU = magnitudeOf(terms.u), absV = magnitudeOf(terms.v), absW = magnitudeOf(terms.w);
  bounds.det = bounds.u + bounds.v + bounds.w + sum * (absU + absV + absW);
  const Number scaledT = edge * ((absU + bounds.u) * A.z + (absV + bounds.v) * B.z + (absW + bounds.w) * C.z) +
                         bounds.u * A.z + bounds.v * B.z + bounds.w * C.z;
  const Number absDet = magnitudeOf(terms.det);
  // Where |det| is not surely above 0 the divisions below divide by 1 instead, and
  // their results are not used.
  const Truth<Number> surelyNotParallel = absDet > bounds.det;
  const Number one = broadcast<Number>(1);
  const Number t = terms.scaledT / (surelyNotParallel ? terms.det : one);
  const Number tBound = (scaledT + magnitudeOf(t) * bounds.det) / (surelyNotParallel ? absDet - bounds.det : one) + sum * magnitudeOf(t);
  bounds.t = surelyNotParallel ? t : broadcast<Number>(0);
  bounds.tBound = surelyNotParallel ? tBound : broadcast<Number>(std::numeric_limits<double>::infinity());
  return bounds;
}

// Bounds on u, v and w for every triangle inside the box [low, high], larger than each
// triangle's own (woopBounds'): the farthest the box reaches from the ray's origin along
// each axis bounds each vertex's magnitude there, and every operation woopBounds takes
// them through is monotonic, so the same operations on the larger values give a bound
// at least as large. A sign decided against it is decided against the triangle's own
// bounds too, at the cost of a few operations per box instead of per triangle. (Only u,
// v and w are set.)
template <typename Number>
HSR_INLINE WoopBounds<Number> edgeBoundsOverBox(const ShearedRay<Number>& ray, const dvec3& low, const dvec3& high) {
  std::array<Number, 3> farthest;
  for (int i = 0; i < 3; ++i) {
    const Number fromLow = magnitudeOf(low[i] - ray.origin[i]), fromHigh = magnitudeOf(high[i] - ray.origin[i]);
    farthest[i] = fromLow > fromHigh ? fromLow : fromHigh;
  }
  const Number x = farthest[ray.kx] + magnitudeOf(ray.sx) * farthest[ray.kz], y = farthest[ray.ky] + magnitudeOf(ray.sy) * farthest[ray.kz];
  WoopBounds<Number> bounds;
  bounds.u = bounds.v = bounds.w = 16 * kUnitRoundoff * (x * y + y * x);
  return bounds;
}

// The test's values in exact arithmetic, for one ray. With d the direction and kz its
// dominant axis, each corner P's sheared coordinates are x = P'[kx] - (d[kx] / d[kz])
// P'[kz] and y likewise, where P' = P - origin: d[kz] x and d[kz] y are sums of products
// of two doubles. So the edge functions' exact values are u = U / d[kz]^2 (and v, w),
// with U = (d[kz] x_c)(d[kz] y_b) - (d[kz] y_c)(d[kz] x_b) a polynomial of degree four in
// doubles, of the same sign; det = (U + V + W) / d[kz]^2; and the hit's parameter
//   t = scaledT / det = (U A'[kz] + V B'[kz] + W C'[kz]) / (d[kz] (U + V + W)),
// a quotient of two polynomials of degree five, kept as they are: t is compared by
// cross-multiplying (degree ten, the most any decision needs: ExactNumber<10>) and
// rounded toward zero only when it becomes the hit's distance.
using Exact = ExactNumber<10>;

// A hit's parameter, numerator over a positive denominator.
struct ExactParameter {
  Exact numerator, denominator;

  friend int compare(const ExactParameter& a, const ExactParameter& b) {
    return (a.numerator * b.denominator - b.numerator * a.denominator).sign();
  }
  friend bool operator<(const ExactParameter& a, const ExactParameter& b) { return compare(a, b) < 0; }
  friend bool operator==(const ExactParameter& a, const ExactParameter& b) { return compare(a, b) == 0; }
  // The sign of t - value.
  int compareWith(double value) const { return (numerator - Exact(value) * denominator).sign(); }
  double truncated() const { return truncatedQuotient(numerator, denominator); }
};

struct ExactTerms {
  Exact u, v, w, det;   // d[kz]^2 times Woop's u, v, w and det: the same signs
  ExactParameter t;     // meaningful where det != 0
};

inline ExactTerms exactTerms(const Ray& ray, const dvec3& a, const dvec3& b, const dvec3& c) {
  const std::array<int, 3> axes = ShearedRay<double>::axesOf(ray.direction);
  const int kx = axes[0], ky = axes[1], kz = axes[2];
  const double dz = ray.direction[kz];
  struct Sheared {
    Exact x, y, z;  // d[kz] times the sheared x and y; z the corner's offset along kz
  };
  const auto sheared = [&](const dvec3& p) {
    const Exact px = Exact(p[kx]) - ray.origin[kx], py = Exact(p[ky]) - ray.origin[ky], pz = Exact(p[kz]) - ray.origin[kz];
    return Sheared{px * dz - Exact(ray.direction[kx]) * pz, py * dz - Exact(ray.direction[ky]) * pz, pz};
  };
  const Sheared A = sheared(a), B = sheared(b), C = sheared(c);
  ExactTerms terms;
  terms.u = C.x * B.y - C.y * B.x;
  terms.v = A.x * C.y - A.y * C.x;
  terms.w = B.x * A.y - B.y * A.x;
  terms.det = terms.u + terms.v + terms.w;
  terms.t.numerator = terms.u * A.z + terms.v * B.z + terms.w * C.z;
  terms.t.denominator = terms.det * dz;
  if (terms.t.denominator.sign() < 0) terms.t.numerator = -terms.t.numerator, terms.t.denominator = -terms.t.denominator;
  return terms;
}

// A decision taken against bounds: surely yes, surely no, or neither (left to the
// exact arithmetic).
template <typename Number>
struct Decided {
  Truth<Number> yes, no;
};

// Inside when u, v, w share a sign (zero counts as either: the edge belongs to both
// triangles that share it, which is what makes the test watertight) and det != 0.
inline bool inside(const ExactTerms& terms) {
  const int u = terms.u.sign(), v = terms.v.sign(), w = terms.w.sign();
  const bool allNonNegative = u >= 0 && v >= 0 && w >= 0;
  const bool allNonPositive = u <= 0 && v <= 0 && w <= 0;
  return (allNonNegative || allNonPositive) && !terms.det.isZero();
}

// `inside`, decided by the bounds where they allow.
template <typename Number>
HSR_INLINE Decided<Number> insideWithBounds(const WoopTerms<Number>& terms, const WoopBounds<Number>& bounds) {
  const Truth<Number> positiveU = terms.u > bounds.u, positiveV = terms.v > bounds.v, positiveW = terms.w > bounds.w;
  const Truth<Number> negativeU = terms.u < -bounds.u, negativeV = terms.v < -bounds.v, negativeW = terms.w < -bounds.w;
  const Truth<Number> somePositive = positiveU | positiveV | positiveW, someNegative = negativeU | negativeV | negativeW;
  const Truth<Number> yes = (positiveU & positiveV & positiveW) | (negativeU & negativeV & negativeW), no = somePositive & someNegative;
  return {yes, no};
}

// The view distance of the point at parameter t of a ray, distance(t) = originDistance
// + t * slope, with its error bound: whether a hit lies between the near and far planes.
template <typename Number>
struct ViewDistance {
  Number originDistance, slope, originDistanceBound, slopeBound;
  double near, far;

  // One ray, or four in lanes.
  ViewDistance(const CameraTransform& camera, const std::array<Number, 3>& origin, const std::array<Number, 3>& direction)
      : near(camera.camera().near), far(camera.camera().far) {
    const dvec3& eye = camera.camera().eye;
    const dvec3& forward = camera.forward();
    const dvec3 f = glm::abs(forward);
    const std::array<Number, 3> fromEye = {origin[0] - eye.x, origin[1] - eye.y, origin[2] - eye.z};
    // glm::dot's sum, as it takes it: ((x + y) + z).
    originDistance = fromEye[0] * forward.x + fromEye[1] * forward.y + fromEye[2] * forward.z;
    slope = direction[0] * forward.x + direction[1] * forward.y + direction[2] * forward.z;
    originDistanceBound = 5 * kUnitRoundoff * (magnitudeOf(fromEye[0]) * f.x + magnitudeOf(fromEye[1]) * f.y + magnitudeOf(fromEye[2]) * f.z);
    slopeBound = 4 * kUnitRoundoff * (magnitudeOf(direction[0]) * f.x + magnitudeOf(direction[1]) * f.y + magnitudeOf(direction[2]) * f.z);
  }

  // Is the hit at t (within tBound) between the near and far planes?
  HSR_INLINE Decided<Number> inRange(const Number& t, const Number& tBound) const {
    const Number d = originDistance + t * slope;
    const Number bound = originDistanceBound + magnitudeOf(t) * slopeBound + magnitudeOf(slope) * tBound +
                         3 * kUnitRoundoff * (magnitudeOf(originDistance) + magnitudeOf(t * slope));
    const Truth<Number> yes = (d - bound >= near) & (d + bound <= far), no = (d + bound < near) | (d - bound > far);
    return {yes, no};
  }
};

}  // namespace hsr::woop
