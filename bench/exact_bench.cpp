// The exact arithmetic (renderer/geometry/exact.hpp) against GMP's rationals, which it
// replaced, on what the reference really asks of it: the exact Woop test of every
// triangle a fall-back ray meets, on the rays of the shipped scenes that needed exact
// arithmetic (the hard cases' centers on shared edges, the dragon's duplicated faces),
// and the orient3d predicate's exact stage on points a few ulps off a plane.
//   build/bench/exact_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <gmpxx.h>

#include <vector>

#include "renderer/geometry/predicates.hpp"
#include "renderer/rays/bvh.hpp"
#include "renderer/reference/bounded_woop.hpp"
#include "renderer/reference/nearest_hit.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/util/conventions.hpp"

namespace {

using namespace hsr;

// One triangle a fall-back ray meets.
struct Case {
  Ray ray;
  dvec3 a, b, c;
};

// Every (ray, triangle) pair the reference's fall-backs test, over the hard cases.
const std::vector<Case>& fallBackCases() {
  static const std::vector<Case> cases = [] {
    std::vector<Case> all;
    for (const char* name : {"hard/shared_edges.toml", "hard/watertight.toml", "hard/coplanar.toml", "dragon.toml"}) {
      const Scene scene = loadScene(std::string(HSR_SOURCE_DIR) + "/scenes/" + name);
      PreparedScene prepared(scene);
      prepared.setSize(160, std::max(1, 160 * scene.height / scene.width));
      Stats stats;
      const CameraTransform camera = prepared.camera();
      const SurfaceReference reference(prepared, stats);
      const Bvh& bvh = prepared.triangleBvh(stats);
      const auto& leaves = prepared.leafTriangles(stats);
      for (int y = 0; y < camera.height(); ++y)
        for (int x = 0; x < camera.width(); ++x) {
          const Ray ray = camera.rayThroughPixel(conventions::pixelCenter(x), conventions::pixelCenter(y));
          SurfaceReference::Counters counters;
          if (!reference.trace(camera, ray, counters).usedExact) continue;
          const RayBoxTest boxes(ray.origin, ray.direction);
          bvh.visitPrimitives([&](const BvhNode& node) { return boxes.entry(node, 1e300) < 1e300; },
                              [&](std::uint32_t, std::uint32_t slot) { all.push_back({ray, leaves[slot].a, leaves[slot].b, leaves[slot].c}); });
        }
    }
    return all;
  }();
  return cases;
}

void exactWoop(benchmark::State& state) {
  const std::vector<Case>& cases = fallBackCases();
  for (auto _ : state)
    for (const Case& c : cases) {
      const woop::ExactTerms terms = woop::exactTerms(c.ray, c.a, c.b, c.c);
      benchmark::DoNotOptimize(woop::inside(terms) ? terms.t.truncated() : 0.0);
    }
  state.counters["cases"] = double(cases.size());
  state.SetItemsProcessed(std::int64_t(state.iterations() * cases.size()));
}
BENCHMARK(exactWoop)->Unit(benchmark::kMillisecond);

// The same test in GMP's rationals, as the reference computed it before.
void gmpWoop(benchmark::State& state) {
  const std::vector<Case>& cases = fallBackCases();
  for (auto _ : state)
    for (const Case& c : cases) {
      const woop::ShearedRay<mpq_class> shear(c.ray);
      const woop::WoopTerms<mpq_class> terms = woop::woopTerms(shear, c.a, c.b, c.c);
      const bool allNonNegative = terms.u >= 0 && terms.v >= 0 && terms.w >= 0, allNonPositive = terms.u <= 0 && terms.v <= 0 && terms.w <= 0;
      benchmark::DoNotOptimize((allNonNegative || allNonPositive) && terms.det != 0 ? mpq_class(terms.scaledT / terms.det).get_d() : 0.0);
    }
  state.SetItemsProcessed(std::int64_t(state.iterations() * fallBackCases().size()));
}
BENCHMARK(gmpWoop)->Unit(benchmark::kMillisecond);

// orient3d's last stage: points a few ulps off a plane whose differences are not exact.
std::vector<std::array<dvec3, 4>> nearPlanePoints() {
  std::vector<std::array<dvec3, 4>> points;
  const dvec3 a(0.1, 0.7, 0.3), b(24.3, 24.1, 0.2), c(0.3, 0.1, 1.7);
  for (int i = 0; i < 32; ++i)
    for (int j = 0; j < 32; ++j) points.push_back({a, b, c, a + 0.37 * (b - a) + 0.41 * (c - a) + dvec3(i * 0x1p-52, j * 0x1p-52, 0)});
  return points;
}

void exactOrient3d(benchmark::State& state) {
  const auto points = nearPlanePoints();
  ExactPredicates predicates;
  for (auto _ : state)
    for (const auto& p : points) benchmark::DoNotOptimize(predicates.orient3d(p[0], p[1], p[2], p[3]));
  state.counters["exact stage share"] = double(predicates.exactFallbacks) / double(predicates.evaluations);
  state.SetItemsProcessed(std::int64_t(state.iterations() * points.size()));
}
BENCHMARK(exactOrient3d)->Unit(benchmark::kMicrosecond);

void gmpOrient3d(benchmark::State& state) {
  const auto points = nearPlanePoints();
  for (auto _ : state)
    for (const auto& p : points) {
      mpq_class u[3], v[3], w[3];
      for (int k = 0; k < 3; ++k) u[k] = mpq_class(p[1][k]) - p[0][k], v[k] = mpq_class(p[2][k]) - p[0][k], w[k] = mpq_class(p[3][k]) - p[0][k];
      benchmark::DoNotOptimize(sgn(u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])));
    }
  state.SetItemsProcessed(std::int64_t(state.iterations() * points.size()));
}
BENCHMARK(gmpOrient3d)->Unit(benchmark::kMicrosecond);

}  // namespace
