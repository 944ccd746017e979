// Exact arithmetic on doubles, without an arbitrary-precision library: the exact
// predicates (predicates.hpp) and the exact reference's fall-back (reference/) decide
// with it where a floating-point error bound leaves a sign open.
//
// ExactNumber<kDegree> holds, exactly, any value a polynomial of degree at most kDegree
// in doubles can take (sums, differences and products of doubles, no product of more
// than kDegree of them): sign x mantissa x 2^(64 exponent), the mantissa an integer of
// at most kLimbs 64-bit limbs kept in the object itself, so nothing is allocated. Every
// double is an integer multiple of 2^-1074 below 2^1024, so a product of k doubles is
// an integer multiple of 2^(-1074 k) below 2^(1024 k), and a sum of n such products
// (of at most k factors each) is a multiple of 2^(-1074 k) below n 2^(1024 k): from its
// lowest to its highest set bit, at most 2098 k + log2(n) bits. A mantissa kept at limb
// granularity holds up to 63 zero bits more below and above; with n below 2^64,
//   kLimbs = (2098 kDegree + 64 + 2 x 63) / 64, rounded up,
// is enough for every value, intermediate ones included. Each operation checks that its
// result fits (HSR_CHECK): a degree the caller understated is a loud failure, never a
// wrong sign. Division is not offered: callers keep a quotient as its numerator and
// denominator and compare by cross-multiplying, and truncatedQuotient rounds one.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "renderer/util/error.hpp"

namespace hsr {

namespace exact_detail {
__extension__ using Wide = unsigned __int128;  // 64 x 64 -> 128-bit products (GCC and Clang, every target here)
// floor(a / b) for b > 0, also for negative a.
constexpr long floorDivide(long a, long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
}  // namespace exact_detail

template <int kDegree>
class ExactNumber {
 public:
  static constexpr int kLimbs = (2098 * kDegree + 64 + 2 * 63 + 63) / 64;

  ExactNumber() = default;
  // A finite double, exactly.
  ExactNumber(double value) {  // NOLINT: implicit, as a double is one
    HSR_CHECK(std::isfinite(value));
    if (value == 0) return;
    negative_ = value < 0;
    int exponent = 0;
    // value = fraction x 2^exponent with fraction in [0.5, 1): 53 bits of it as an integer.
    const double fraction = std::frexp(std::abs(value), &exponent);
    std::uint64_t mantissa = static_cast<std::uint64_t>(std::ldexp(fraction, 53));
    int bitExponent = exponent - 53;  // value = mantissa x 2^bitExponent
    // To limb granularity: exponent64 = floor(bitExponent / 64), the rest shifted in.
    const int exponent64 = bitExponent >= 0 ? bitExponent / 64 : -((-bitExponent + 63) / 64);
    const int shift = bitExponent - 64 * exponent64;  // 0 ... 63
    exponent_ = exponent64;
    limbs_[0] = mantissa << shift;
    limbs_[1] = shift == 0 ? 0 : mantissa >> (64 - shift);
    size_ = 2;
    normalize();
  }

  ExactNumber(const ExactNumber& other) { copyFrom(other); }
  ExactNumber& operator=(const ExactNumber& other) {
    copyFrom(other);
    return *this;
  }

  int sign() const { return size_ == 0 ? 0 : negative_ ? -1 : 1; }
  bool isZero() const { return size_ == 0; }

  ExactNumber operator-() const {
    ExactNumber result = *this;
    result.negative_ = size_ != 0 && !negative_;
    return result;
  }
  friend ExactNumber operator+(const ExactNumber& a, const ExactNumber& b) { return sum(a, b, false); }
  friend ExactNumber operator-(const ExactNumber& a, const ExactNumber& b) { return sum(a, b, true); }
  friend ExactNumber operator*(const ExactNumber& a, const ExactNumber& b) {
    ExactNumber product;
    if (a.size_ == 0 || b.size_ == 0) return product;
    HSR_CHECK(a.size_ + b.size_ <= kLimbs + 1);
    std::array<std::uint64_t, kLimbs + 1> wide{};
    for (int i = 0; i < a.size_; ++i) {
      exact_detail::Wide carry = 0;
      for (int j = 0; j < b.size_; ++j) {
        carry += static_cast<exact_detail::Wide>(a.limbs_[i]) * b.limbs_[j] + wide[i + j];
        wide[i + j] = static_cast<std::uint64_t>(carry);
        carry >>= 64;
      }
      wide[i + b.size_] = static_cast<std::uint64_t>(carry);
    }
    int size = a.size_ + b.size_;
    while (size > 0 && wide[size - 1] == 0) --size;
    HSR_CHECK(size <= kLimbs);
    std::copy_n(wide.begin(), size, product.limbs_.begin());
    product.size_ = size;
    product.exponent_ = a.exponent_ + b.exponent_;
    product.negative_ = a.negative_ != b.negative_;
    product.normalize();
    return product;
  }
  ExactNumber& operator+=(const ExactNumber& other) { return *this = *this + other; }
  ExactNumber& operator-=(const ExactNumber& other) { return *this = *this - other; }
  ExactNumber& operator*=(const ExactNumber& other) { return *this = *this * other; }

