// The exact arithmetic (renderer/geometry/exact.hpp) against GMP's rationals, an
// independent oracle: ExactNumber's values and roundings on adversarial expressions, the
// exact predicates on 100,000 adversarial inputs (near-degenerate, huge and tiny
// magnitudes, exact ties), the reference's exact Woop test against the same test in
// rationals on random rays and triangles, and on every triangle a fall-back ray meets in
// every shipped scene and hard case. Built only where GMP is installed (tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <random>

#include <gmpxx.h>

#include "renderer/geometry/exact.hpp"
#include "renderer/geometry/predicates.hpp"
#include "renderer/reference/bounded_woop.hpp"
#include "renderer/reference/nearest_hit.hpp"
#include "renderer/util/conventions.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

bool sameBits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// A double an adversary would pick: zero, tiny and subnormal, huge, one ulp off 1, a
// power of two, a small integer (ties), or an ordinary value of some magnitude.
double adversarial(std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(-1, 1);
  switch (std::uniform_int_distribution<int>(0, 9)(random)) {
    case 0: return 0.0;
    case 1: return std::ldexp(unit(random), std::uniform_int_distribution<int>(-1074, 1000)(random));
    case 2: return std::nextafter(1.0, 2.0) * (unit(random) < 0 ? -1 : 1);
    case 3: return std::ldexp(1.0, std::uniform_int_distribution<int>(-1074, 1023)(random));
    case 4: return 5e-324 * std::uniform_int_distribution<int>(-5, 5)(random);
    case 5: return std::round(unit(random) * 100);
    default: return unit(random) * std::ldexp(1.0, std::uniform_int_distribution<int>(-40, 40)(random));
  }
}

using Exact10 = ExactNumber<10>;

TEST(ExactNumber, RoundsTowardZeroLikeGmp) {
  EXPECT_EQ(truncatedQuotient(Exact10(1), Exact10(3)), mpq_class(1, 3).get_d());
  EXPECT_EQ(truncatedQuotient(Exact10(-2), Exact10(3)), mpq_class(-2, 3).get_d());
  EXPECT_LT(truncatedQuotient(Exact10(1), Exact10(10)), 0.1) << "toward zero, where the nearest double is above";
  EXPECT_EQ(truncatedQuotient(Exact10(-1), Exact10(10)), -truncatedQuotient(Exact10(1), Exact10(10)));
  EXPECT_EQ((Exact10(0x1p-1074) * Exact10(1.5)).truncated(), 0x1p-1074) << "a subnormal, truncated";
  EXPECT_EQ((Exact10(0x1p-1074) * Exact10(0.5)).truncated(), 0.0) << "below the smallest subnormal";
  EXPECT_EQ((Exact10(0x1p1023) * Exact10(4)).truncated(), std::numeric_limits<double>::infinity());
  EXPECT_EQ(truncatedQuotient(Exact10(0x1p1023), Exact10(0x1p-10)), std::numeric_limits<double>::infinity());
  EXPECT_EQ(Exact10(0.1) + Exact10(0.2) == Exact10(0.3), false) << "exact: 0.1 + 0.2 is not the double 0.3";
  EXPECT_EQ((Exact10(0.1) + Exact10(0.2) - Exact10(0.1) - Exact10(0.2)).sign(), 0);
}

// The widest value a degree-ten expression can take: products of ten doubles from both
// ends of the range, summed. It fits (the capacity's bound, argued in exact.hpp, holds
// with no check failing) and is exact.
TEST(ExactNumber, TheWidestValueOfItsDegreeFitsAndIsExact) {
  Exact10 huge = 1, tiny = 1;
  mpq_class hugeQ = 1, tinyQ = 1;
  for (int k = 0; k < 10; ++k) {
    const double big = std::nextafter(std::numeric_limits<double>::max(), 0.0), small = 3 * 0x1p-1074;
    huge *= big, hugeQ *= mpq_class(big);
    tiny *= small, tinyQ *= mpq_class(small);
  }
  const Exact10 sum = huge + tiny - Exact10(1);
  const mpq_class sumQ = hugeQ + tinyQ - 1;
  EXPECT_EQ(sum.sign(), sgn(sumQ));
  EXPECT_EQ((sum - huge).sign(), sgn(sumQ - hugeQ)) << "the tiny part is kept beside the huge one";
  EXPECT_TRUE(sameBits(truncatedQuotient(tiny, huge), mpq_class(tinyQ / hugeQ).get_d()));
}

