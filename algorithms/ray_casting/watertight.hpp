// The watertight ray-triangle test (Woop, Benthin and Wald 2013), shared by the exact
// variants (naive, bvh) and the fast paths. Set up once per ray: a permutation and shear
// that map the ray onto the +z axis from the origin, so that the test of a triangle
// reduces to the signs of three 2D edge functions at (0, 0). An edge shared by two
// triangles gives them exactly opposite edge functions (the same products, subtracted
// the other way round), so a ray through the edge cannot slip between them: no cracks in
// a closed mesh, whatever the rounding.
//
// Number is double for one ray, or Double4 (renderer/util/simd.hpp) for four rays that share
// the permutation, one per lane: the same operations in the same order on each lane, so
// the same bits as four single rays.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "algorithms/ray_casting/cast.hpp"
#include "renderer/geometry/camera.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/steps/why.hpp"
#include "renderer/util/math.hpp"

namespace hsr::ray_casting {

// Steps 3 and 4 for one triangle: the scaled barycentrics u, v, w, and the vertices'
// sheared z relative to the origin, which step 5 interpolates.
template <typename Number>
struct ScaledBarycentrics {
  Number u, v, w;
  Number az, bz, cz;
};

template <typename Number>
class WatertightRay {
 public:
  // Step 1: kz, the axis the direction is largest along; kx, ky the other two, swapped
  // when the ray runs down kz so the triangle's winding is kept.
  static int largestAxis(const dvec3& direction) {
    const dvec3 size = glm::abs(direction);
    return size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
  }
  static std::array<int, 3> permutation(const dvec3& direction) {
    const int kz = largestAxis(direction);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (direction[kz] < 0) std::swap(kx, ky);
    return {kx, ky, kz};
  }

  // One ray (Number = double). inverseDirection: 1 / ray.direction, per axis (the slab
  // test needs it too).
  WatertightRay(const Ray& ray, const dvec3& inverseDirection) : WatertightRay(permutation(ray.direction)) {
    // Step 2: the shear that takes the direction to (0, 0, 1).
    for (int axis = 0; axis < 3; ++axis) origin[axis] = ray.origin[axis];
    shearZ = inverseDirection[kz];
    shearX = ray.direction[kx] * shearZ;
    shearY = ray.direction[ky] * shearZ;
  }
  // Rays set up lane by lane (Number = Double4): the caller fills origin and the shears.
  explicit WatertightRay(const std::array<int, 3>& axes) : kx(axes[0]), ky(axes[1]), kz(axes[2]) {}

  // Steps 3 and 4: the vertices relative to the origin, sheared in the xy plane, and the
  // 2D edge functions of the sheared triangle at (0, 0).
  ScaledBarycentrics<Number> barycentrics(const dvec3& a, const dvec3& b, const dvec3& c) const {
    const Number Az = a[kz] - origin[kz], Bz = b[kz] - origin[kz], Cz = c[kz] - origin[kz];
    const Number ax = (a[kx] - origin[kx]) - shearX * Az, ay = (a[ky] - origin[ky]) - shearY * Az;
    const Number bx = (b[kx] - origin[kx]) - shearX * Bz, by = (b[ky] - origin[ky]) - shearY * Bz;
    const Number cx = (c[kx] - origin[kx]) - shearX * Cz, cy = (c[ky] - origin[ky]) - shearY * Cz;
    return {cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax, Az, Bz, Cz};
  }

  // Step 5: the hit parameter t, the sheared z interpolated by the barycentrics over
  // det. (Written into t rather than returned: a vector of four doubles returned by a
  // function compiled for the baseline would be returned differently than where AVX is
  // enabled.)
  void hitParameter(const ScaledBarycentrics<Number>& s, const Number& det, Number& t) const {
    t = (s.u * (shearZ * s.az) + s.v * (shearZ * s.bz) + s.w * (shearZ * s.cz)) / det;
  }

  // The hit parameter when the ray meets the triangle in [tMin, tMax] (Number = double).
  bool hit(const dvec3& a, const dvec3& b, const dvec3& c, double tMin, double tMax, double& t) const {
    const ScaledBarycentrics<double> s = barycentrics(a, b, c);
    // The ray passes inside (or on an edge) when u, v, w share a sign; 0 counts as
    // either, so an edge belongs to both its triangles.
    if ((s.u < 0 || s.v < 0 || s.w < 0) && (s.u > 0 || s.v > 0 || s.w > 0)) return false;
    const double det = s.u + s.v + s.w;
    if (det == 0) return false;  // the ray lies in the triangle's plane: it sees the triangle edge-on
    hitParameter(s, det, t);
    return t >= tMin && t <= tMax;
  }

  Number origin[3];
  int kx, ky, kz;
  Number shearX, shearY, shearZ;
};

using PackedTriangle = PreparedScene::LeafTriangle;

// Offers a triangle to the nearest hit so far. The nearest wins; at exactly equal t the
// lower id does, so the answer does not depend on the order triangles are offered in
// (which is why naive and bvh give identical images).
// `nearest` starts as {background, tFar}: the first hit up to the far plane is taken.
// hsr why: the test of a triangle at a pixel asked about (history: its events; null
// otherwise), recorded before the nearest hit changes: what the ray met, and the outcome.
[[gnu::cold]] void witnessOffer(const WatertightRay<double>& ray, const PackedTriangle& triangle, const PixelRay& pixel, const Hit& nearest,
                  bool met, double t, bool nearer, std::vector<PixelEvent>& history);

inline void offer(const WatertightRay<double>& ray, const PackedTriangle& triangle, const PixelRay& pixel, Hit& nearest,
                  std::vector<PixelEvent>* history = nullptr) {
  double t = 0;
  const bool met = ray.hit(triangle.a, triangle.b, triangle.c, pixel.tNear, nearest.t, t);
  const bool nearer = met && (nearest.id == conventions::kBackgroundId || t < nearest.t || triangle.id < nearest.id);
  if (history) [[unlikely]] witnessOffer(ray, triangle, pixel, nearest, met, t, nearer, *history);
  if (nearer) nearest = {triangle.id, t};
}

}  // namespace hsr::ray_casting