  friend int compare(const ExactNumber& a, const ExactNumber& b) { return (a - b).sign(); }
  friend bool operator<(const ExactNumber& a, const ExactNumber& b) { return compare(a, b) < 0; }
  friend bool operator>(const ExactNumber& a, const ExactNumber& b) { return compare(a, b) > 0; }
  friend bool operator<=(const ExactNumber& a, const ExactNumber& b) { return compare(a, b) <= 0; }
  friend bool operator>=(const ExactNumber& a, const ExactNumber& b) { return compare(a, b) >= 0; }
  friend bool operator==(const ExactNumber& a, const ExactNumber& b) { return compare(a, b) == 0; }

  // The double nearest zero of the two around the value (rounding toward zero, as
  // GMP's mpz_get_d and mpq_get_d do); infinity beyond the largest double.
  double truncated() const {
    if (size_ == 0) return 0;
    // The value's highest set bit is bit `top` of the whole number (its weight 2^top).
    const int highBits = 64 - std::countl_zero(limbs_[size_ - 1]);
    const long top = 64L * (exponent_ + size_ - 1) + highBits - 1;
    if (top > 1023) return negative_ ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
    // The last bit a double can keep: 52 below the top, or 2^-1074 for a subnormal.
    const long lowest = std::max(top - 52, -1074L);
    if (lowest > top) return 0.0;  // below the smallest subnormal: zero, unsigned, as GMP gives it
    // The bits from `top` down to `lowest` as an integer (at most 53 of them).
    std::uint64_t kept = 0;
    for (long bit = top; bit >= lowest; --bit) kept = kept << 1 | bitAt(bit);
    const double magnitude = std::ldexp(static_cast<double>(kept), static_cast<int>(lowest));
    return negative_ ? -magnitude : magnitude;
  }

  // numerator / denominator (which must not be zero), rounded toward zero, as GMP's
  // mpq_get_d does; infinity beyond the largest double.
  friend double truncatedQuotient(const ExactNumber& numerator, const ExactNumber& denominator) {
    HSR_CHECK(!denominator.isZero());
    if (numerator.isZero()) return 0;
    const bool negative = numerator.negative_ != denominator.negative_;
    const ExactNumber n = numerator.magnitude(), d = denominator.magnitude();
    constexpr double kLargest = std::numeric_limits<double>::max(), kInfinity = std::numeric_limits<double>::infinity();
    // A guess from the two values' leading bits, within a few units in the last place,
    // then stepped until the exact check q d <= n < next(q) d holds.
    // From 2^1024 on the guess is the largest double, not ldexp's overflow (which the
    // floating-point traps of the debug and sanitizer builds stop at).
    const long exponent = n.topBit() - d.topBit();
    const double ratio = n.leadingFraction() / d.leadingFraction();  // in (1/2, 2)
    double q = kLargest;
    if (exponent < 1024 || (exponent == 1024 && ratio < 1))
      q = std::min(std::ldexp(ratio, static_cast<int>(std::max(exponent, -4000L))), kLargest);
    while (q > 0 && ExactNumber(q) * d > n) q = std::nextafter(q, 0.0);
    while (q < kLargest && ExactNumber(std::nextafter(q, kInfinity)) * d <= n) q = std::nextafter(q, kInfinity);
    // At the largest double: infinity when the quotient reaches 2^1024.
    if (q == kLargest && ExactNumber(0x1p1023) * ExactNumber(2.0) * d <= n) q = kInfinity;
    return negative && q != 0 ? -q : q;  // a quotient below the smallest double is zero, unsigned, as GMP gives it
  }

 private:
  void copyFrom(const ExactNumber& other) {
    size_ = other.size_;
    exponent_ = other.exponent_;
    negative_ = other.negative_;
    std::copy_n(other.limbs_.begin(), size_, limbs_.begin());
  }