TEST(ExactNumber, AgreesWithGmpOnAdversarialExpressions) {
  std::mt19937_64 random(20261127);
  using Exact = ExactNumber<6>;
  for (int i = 0; i < 100000; ++i) {
    double v[6];
    for (double& x : v) x = adversarial(random);
    const Exact a = Exact(v[0]) - v[1], b = Exact(v[2]) * v[3] - Exact(v[4]) * v[5];
    const mpq_class qa = mpq_class(v[0]) - v[1], qb = mpq_class(v[2]) * v[3] - mpq_class(v[4]) * v[5];
    const Exact p = a * b * a - b * b + v[5];
    const mpq_class qp = qa * qb * qa - qb * qb + v[5];
    ASSERT_EQ(p.sign(), sgn(qp)) << i;
    ASSERT_TRUE(sameBits(p.truncated(), qp.get_d()) || (p.truncated() == 0 && qp.get_d() == 0)) << i;
    if (b.sign() != 0) {
      ASSERT_TRUE(sameBits(truncatedQuotient(p, b), mpq_class(qp / qb).get_d())) << i;
    }
    ASSERT_EQ(compare(a, b), sgn(qa - qb)) << i;
  }
}

// Points near a plane (or a line), built to defeat double precision: a, b, c adversarial
// or of one magnitude, d an affine combination of them rounded, or a grid point, or one
// of them exactly; all moved far from the origin or shrunk toward zero at times.
TEST(ExactPredicates, AgreeWithGmpOnAdversarialInputs) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  ExactPredicates predicates;
  int zeros = 0;
  for (int i = 0; i < 100000; ++i) {
    const double scale = std::ldexp(1.0, std::uniform_int_distribution<int>(-300, 40)(random));
    const dvec3 offset = i % 3 == 0 ? dvec3(unit(random), unit(random), unit(random)) * 1e7 : dvec3(0);
    const auto point = [&] {
      if (i % 5 == 0) return dvec3(adversarial(random), adversarial(random), adversarial(random));
      if (i % 7 == 0) return dvec3(std::round(unit(random) * 8), std::round(unit(random) * 8), std::round(unit(random) * 8)) * scale + offset;
      return dvec3(unit(random), unit(random), unit(random)) * scale + offset;
    };
    const dvec3 a = point(), b = point(), c = point();
    const double s = unit(random), t = unit(random);
    dvec3 d = a + s * (b - a) + t * (c - a);
    if (i % 11 == 0) d = b;
    mpq_class u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) u[k] = mpq_class(b[k]) - a[k], v[k] = mpq_class(c[k]) - a[k], w[k] = mpq_class(d[k]) - a[k];
    const mpq_class det3 = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
    const mpq_class det2 = u[0] * v[1] - u[1] * v[0];
    ASSERT_EQ(predicates.orient3d(a, b, c, d), sgn(det3)) << i;
    ASSERT_EQ(predicates.orient2d(a, b, c), sgn(det2)) << i;
    // The value carries the exact sign, even where it lies below the smallest double.
    const double value = predicates.orient3dValue(a, b, c, d);
    ASSERT_EQ((value > 0) - (value < 0), sgn(det3)) << i;
    zeros += sgn(det3) == 0;
  }
  EXPECT_GT(predicates.exactFallbacks, 1000) << "the inputs must reach the exact arithmetic to mean anything";
  EXPECT_GT(zeros, 1000) << "and exact ties";
}

// The reference's exact Woop test as it was written in GMP's rationals: the shear
// divided out, t a quotient, the view distance compared with near and far.
std::optional<mpq_class> rationalHit(const Ray& ray, const CameraTransform& camera, const dvec3& a, const dvec3& b, const dvec3& c) {
  const woop::ShearedRay<mpq_class> shear(ray);
  const woop::WoopTerms<mpq_class> terms = woop::woopTerms(shear, a, b, c);
  const bool allNonNegative = terms.u >= 0 && terms.v >= 0 && terms.w >= 0;
  const bool allNonPositive = terms.u <= 0 && terms.v <= 0 && terms.w <= 0;
  if (!(allNonNegative || allNonPositive) || terms.det == 0) return std::nullopt;
  const mpq_class t = terms.scaledT / terms.det;
  mpq_class distance = 0;
  for (int i = 0; i < 3; ++i)
    distance += t * mpq_class(ray.direction[i]) * camera.forward()[i] + (mpq_class(ray.origin[i]) - camera.camera().eye[i]) * camera.forward()[i];
  if (distance < camera.camera().near || distance > camera.camera().far) return std::nullopt;
  return t;
}

