// Exact orientation predicates for double-precision points (Shewchuk 1997's filter, exact
// arithmetic behind it: renderer/geometry/exact.hpp). Every double is a rational number,
// so the sign of a determinant of doubles has one right answer; these return it.
//
// Each predicate first evaluates the determinant in double precision together with a
// forward error bound (Shewchuk's "A" bounds); when the value's magnitude exceeds the
// bound its sign is certain. Otherwise, if the coordinate differences were exact, it
// sums the products exactly in double-precision expansions (fused multiply-add); else it
// evaluates again in exact arithmetic (ExactNumber), which is slower, rare and counted.
// The two floating-point stages hold only while no product underflows or overflows:
// points whose coordinate differences lie outside 2^-290 to 2^290 (and are not zero) go
// straight to the exact stage.
#pragma once

#include <cstdint>

#include "renderer/util/math.hpp"

namespace hsr {

class ExactPredicates {
 public:
  // Sign of (b - a) x (c - a) over x and y: +1, 0 or -1.
  int orient2d(const dvec3& a, const dvec3& b, const dvec3& c);
  // Sign of det[b - a, c - a, d - a] = ((b - a) x (c - a)) . (d - a): which side of the
  // plane through a, b, c the point d lies on (0: on it).
  int orient3d(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d);
  // Sign of det[b - a, c - a, direction]: which way the plane through a, b, c faces
  // relative to a direction (0: the plane is parallel to it).
  int facing(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& direction);

  // The value of orient3d's determinant, to within a few units in its own last place
  // (its sign is orient3d's): the double evaluation where its error bound is under 1e-12
  // of it, else the exact value rounded. For placing where a segment crosses a plane:
  // the heights of its ends, so computed, have opposite signs and no cancellation between
  // them, so the crossing is as accurate as its ends however thin the cut.
  double orient3dValue(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d);

  std::int64_t evaluations = 0;     // predicate calls
  std::int64_t exactFallbacks = 0;  // calls that needed exact arithmetic

 private:
  int orient3dOfVectors(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d, bool dIsPoint);
  double orient3dDeterminant(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d, bool dIsPoint, double relativeBound);
  // orient3dDeterminant's exact stages, where the double evaluation's bound did not
  // decide: the expansion when the differences are exact (`safe`: and none underflows or
  // overflows), else exact numbers. Apart, and never inlined, because their exact numbers
  // need a frame of some 25 KB, which every call would otherwise set up, with the double
  // evaluation's spills spread across it, though nearly all calls end there (backface
  // culling's orient3d on the dragons took 1.2-1.3 times as long).
  [[gnu::cold, gnu::noinline]] double orient3dExactly(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d, bool dIsPoint, bool safe);
};

}  // namespace hsr
