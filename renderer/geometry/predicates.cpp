#include "renderer/geometry/predicates.hpp"

#include <cmath>
#include <limits>

#include "renderer/geometry/exact.hpp"

namespace hsr {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon() / 2;  // 2^-53: half an ulp of 1
// Shewchuk's bounds on the rounding error of the double-precision determinants, as a
// multiple of the "permanent" (the same sum with every term made non-negative).
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;
// Those bounds, and the expansions below, hold while no product of two or three
// coordinate differences underflows or overflows: differences between 2^-290 and 2^290
// (or zero) keep every product, and every error term the expansions split off, inside the
// normal doubles. Points closer together or farther apart than that go straight to the
// exact stage.
constexpr double kSmallestDifference = 0x1p-290, kLargestDifference = 0x1p290;
bool inSafeRange(double difference) {
  const double size = std::abs(difference);
  return size == 0 || (size >= kSmallestDifference && size <= kLargestDifference);
}
bool inSafeRange(const dvec3& difference) { return inSafeRange(difference.x) && inSafeRange(difference.y) && inSafeRange(difference.z); }

// Whether no difference of these points' coordinates can overflow (each at most 2^1020
// in magnitude, so a difference is at most 2^1021): beyond that even b - a could be
// infinite, and such inputs go straight to the exact stage, as the floating-point traps
// of the debug and sanitizer builds demand of every step, used or not.
bool differencesFit(std::initializer_list<dvec3> points) {
  constexpr double kLargestCoordinate = 0x1p1020;
  for (const dvec3& point : points)
    for (int i = 0; i < 3; ++i)
      if (!(std::abs(point[i]) <= kLargestCoordinate)) return false;
  return true;
}

// The second stage, exact in double precision when the coordinate differences are
// (always so when the points are close, or on a grid, as modelled coplanar faces often
// are): a - b, if the subtraction rounded nothing.
bool exactDifference(double a, double b, double& difference) {
  difference = a - b;
  // Knuth's two-sum, for a difference: the rounding error is zero exactly when nothing was lost.
  const double bVirtual = a - difference, aVirtual = difference + bVirtual;
  return (a - aVirtual) + (bVirtual - b) == 0;
}

// The exact sign of a sum of products of three doubles, sum over i of sign_i * x_i y_i z_i:
// each product is split exactly into four doubles with fused multiply-adds, and the
// terms are accumulated into a nonoverlapping expansion (Shewchuk's grow-expansion),
// whose sign is that of its largest nonzero component.
class ExactSum {
 public:
  void addProduct(double x, double y, double z) {
    const double xy = x * y, xyError = std::fma(x, y, -xy);
    for (const double factor : {xy, xyError}) {
      const double product = factor * z;
      add(product);
      add(std::fma(factor, z, -product));
    }
  }
  int sign() const {
    for (int i = count_ - 1; i >= 0; --i)
      if (terms_[i] != 0) return terms_[i] > 0 ? 1 : -1;
    return 0;
  }
  // The sum, rounded: the components do not overlap and grow, so adding them smallest
  // first loses less than an ulp of the result.
  double value() const {
    double sum = 0;
    for (int i = 0; i < count_; ++i) sum += terms_[i];
    return sum;
  }

 private:
  void add(double value) {
    for (int i = 0; i < count_; ++i) {
      const double sum = value + terms_[i];
      const double bVirtual = sum - value, aVirtual = sum - bVirtual;
      terms_[i] = (value - aVirtual) + (terms_[i] - bVirtual);
      value = sum;
    }
    terms_[count_++] = value;
  }
  double terms_[24] = {};
  int count_ = 0;
};

}  // namespace

int ExactPredicates::orient2d(const dvec3& a, const dvec3& b, const dvec3& c) {
  ++evaluations;
  if (differencesFit({a, b, c})) {
    const dvec3 u = b - a, v = c - a;
    if (inSafeRange(dvec3(u.x, u.y, v.x)) && inSafeRange(v.y)) {
      const double left = u.x * v.y, right = u.y * v.x;
      const double det = left - right;
      if (std::abs(det) > kOrient2dBound * (std::abs(left) + std::abs(right))) return det > 0 ? 1 : -1;
      double bx, by, cx, cy;
      if (exactDifference(b.x, a.x, bx) && exactDifference(b.y, a.y, by) && exactDifference(c.x, a.x, cx) &&
          exactDifference(c.y, a.y, cy)) {
        ExactSum sum;
        sum.addProduct(bx, cy, 1);
        sum.addProduct(-by, cx, 1);
        return sum.sign();
      }
    }
  }
  ++exactFallbacks;
  using Exact = ExactNumber<2>;  // a difference of products of two differences of doubles
  return ((Exact(b.x) - a.x) * (Exact(c.y) - a.y) - (Exact(b.y) - a.y) * (Exact(c.x) - a.x)).sign();
}

