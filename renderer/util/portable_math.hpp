// The elementary functions the suite computes with (sine, cosine, tangent, arctangent,
// exponential, hyperbolic tangent, logarithm, powers, hypotenuse), written here with +, -, *, / and sqrt
// alone, so that they give the same bits on every target. Each C library computes
// std::sin and the rest its own way (glibc differs between x86-64 and arm64, where it
// fuses multiply-adds; musl in WebAssembly differs from both): a vertex of a sphere, a
// rotated box or the camera's field of view would move by a unit in the last place from
// one machine to the next, and with it a pixel. IEEE 754 makes +, -, *, / and sqrt
// correctly rounded everywhere, and the build forbids fusing them (-ffp-contract=off), so
// these functions, built from them alone, are the same bits on every target.
//
// Each reduces its argument exactly or nearly (Cody and Waite's split constants) and
// sums a Taylor series far enough that the series' own error is below a hundredth of a
// unit in the last place; what remains is the rounding of a dozen operations
// (tests/renderer/util/portable_math_test.cpp measures it against glibc: the same double
// in most cases; sin, cos, exp, log and hypot within 2 units, tan, atan and tanh within
// 3, and pow, which carries log's error times |y log x|, within 2.5 (1 + |y log x|)).
// Arguments are doubles; sin, cos and tan reduce |x| below 2^20 (a million radians) to
// within a unit in the last place of the result, and beyond that stay the same bits
// everywhere but lose accuracy (no scene needs such angles).
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