// One triangle's exact hit both ways: the same decision, the same parameter.
void expectSameHit(const reference_search::RayQuery& query, const Ray& ray, const CameraTransform& camera, const dvec3& a,
                   const dvec3& b, const dvec3& c, int& hits) {
  const std::optional<woop::ExactParameter> exact = query.exactHit(a, b, c);
  const std::optional<mpq_class> rational = rationalHit(ray, camera, a, b, c);
  ASSERT_EQ(exact.has_value(), rational.has_value());
  if (!exact) return;
  ++hits;
  ASSERT_TRUE(sameBits(exact->truncated(), rational->get_d()));
  ASSERT_EQ(exact->compareWith(0.5), sgn(*rational - 0.5));
}

TEST(ExactWoop, AgreesWithGmpOnRandomRaysAndTrianglesThroughEdgesAndCorners) {
  const test::LoadedScene loaded(test::sourcePath("scenes/cube.toml"), 64);
  const CameraTransform camera = loaded.prepared.camera();
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray ray = camera.rayThroughPixel(32 + 30 * unit(random), 24 + 22 * unit(random));
    const double along = 1 + 5 * std::abs(unit(random));
    const dvec3 center = ray.origin + along * ray.direction;
    const double size = std::ldexp(1.0, std::uniform_int_distribution<int>(-30, 3)(random));
    dvec3 a = center + size * dvec3(unit(random), unit(random), unit(random));
    dvec3 b = center + size * dvec3(unit(random), unit(random), unit(random));
    dvec3 c = center + size * dvec3(unit(random), unit(random), unit(random));
    // Every other triangle has the ray's point on an edge or at a corner, as rounding allows.
    if (i % 2 == 0) b = center + (center - a);
    if (i % 6 == 0) c = center;
    reference_search::RayQuery query(ray, camera);
    expectSameHit(query, ray, camera, a, b, c, hits);
    expectSameHit(query, ray, camera, b, a, c, hits);
  }
  EXPECT_GT(hits, 5000);
}

// Every ray of every shipped scene and hard case that needed exact arithmetic, and every
// triangle whose box it meets: the exact test decides as the rational one, to the bit.
TEST(ExactWoop, AgreesWithGmpOnEveryFallBackOfTheShippedScenes) {
  int rays = 0, triangles = 0, hits = 0;
  for (const auto& file : test::shippedScenes()) {
    if (test::isStudyLevel(file)) continue;
    const test::LoadedScene loaded(file, 96);
    Stats stats;
    const CameraTransform camera = loaded.prepared.camera();
    const SurfaceReference reference(loaded.prepared, stats);
    const Bvh& bvh = loaded.prepared.triangleBvh(stats);
    const auto& leaves = loaded.prepared.leafTriangles(stats);
    for (int y = 0; y < camera.height(); ++y)
      for (int x = 0; x < camera.width(); ++x) {
        const Ray ray = camera.rayThroughPixel(conventions::pixelCenter(x), conventions::pixelCenter(y));
        SurfaceReference::Counters counters;
        if (!reference.trace(camera, ray, counters).usedExact) continue;
        ++rays;
        const reference_search::RayQuery query(ray, camera);
        const RayBoxTest boxes(ray.origin, ray.direction);
        bvh.visitPrimitives([&](const BvhNode& node) { return boxes.entry(node, std::numeric_limits<double>::infinity()) < std::numeric_limits<double>::infinity(); },
                            [&](std::uint32_t, std::uint32_t slot) {
                              ++triangles;
                              expectSameHit(query, ray, camera, leaves[slot].a, leaves[slot].b, leaves[slot].c, hits);
                            });
      }
  }
  EXPECT_GT(rays, 100);
  EXPECT_GT(hits, 100);
  std::printf("%d fall-back rays, %d triangles met, %d hits: the same decisions and parameters\n", rays, triangles, hits);
}

}  // namespace
}  // namespace hsr