int ExactPredicates::orient3d(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d) {
  // A corner of the plane's own triangle (a mesh's shared vertices make this common):
  // the determinant is exactly zero, which no error bound can certify.
  if (d == a || d == b || d == c) {
    ++evaluations;
    return 0;
  }
  return orient3dOfVectors(a, b, c, d, true);
}

int ExactPredicates::facing(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& direction) {
  return orient3dOfVectors(a, b, c, direction, false);
}

double ExactPredicates::orient3dValue(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d) {
  if (d == a || d == b || d == c) {  // as in orient3d: exactly zero, which no bound certifies
    ++evaluations;
    return 0;
  }
  return orient3dDeterminant(a, b, c, d, true, 1e-12);
}

int ExactPredicates::orient3dOfVectors(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d, bool dIsPoint) {
  const double det = orient3dDeterminant(a, b, c, d, dIsPoint, 1.0);
  return det > 0 ? 1 : det < 0 ? -1 : 0;
}

// det[b - a, c - a, w], where w is d - a for a point d, or d itself for a direction (a
// direction carries no rounding of its own, so the orient3d bound covers both): the
// double evaluation when its error bound is under `relativeBound` of it, else the exact
// value rounded to double, whose sign is the exact sign.
double ExactPredicates::orient3dDeterminant(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d, bool dIsPoint,
                                            double relativeBound) {
  ++evaluations;
  const bool fits = differencesFit({a, b, c, d});
  const dvec3 u = fits ? b - a : dvec3(0), v = fits ? c - a : dvec3(0), w = !fits ? dvec3(0) : dIsPoint ? d - a : d;
  const bool safe = fits && inSafeRange(u) && inSafeRange(v) && inSafeRange(w);
  if (safe) {
    const double m0 = v.y * w.z, m1 = v.z * w.y, m2 = v.x * w.z, m3 = v.z * w.x, m4 = v.x * w.y, m5 = v.y * w.x;
    const double det = u.x * (m0 - m1) - u.y * (m2 - m3) + u.z * (m4 - m5);
    const double permanent = std::abs(u.x) * (std::abs(m0) + std::abs(m1)) + std::abs(u.y) * (std::abs(m2) + std::abs(m3)) +
                             std::abs(u.z) * (std::abs(m4) + std::abs(m5));
    if (kOrient3dBound * permanent < relativeBound * std::abs(det)) return det;
  }
  return orient3dExactly(a, b, c, d, dIsPoint, safe);
}

double ExactPredicates::orient3dExactly(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d, bool dIsPoint, bool safe) {
  dvec3 eu(0), ev(0), ew = d;
  bool exact = safe;
  for (int i = 0; i < 3 && exact; ++i) {
    exact &= exactDifference(b[i], a[i], eu[i]) && exactDifference(c[i], a[i], ev[i]);
    if (dIsPoint) exact &= exactDifference(d[i], a[i], ew[i]);
  }
  if (exact) {
    ExactSum sum;
    sum.addProduct(eu.x, ev.y, ew.z);
    sum.addProduct(-eu.x, ev.z, ew.y);
    sum.addProduct(-eu.y, ev.x, ew.z);
    sum.addProduct(eu.y, ev.z, ew.x);
    sum.addProduct(eu.z, ev.x, ew.y);
    sum.addProduct(-eu.z, ev.y, ew.x);
    return sum.value();
  }
  ++exactFallbacks;
  using Exact = ExactNumber<3>;  // products of three differences of doubles
  Exact exactU[3], exactV[3], exactW[3];
  for (int i = 0; i < 3; ++i) {
    exactU[i] = Exact(b[i]) - a[i];
    exactV[i] = Exact(c[i]) - a[i];
    exactW[i] = dIsPoint ? Exact(d[i]) - a[i] : Exact(d[i]);
  }
  const Exact value = exactU[0] * (exactV[1] * exactW[2] - exactV[2] * exactW[1]) - exactU[1] * (exactV[0] * exactW[2] - exactV[2] * exactW[0]) +
                      exactU[2] * (exactV[0] * exactW[1] - exactV[1] * exactW[0]);
  // Rounded toward zero; a value nonzero but below the smallest double keeps its sign as
  // that smallest double (the sign is what orient3d returns).
  const double rounded = value.truncated();
  return rounded != 0 || value.isZero() ? rounded : value.sign() * std::numeric_limits<double>::denorm_min();
}

}  // namespace hsr
