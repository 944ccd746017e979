// Floating-point exceptions as failures: an invalid operation (a NaN born), a division
// by zero or an overflow stops the program at the instruction that caused it, instead of
// printing a grey pixel three passes later. The debug and sanitize presets trap them in
// every test (tests/test_main.cpp); a test can trap them for a scope of its own in any
// build.
#pragma once

#include <cfenv>

namespace hsr::test {

inline constexpr int kTrappedExceptions = FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW;

// Traps exactly `exceptions` while it lives (none for 0), then restores what was
// trapped before. Threads started meanwhile inherit the traps (POSIX: a thread starts
// with its creator's floating-point environment).
class TrappedFloatingPoint {
 public:
  explicit TrappedFloatingPoint(int exceptions = kTrappedExceptions) : previous_(fegetexcept()) {
    fedisableexcept(FE_ALL_EXCEPT);
    std::feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(exceptions);
  }
  ~TrappedFloatingPoint() {
    std::feclearexcept(FE_ALL_EXCEPT);
    fedisableexcept(FE_ALL_EXCEPT);
    feenableexcept(previous_);
  }
  TrappedFloatingPoint(const TrappedFloatingPoint&) = delete;
  TrappedFloatingPoint& operator=(const TrappedFloatingPoint&) = delete;

 private:
  int previous_;
};

// Code we do not own runs untrapped: OpenImageIO's compare divides by zero on purpose
// (the PSNR of two identical images is infinite), which is its answer, not our bug.
class UntrappedFloatingPoint : public TrappedFloatingPoint {
 public:
  UntrappedFloatingPoint() : TrappedFloatingPoint(0) {}
};

// Called first by every test program: traps for the whole run when the build asks
// (-DHSR_TRAP_FLOATING_POINT=ON, the debug and sanitize presets).
inline void trapFloatingPointWhenAsked() {
#ifdef HSR_TRAP_FLOATING_POINT
  std::feclearexcept(FE_ALL_EXCEPT);
  feenableexcept(kTrappedExceptions);
#endif
}

}  // namespace hsr::test