namespace hsr::portable {
namespace detail {

// π/2 in four parts, the first three of 33 bits, so that k times each is exact for
// |k| < 2^20 (Cody and Waite; fdlibm's constants).
inline constexpr double kHalfPi1 = 1.57079632673412561417e+00;  // the first 33 bits
inline constexpr double kHalfPi2 = 6.07710050630396597660e-11;  // the next 33
inline constexpr double kHalfPi3 = 2.02226624871116645580e-21;  // the next 33
inline constexpr double kHalfPi4 = 8.47842766036889956997e-32;  // the rest, rounded
inline constexpr double kTwoOverPi = 6.36619772367581382433e-01;
inline constexpr double kLn2High = 6.93147180369123816490e-01;  // ln 2 in two parts (Cody and Waite)
inline constexpr double kLn2Low = 1.90821492927058770002e-10;
inline constexpr double kInverseLn2 = 1.44269504088896338700e+00;
inline constexpr double kHalfPi = 1.57079632679489655800e+00;
inline constexpr double kPi = 3.14159265358979311600e+00;

// r reduced to [-π/4, π/4] with x = r + quadrant π/2.
inline double reduced(double x, int& quadrant) {
  const double k = std::nearbyint(x * kTwoOverPi);
  quadrant = static_cast<int>(static_cast<long long>(k) & 3);
  return (((x - k * kHalfPi1) - k * kHalfPi2) - k * kHalfPi3) - k * kHalfPi4;
}

// The Taylor series of sin and cos on [-π/4, π/4]: r^19/19! there is below 1e-19.
inline double sinSeries(double r) {
  const double r2 = r * r;
  double sum = -1.0 / 121645100408832000.0;  // -1/19!
  for (const double coefficient : {1.0 / 355687428096000.0, -1.0 / 1307674368000.0, 1.0 / 6227020800.0, -1.0 / 39916800.0,
                                   1.0 / 362880.0, -1.0 / 5040.0, 1.0 / 120.0, -1.0 / 6.0})
    sum = sum * r2 + coefficient;
  return r + r * r2 * sum;
}
inline double cosSeries(double r) {
  const double r2 = r * r;
  double sum = 1.0 / 2432902008176640000.0;  // 1/20!
  for (const double coefficient : {-1.0 / 6402373705728000.0, 1.0 / 20922789888000.0, -1.0 / 87178291200.0, 1.0 / 479001600.0,
                                   -1.0 / 3628800.0, 1.0 / 40320.0, -1.0 / 720.0, 1.0 / 24.0})
    sum = sum * r2 + coefficient;
  return 1.0 - 0.5 * r2 + r2 * r2 * sum;
}

// e^r - 1 for |r| <= ln 2 / 2, by the series of e^r to r^17/17! (below 1e-20), without
// the 1, so that it keeps its relative accuracy as r goes to 0.
inline double expMinusOneSeries(double r) {
  double sum = 1.0 / 355687428096000.0;  // 1/17!
  for (const double coefficient : {1.0 / 20922789888000.0, 1.0 / 1307674368000.0, 1.0 / 87178291200.0, 1.0 / 6227020800.0,
                                   1.0 / 479001600.0, 1.0 / 39916800.0, 1.0 / 3628800.0, 1.0 / 362880.0, 1.0 / 40320.0, 1.0 / 5040.0,
                                   1.0 / 720.0, 1.0 / 120.0, 1.0 / 24.0, 1.0 / 6.0, 0.5})
    sum = sum * r + coefficient;
  return r + r * r * sum;
}

// atan(x) for |x| <= tan(π/16) (about 0.199): x - x^3/3 + x^5/5 ..., to x^29/29.
inline double atanSeries(double x) {
  const double x2 = x * x;
  double sum = -1.0 / 31;
  for (int n = 29; n >= 3; n -= 2) sum = sum * x2 + ((n / 2) % 2 == 0 ? 1.0 : -1.0) / n;
  return x + x * x2 * sum;
}

}  // namespace detail

inline double sin(double x) {
  if (!std::isfinite(x)) return std::numeric_limits<double>::quiet_NaN();
  int quadrant = 0;
  const double r = detail::reduced(x, quadrant);
  const double value = quadrant % 2 == 0 ? detail::sinSeries(r) : detail::cosSeries(r);
  return quadrant >= 2 ? -value : value;
}

inline double cos(double x) {
  if (!std::isfinite(x)) return std::numeric_limits<double>::quiet_NaN();
  int quadrant = 0;
  const double r = detail::reduced(x, quadrant);
  const double value = quadrant % 2 == 0 ? detail::cosSeries(r) : detail::sinSeries(r);
  return quadrant == 1 || quadrant == 2 ? -value : value;
}

inline double tan(double x) {
  if (!std::isfinite(x)) return std::numeric_limits<double>::quiet_NaN();
  int quadrant = 0;
  const double r = detail::reduced(x, quadrant);
  const double s = detail::sinSeries(r), c = detail::cosSeries(r);
  return quadrant % 2 == 0 ? s / c : -c / s;
}

// atan(x) in (-π/2, π/2).
inline double atan(double x) {
  if (std::isnan(x)) return x;
  const bool negative = x < 0;
  double a = std::abs(x);
  // atan(a) = π/2 - atan(1/a) above 1; then twice atan(a) = 2 atan(a / (1 + sqrt(1 + a^2)))
  // brings a below tan(π/16).
  const bool inverted = a > 1;
  if (inverted) a = 1 / a;
  a = a / (1 + std::sqrt(1 + a * a));
  a = a / (1 + std::sqrt(1 + a * a));
  double angle = 4 * detail::atanSeries(a);
  if (inverted) angle = detail::kHalfPi - angle;
  return negative ? -angle : angle;
}

// The angle of the point (x, y), in [-π, π].
inline double atan2(double y, double x) {
  if (std::isnan(x) || std::isnan(y)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0 && y == 0) return std::signbit(x) ? (std::signbit(y) ? -detail::kPi : detail::kPi) : y;
  if (std::abs(x) >= std::abs(y)) {
    const double angle = atan(y / x);
    if (x > 0) return angle;
    return std::signbit(y) ? angle - detail::kPi : angle + detail::kPi;
  }
  const double angle = -atan(x / y);
  return y > 0 ? angle + detail::kHalfPi : angle - detail::kHalfPi;
}

inline double exp(double x) {
  if (std::isnan(x)) return x;
  if (x > 709.782712893384) return std::numeric_limits<double>::infinity();
  if (x < -745.1332191019412) return 0;
  // x = k ln 2 + r with |r| <= ln2 / 2, then e^r by its series to r^17/17! (below 1e-20).
  const double k = std::nearbyint(x * detail::kInverseLn2);
  const double r = (x - k * detail::kLn2High) - k * detail::kLn2Low;
  const double value = 1.0 + detail::expMinusOneSeries(r);
  // 2^k in two steps, so that neither overflows nor loses a subnormal result's bits twice.
  const int half = static_cast<int>(k) / 2;
  return std::ldexp(std::ldexp(value, half), static_cast<int>(k) - half);
}

// tanh x = (e^2x - 1) / (e^2x + 1). Near 0 from e^2x - 1's series (the difference
// 1 - 2/(e^2x + 1) would cancel there); beyond 19, 1 (tanh 19 is 1 - 6e-17, which rounds
// to 1).
inline double tanh(double x) {
  if (std::isnan(x)) return x;
  const double a = std::abs(x);
  double magnitude = 1;
  if (a <= 0.5 * detail::kLn2High) {
    const double m = detail::expMinusOneSeries(2 * a);
    magnitude = m / (m + 2);
  } else if (a < 19) {
    magnitude = 1 - 2 / (exp(2 * a) + 1);
  }
  return std::copysign(magnitude, x);
}

inline double log(double x) {
  if (std::isnan(x) || x < 0) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0) return -std::numeric_limits<double>::infinity();
  if (std::isinf(x)) return x;
  // x = m 2^e with m in [sqrt(1/2), sqrt(2)); log m = 2 atanh(f), f = (m - 1) / (m + 1),
  // |f| <= 0.1716, by its series to f^23/23 (below 1e-19).
  int e = 0;
  double m = std::frexp(x, &e);  // [0.5, 1)
  if (m < 0.70710678118654752440) m *= 2, --e;
  const double f = (m - 1) / (m + 1), f2 = f * f;
  double sum = 1.0 / 23;
  for (int n = 21; n >= 3; n -= 2) sum = sum * f2 + 1.0 / n;
  const double logM = 2 * f + 2 * f * f2 * sum;
  return (e * detail::kLn2High + logM) + e * detail::kLn2Low;
}

