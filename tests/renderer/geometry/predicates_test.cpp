// The exact predicates against GMP's rationals, on inputs built to defeat double
// precision: points a few ulps off a line or plane, far from the origin.
#include <gtest/gtest.h>

#include <cmath>

#include <gmpxx.h>

#include "renderer/geometry/predicates.hpp"

namespace hsr {
namespace {

int exactOrient2d(const dvec3& a, const dvec3& b, const dvec3& c) {
  return sgn((mpq_class(b.x) - a.x) * (mpq_class(c.y) - a.y) - (mpq_class(b.y) - a.y) * (mpq_class(c.x) - a.x));
}

int exactOrient3d(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& d) {
  mpq_class u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = mpq_class(b[i]) - a[i];
    v[i] = mpq_class(c[i]) - a[i];
    w[i] = mpq_class(d[i]) - a[i];
  }
  return sgn(u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]));
}

// Shewchuk's figure: the point (0.5 + i ulp, 0.5 + j ulp) against the line through
// (12, 12) and (24, 24). Double precision gets a large share of these wrong.
TEST(ExactPredicates, Orient2dNearALineMatchesRationals) {
  ExactPredicates predicates;
  const dvec3 b(12, 12, 0), c(24, 24, 0);
  int naiveWrong = 0, zeros = 0;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const dvec3 a(0.5 + i * 0x1p-53, 0.5 + j * 0x1p-53, 0);
      const int exact = exactOrient2d(a, b, c);
      ASSERT_EQ(predicates.orient2d(a, b, c), exact) << i << "," << j;
      const double naive = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      naiveWrong += (naive > 0) - (naive < 0) != exact;
      zeros += exact == 0;
    }
  EXPECT_GT(naiveWrong, 100) << "the test must defeat plain doubles to mean anything";
  EXPECT_GT(zeros, 0);
  EXPECT_GT(predicates.exactFallbacks, 0);
}

// The same figure in 3D: points a few ulps off the plane x = y (through (12, 12, 0),
// (24, 24, 0) and (0, 0, 1)), then the whole set moved far from the origin.
TEST(ExactPredicates, Orient3dNearAPlaneMatchesRationals) {
  ExactPredicates predicates;
  for (const dvec3 offset : {dvec3(0), dvec3(0, 0, 1e6)}) {
    const dvec3 a = dvec3(12, 12, 0) + offset, b = dvec3(24, 24, 0) + offset, c = dvec3(0, 0, 1) + offset;
    int naiveWrong = 0;
    for (int i = 0; i < 32; ++i)
      for (int j = 0; j < 32; ++j) {
        const dvec3 d = dvec3(0.5 + i * 0x1p-53, 0.5 + j * 0x1p-53, 0.3) + offset;
        const int exact = exactOrient3d(a, b, c, d);
        ASSERT_EQ(predicates.orient3d(a, b, c, d), exact) << i << "," << j;
        const double naive = glm::dot(glm::cross(b - a, c - a), d - a);
        naiveWrong += (naive > 0) - (naive < 0) != exact;
      }
    EXPECT_GT(naiveWrong, 100) << "offset z " << offset.z;
  }
  const dvec3 a(1, 2, 3), b(4, -5, 6), c(-7, 8, 9);
  EXPECT_EQ(predicates.orient3d(a, b, c, b), 0) << "a corner of the plane's own triangle";
}

// On a grid (coordinates with exact differences), coplanar points are decided by the
// double-precision expansions without any rational arithmetic.
TEST(ExactPredicates, GridPointsNeedNoRationals) {
  ExactPredicates predicates;
  const dvec3 a(0.25, 1.5, -2), b(3.75, 1.5, -2), c(0.25, 1.5, 6.125);
  for (int i = -5; i <= 5; ++i) EXPECT_EQ(predicates.orient3d(a, b, c, dvec3(i * 0.375, 1.5, i * 1.25)), 0);
  EXPECT_EQ(predicates.orient3d(a, b, c, dvec3(1, 1.5 + 0x1p-40, 1)), -exactOrient3d(a, b, c, dvec3(1, 1.5 - 0x1p-40, 1)));
  EXPECT_EQ(predicates.exactFallbacks, 0);
  EXPECT_EQ(predicates.facing(a, b, c, dvec3(0, 1, 0)), exactOrient3d(a, b, c, a + dvec3(0, 1, 0)));
}

}  // namespace
}  // namespace hsr