  // Drops zero limbs at both ends, keeping the value.
  void normalize() {
    while (size_ > 0 && limbs_[size_ - 1] == 0) --size_;
    int low = 0;
    while (low < size_ && limbs_[low] == 0) ++low;
    if (low > 0) {
      std::copy(limbs_.begin() + low, limbs_.begin() + size_, limbs_.begin());
      size_ -= low;
      exponent_ += low;
    }
    if (size_ == 0) negative_ = false, exponent_ = 0;
  }

  ExactNumber magnitude() const {
    ExactNumber result = *this;
    result.negative_ = false;
    return result;
  }

  // The weight of the highest set bit (the value is below 2^(topBit() + 1)).
  long topBit() const { return 64L * (exponent_ + size_ - 1) + (63 - std::countl_zero(limbs_[size_ - 1])); }
  // The value's leading bits as a double in [1, 2): value = leadingFraction() x 2^topBit()
  // to within a few units in the last place (a guess for truncatedQuotient to refine).
  double leadingFraction() const {
    const long top = topBit();
    std::uint64_t leading = 0;
    for (long bit = top; bit > top - 64; --bit) leading = leading << 1 | bitAt(bit);
    return std::ldexp(static_cast<double>(leading), -63);
  }
  // Bit `bit` of the value (its weight 2^bit), 0 or 1.
  std::uint64_t bitAt(long bit) const {
    const long limb = exact_detail::floorDivide(bit, 64);
    const long index = limb - exponent_;
    if (index < 0 || index >= size_) return 0;
    return limbs_[index] >> (bit - 64 * limb) & 1;
  }

  // a + b, or a - b when `subtract`.
  static ExactNumber sum(const ExactNumber& a, const ExactNumber& bIn, bool subtract) {
    const bool bNegative = bIn.size_ != 0 && (bIn.negative_ != subtract);
    if (a.size_ == 0) {
      ExactNumber result = bIn;
      result.negative_ = bNegative;
      return result;
    }
    if (bIn.size_ == 0) return a;
    // Both aligned to the lower exponent.
    const int exponent = std::min(a.exponent_, bIn.exponent_);
    const int aShift = a.exponent_ - exponent, bShift = bIn.exponent_ - exponent;
    const int size = std::max(a.size_ + aShift, bIn.size_ + bShift);
    HSR_CHECK(size <= kLimbs);
    const auto limbOf = [](const ExactNumber& x, int shift, int i) { return i >= shift && i - shift < x.size_ ? x.limbs_[i - shift] : std::uint64_t(0); };
    ExactNumber result;
    result.exponent_ = exponent;
    if (a.negative_ == bNegative) {
      std::uint64_t carry = 0;
      for (int i = 0; i < size; ++i) {
        const exact_detail::Wide total = static_cast<exact_detail::Wide>(limbOf(a, aShift, i)) + limbOf(bIn, bShift, i) + carry;
        result.limbs_[i] = static_cast<std::uint64_t>(total);
        carry = static_cast<std::uint64_t>(total >> 64);
      }
      result.size_ = size;
      if (carry) {
        HSR_CHECK(size + 1 <= kLimbs);
        result.limbs_[size] = carry;
        result.size_ = size + 1;
      }
      result.negative_ = a.negative_;
    } else {
      // The larger magnitude minus the smaller, with the larger's sign.
      int order = 0;
      for (int i = size - 1; i >= 0 && order == 0; --i) {
        const std::uint64_t x = limbOf(a, aShift, i), y = limbOf(bIn, bShift, i);
        order = x > y ? 1 : x < y ? -1 : 0;
      }
      if (order == 0) return ExactNumber();
      const ExactNumber& larger = order > 0 ? a : bIn;
      const ExactNumber& smaller = order > 0 ? bIn : a;
      const int largerShift = order > 0 ? aShift : bShift, smallerShift = order > 0 ? bShift : aShift;
      std::uint64_t borrow = 0;
      for (int i = 0; i < size; ++i) {
        const std::uint64_t x = limbOf(larger, largerShift, i), y = limbOf(smaller, smallerShift, i);
        const std::uint64_t difference = x - y - borrow;
        borrow = (x < y || (x == y && borrow)) ? 1 : 0;
        result.limbs_[i] = difference;
      }
      result.size_ = size;
      result.negative_ = order > 0 ? a.negative_ : bNegative;
    }
    result.normalize();
    return result;
  }

  std::array<std::uint64_t, kLimbs> limbs_;  // little-endian; only the first size_ are meaningful
  int size_ = 0;
  int exponent_ = 0;  // in limbs: the value is mantissa x 2^(64 exponent_)
  bool negative_ = false;
};

}  // namespace hsr