// x^y for x >= 0 (and for x < 0 with an integer y): e^(y log x).
inline double pow(double x, double y) {
  if (y == 0) return 1;
  if (std::isnan(x) || std::isnan(y)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0) return y > 0 ? 0.0 : std::numeric_limits<double>::infinity();
  if (x < 0) {
    if (std::nearbyint(y) != y) return std::numeric_limits<double>::quiet_NaN();
    const double magnitude = pow(-x, y);
    return std::fmod(y, 2.0) != 0 ? -magnitude : magnitude;
  }
  return exp(y * log(x));
}

// 10^n: exact for 0 <= n <= 22 (every such power is a double), the correctly rounded
// 1 / 10^-n for -22 <= n < 0, and beyond those, products of them (a few roundings).
inline double powerOfTen(long n) {
  constexpr double kExact[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  if (n >= 0 && n <= 22) return kExact[n];
  if (n < 0 && n >= -22) return 1 / kExact[-n];
  if (n > 0) return n > 330 ? std::numeric_limits<double>::infinity() : kExact[22] * powerOfTen(n - 22);
  return n < -350 ? 0.0 : powerOfTen(n + 22) / kExact[22];
}

// sqrt(x^2 + y^2) without overflow or underflow in the squares.
inline double hypot(double x, double y) {
  x = std::abs(x), y = std::abs(y);
  if (std::isinf(x) || std::isinf(y)) return std::numeric_limits<double>::infinity();
  if (std::isnan(x) || std::isnan(y)) return std::numeric_limits<double>::quiet_NaN();
  const double larger = std::max(x, y), smaller = std::min(x, y);
  if (larger == 0) return 0;
  const double ratio = smaller / larger;
  return larger * std::sqrt(1 + ratio * ratio);
}

}  // namespace hsr::portable
