// The suite's own elementary functions (renderer/util/portable_math.hpp) against the C
// library's: how many units in the last place apart they are at most, over the ranges
// the scenes use, and their special values. The same bits on every target are checked
// by the identity test (tests/identity); this checks they are also the right numbers.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <random>

#include "renderer/util/portable_math.hpp"

namespace hsr {
namespace {

// The number of doubles between a and b (0 when equal, both NaN, or +0 and -0).
std::int64_t unitsApart(double a, double b) {
  if (a == b || (std::isnan(a) && std::isnan(b))) return 0;
  std::int64_t x = 0, y = 0;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  // Negative doubles' bits count down as the values go down: mirror them below zero.
  if (x < 0) x = std::numeric_limits<std::int64_t>::min() - x;
  if (y < 0) y = std::numeric_limits<std::int64_t>::min() - y;
  return x > y ? x - y : y - x;
}

// The largest distance over 100,000 arguments drawn evenly from [from, to].
std::int64_t worstUnitsApart(const std::function<double(double)>& ours, const std::function<double(double)>& library,
                             double from, double to) {
  std::mt19937_64 random(52);
  std::uniform_real_distribution<double> argument(from, to);
  std::int64_t worst = 0;
  for (int i = 0; i < 100'000; ++i) {
    const double x = argument(random);
    worst = std::max(worst, unitsApart(ours(x), library(x)));
  }
  return worst;
}

TEST(PortableMath, UnitsApartCountsDoubles) {
  EXPECT_EQ(unitsApart(1.0, std::nextafter(1.0, 2.0)), 1);
  EXPECT_EQ(unitsApart(-0.0, 0.0), 0);
  EXPECT_EQ(unitsApart(-std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::denorm_min()), 2);
}

TEST(PortableMath, SineAndCosineWithinTwoUnitsOverAHundredRadians) {
  // Near every multiple of π the sine is small, and only a reduction that carries π/2 to
  // more than 100 bits keeps it within a unit or two there.
  EXPECT_LE(worstUnitsApart(portable::sin, [](double x) { return std::sin(x); }, -100, 100), 2);
  EXPECT_LE(worstUnitsApart(portable::cos, [](double x) { return std::cos(x); }, -100, 100), 2);
  for (int k = -30; k <= 30; ++k) {
    const double nearMultiple = k * 3.14159265358979311600 + 1e-7;
    EXPECT_LE(unitsApart(portable::sin(nearMultiple), std::sin(nearMultiple)), 2) << "k = " << k;
  }
}

TEST(PortableMath, TangentAndArctangentWithinThreeUnits) {
  EXPECT_LE(worstUnitsApart(portable::tan, [](double x) { return std::tan(x); }, -1.5, 1.5), 3);
  EXPECT_LE(worstUnitsApart(portable::atan, [](double x) { return std::atan(x); }, -100, 100), 3);
  EXPECT_LE(worstUnitsApart([](double y) { return portable::atan2(y, -0.7); }, [](double y) { return std::atan2(y, -0.7); }, -5, 5), 3);
}

TEST(PortableMath, ExponentialLogarithmAndTanhWithinAFewUnits) {
  EXPECT_LE(worstUnitsApart(portable::exp, [](double x) { return std::exp(x); }, -700, 700), 1);
  EXPECT_LE(worstUnitsApart(portable::log, [](double x) { return std::log(x); }, 1e-10, 1e10), 2);
  EXPECT_LE(worstUnitsApart(portable::log, [](double x) { return std::log(x); }, 0.5, 2), 2);
  EXPECT_LE(worstUnitsApart(portable::tanh, [](double x) { return std::tanh(x); }, -3, 3), 3);
  EXPECT_LE(worstUnitsApart(portable::tanh, [](double x) { return std::tanh(x); }, -1e-3, 1e-3), 3);
  EXPECT_LE(worstUnitsApart([](double x) { return portable::hypot(x, 1.7); }, [](double x) { return std::hypot(x, 1.7); }, -10, 10), 2);
}

TEST(PortableMath, PowerCarriesTheLogarithmsErrorTimesItsExponent) {
  // x^y = e^(y log x): the units by which y log x is off are units of y log x, which
  // e^(y log x) turns into relative error, so the bound grows with |y log x| (a million
  // draws stay within 2.3 (1 + |y log x|) units; at x = 1e-4, y = 2.2, that is 49).
  std::mt19937_64 random(52);
  std::uniform_real_distribution<double> base(0, 10), exponent(-3, 3);
  for (int i = 0; i < 100'000; ++i) {
    const double x = base(random), y = exponent(random);
    const double carried = std::abs(y * std::log(x));
    ASSERT_LE(double(unitsApart(portable::pow(x, y), std::pow(x, y))), 2.5 * (1 + carried)) << x << "^" << y;
  }
  EXPECT_DOUBLE_EQ(portable::pow(-2, 3), -8);  // within 4 units, and negative: an odd power
  EXPECT_TRUE(std::isnan(portable::pow(-2, 0.5)));
  EXPECT_EQ(portable::pow(0, -1), std::numeric_limits<double>::infinity());
}

TEST(PortableMath, SpecialValues) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isnan(portable::sin(kInfinity)));
  EXPECT_TRUE(std::isnan(portable::log(-1)));
  EXPECT_EQ(portable::log(0), -kInfinity);
  EXPECT_EQ(portable::exp(710), kInfinity);
  EXPECT_EQ(portable::exp(-746), 0);
  EXPECT_EQ(portable::tanh(25), 1);
  EXPECT_EQ(portable::tanh(-25), -1);
  EXPECT_TRUE(std::signbit(portable::tanh(-0.0)));
  EXPECT_EQ(portable::hypot(3e300, 4e300), 5e300);  // no overflow in the squares
  EXPECT_EQ(portable::hypot(kInfinity, std::numeric_limits<double>::quiet_NaN()), kInfinity);
  EXPECT_EQ(portable::powerOfTen(22), 1e22);
  EXPECT_EQ(portable::powerOfTen(-5), 1e-5);
  EXPECT_EQ(portable::atan2(0.0, -1.0), 3.14159265358979311600);
}

}  // namespace
}  // namespace hsr
