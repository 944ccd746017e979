// The one place that knows the instruction set. What the fast paths share (the z-buffer's
// blocks, the wide BVH's traversal, ray packets, the occluder map's rows): how x86's AVX2
// code is marked and chosen, vectors of doubles and floats as values, and the few
// operations on them that need an instruction of their own.
//
// On x86-64 the program is built for the baseline instruction set. Only functions marked
// HSR_AVX2 use AVX2 instructions, and they run only where cpuHasAvx2() says the CPU has
// them; elsewhere the textbook loop runs, so one binary runs anywhere. A function of the
// baseline build may be inlined into an HSR_AVX2 one (it then gets AVX2 code), never the
// other way, so nothing compiled for AVX2 leaks into the rest of the program.
//
// On every other target (arm64, WebAssembly) the choice is made when building: kX86 is
// false, cpuHasAvx2() is a constant false, HSR_AVX2 marks nothing, and every fast path
// gives way to its portable textbook loop, whose bits the fast paths reproduce. The
// operations below have a portable form there, written with the vector types alone, so
// that the code around the fast paths compiles unchanged.
//
// Double4 is four doubles with GCC's vector extensions (which clang also has): `a * b +
// c` on Double4 values is the scalar expression lane by lane, the same IEEE operations
// in the same order, so a vector path gives the scalar path's bits. (No build lets the
// compiler fuse a multiply and an add: -ffp-contract=off, CMakeLists.txt.) Comparisons
// give a Mask4, all bits set in a true lane; `mask ? a : b` selects by lane.
#pragma once

#include <cstdint>
#include <limits>
#include <type_traits>

#if defined(__x86_64__) || defined(__i386__)
#define HSR_X86 1
#include <immintrin.h>
#define HSR_AVX2 __attribute__((target("avx2")))
#else
#define HSR_X86 0
#define HSR_AVX2
#endif
// A function of the baseline build inlined wherever it is called, so that in an HSR_AVX2
// function it becomes AVX2 code (templates shared by one ray and four lanes).
#define HSR_INLINE [[gnu::always_inline]] inline

namespace hsr {

// Whether this build targets x86, whose fast paths use its instructions by name.
inline constexpr bool kX86 = HSR_X86 != 0;

// Whether this CPU runs AVX2 (asked once); false on every other target.
inline bool cpuHasAvx2() {
#if HSR_X86
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

// A hint, in a loop that waits for another thread, that the loop is waiting (x86's
// pause, arm64's yield): it saves power and lets the other hyper-thread run. It changes
// no result, and where there is no such instruction it is nothing.
inline void spinWaitHint() {
#if HSR_X86
  _mm_pause();
#elif defined(__aarch64__)
  __asm__ __volatile__("yield");
#endif
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
// Eight floats, and eight 32-bit integers: one AVX2 register each.
using Float8 = float __attribute__((vector_size(32)));
using Int8 = std::int32_t __attribute__((vector_size(32)));

// Bit i set where lane i of the mask is true.
HSR_AVX2 inline int laneBits(Mask4 mask) {
#if HSR_X86
  return _mm256_movemask_pd(__m256d(mask));
#else
  return int(mask[0] & 1) | int(mask[1] & 1) << 1 | int(mask[2] & 1) << 2 | int(mask[3] & 1) << 3;
#endif
}
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
HSR_AVX2 inline Double4 widened(const float* four) {
  Float4 narrow;
  __builtin_memcpy(&narrow, four, sizeof narrow);
  return __builtin_convertvector(narrow, Double4);
}

// Four doubles rounded to the nearest floats, and eight of them from two halves.
HSR_AVX2 inline Float4 narrowed(Double4 four) { return __builtin_convertvector(four, Float4); }
HSR_AVX2 inline Float8 narrowed(Double4 low, Double4 high) {
  const Float4 lowHalf = narrowed(low), highHalf = narrowed(high);
  return Float8{lowHalf[0], lowHalf[1], lowHalf[2], lowHalf[3], highHalf[0], highHalf[1], highHalf[2], highHalf[3]};
}

// The lanes of `row + x` that `lanes` selects (all bits set in a selected lane), loaded;
// the others 0 and never read (the row may end there). And the same lanes stored.
HSR_AVX2 inline Float8 maskedLoad(const float* row, Int8 lanes) {
#if HSR_X86
  return Float8(_mm256_maskload_ps(row, __m256i(lanes)));
#else
  Float8 loaded{};
  for (int lane = 0; lane < 8; ++lane)
    if (lanes[lane]) loaded[lane] = row[lane];
  return loaded;
#endif
}
HSR_AVX2 inline void maskedStore(float* row, Int8 lanes, Float8 values) {
#if HSR_X86
  _mm256_maskstore_ps(row, __m256i(lanes), __m256(values));
#else
  for (int lane = 0; lane < 8; ++lane)
    if (lanes[lane]) row[lane] = values[lane];
#endif
}

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

// inverseOf (renderer/util/math.hpp) lane by lane: 1 / d, and +-infinity by d's sign for
// a zero lane, without dividing by zero.
HSR_AVX2 inline Double4 inverseOf(Double4 d) {
  const Mask4 zero = d == 0.0;
  const Mask4 sign = Mask4(d) & Mask4(lanesOf(-0.0));
  const Double4 signedInfinity = Double4(sign | Mask4(lanesOf(std::numeric_limits<double>::infinity())));
  return zero ? signedInfinity : 1.0 / (zero ? lanesOf(1.0) : d);
}

}  // namespace hsr
