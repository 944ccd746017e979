// What the fast paths share (the z-buffer's blocks, the wide BVH's traversal, ray
// packets): how AVX2 code is marked and chosen, and four doubles as one value.
//
// The program is built for the baseline x86-64. Only functions marked HSR_AVX2 use AVX2
// instructions, and they run only where cpuHasAvx2() says the CPU has them; elsewhere
// the textbook loop runs, so one binary runs anywhere. A function of the baseline build
// may be inlined into an HSR_AVX2 one (it then gets AVX2 code), never the other way, so
// nothing compiled for AVX2 leaks into the rest of the program.
//
// Double4 is four doubles with GCC's vector extensions: `a * b + c` on Double4 values is
// the scalar expression lane by lane, the same IEEE operations in the same order, so a
// vector path gives the scalar path's bits. (Neither build lets the compiler fuse a
// multiply and an add: the baseline has no FMA, and HSR_AVX2 does not enable it.)
// Comparisons give a Mask4, all bits set in a true lane; `mask ? a : b` selects by lane.
#pragma once

#include <immintrin.h>

#include <cstdint>
#include <limits>
#include <type_traits>

#define HSR_AVX2 __attribute__((target("avx2")))
// A function of the baseline build inlined wherever it is called, so that in an HSR_AVX2
// function it becomes AVX2 code (templates shared by one ray and four lanes).
#define HSR_INLINE [[gnu::always_inline]] inline

namespace hsr {

// Whether this CPU runs AVX2 (asked once).
inline bool cpuHasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

// Starts loading every cache line of `value`, ahead of its use: for data read in an
// order the hardware's prefetcher cannot guess (a tile's triangles, scattered through
// the scene's list; occluders taken nearest first). A hint: it changes no result.
template <typename T>
inline void prefetch(const T& value) {
  constexpr std::uintptr_t kLine = 64;
  const auto first = reinterpret_cast<std::uintptr_t>(&value);
  for (std::uintptr_t line = first & ~(kLine - 1); line < first + sizeof(T); line += kLine) __builtin_prefetch(reinterpret_cast<const void*>(line));
}

// Four floats: one SSE register, which the baseline x86-64 has, so no AVX2 needed.
using Float4 = float __attribute__((vector_size(16)));

using Double4 = double __attribute__((vector_size(32)));
using Mask4 = std::int64_t __attribute__((vector_size(32)));
// Eight doubles: two AVX2 registers, which the compiler pairs up operation by operation
// (ray packets: a ray per lane).
using Double8 = double __attribute__((vector_size(64)));
using Mask8 = std::int64_t __attribute__((vector_size(64)));

// Bit i set where lane i of the mask is true.
HSR_AVX2 inline int laneBits(Mask4 mask) { return _mm256_movemask_pd(__m256d(mask)); }
HSR_AVX2 inline int laneBits(const Mask8& mask) {
  Mask4 low, high;
  __builtin_memcpy(&low, &mask, sizeof low);
  __builtin_memcpy(&high, reinterpret_cast<const char*>(&mask) + sizeof low, sizeof high);
  return laneBits(low) | laneBits(high) << 4;
}
// The lanes whose bit is set in `bits`, as a mask (the inverse of laneBits).
HSR_AVX2 inline Mask4 laneMask4(int bits) {
  const Mask4 laneBit = {1, 2, 4, 8};
  return (bits & laneBit) != 0;
}

// Four floats widened to doubles (exactly).
HSR_AVX2 inline Double4 widened(const float* four) { return Double4(_mm256_cvtps_pd(_mm_loadu_ps(four))); }

HSR_AVX2 inline Double4 lanesOf(double value) { return Double4{value, value, value, value}; }
// One value as a Number: itself for double, in every lane for Double4 (code shared by
// one item and four lanes).
template <typename Number>
HSR_INLINE Number broadcast(double value) {
  if constexpr (std::is_same_v<Number, Double4>) return Double4{value, value, value, value};
  else return Number(value);
}
HSR_AVX2 inline Double8 eightLanesOf(double value) { return Double8{value, value, value, value, value, value, value, value}; }

// The larger and the smaller of two values, lane by lane, as `a > b ? a : b` and
// `a < b ? a : b` choose them (so b where either is NaN).
HSR_AVX2 inline Double4 larger(Double4 a, Double4 b) { return a > b ? a : b; }
HSR_AVX2 inline Double4 smaller(Double4 a, Double4 b) { return a < b ? a : b; }

// inverseOf (renderer/math.hpp) lane by lane: 1 / d, and +-infinity by d's sign for a
// zero lane, without dividing by zero.
HSR_AVX2 inline Double4 inverseOf(Double4 d) {
  const Mask4 zero = d == 0.0;
  const __m256d sign = _mm256_and_pd(__m256d(d), __m256d(lanesOf(-0.0)));
  const Double4 signedInfinity = Double4(_mm256_or_pd(sign, __m256d(lanesOf(std::numeric_limits<double>::infinity()))));
  return zero ? signedInfinity : 1.0 / (zero ? lanesOf(1.0) : d);
}

}  // namespace hsr
