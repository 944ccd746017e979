#include "renderer/reference/tile_proof.hpp"

#include <algorithm>
#include <cmath>

namespace hsr {
namespace {

// How far inside a halfspace a point must be computed to lie for the test to count it
// out, as a fraction of the magnitudes its value is computed from. The rounding of that
// value, and of the normal it uses, is a few units of 2^-53 of the same magnitudes.
constexpr double kMargin = 1e-9;

// a x b, and the magnitudes its components are computed from: |a_j b_k| + |a_k b_j|,
// which bound the rounding of each component up to a few units of 2^-53.
struct Cross {
  dvec3 value, magnitude;
};
Cross crossWithMagnitude(const dvec3& a, const dvec3& b) {
  const dvec3 magnitude(std::abs(a.y * b.z) + std::abs(a.z * b.y), std::abs(a.z * b.x) + std::abs(a.x * b.z),
                        std::abs(a.x * b.y) + std::abs(a.y * b.x));
  return {glm::cross(a, b), magnitude};
}

}  // namespace

// The margin covers the rounding of the value's terms, which is relative to the
// differences p - anchor, and the rounding of the points themselves (a corner of the
// region, a ray's origin under orthographic), which is relative to their coordinates:
// far from the origin, the larger.
TileRegion::Halfspace TileRegion::Halfspace::through(const dvec3& normal, const dvec3& magnitude, const dvec3& anchor, double offset,
                                                     const Aabb& reach) {
  dvec3 farthest, largest;
  for (int axis = 0; axis < 3; ++axis) {
    farthest[axis] = std::max(std::abs(reach.lo[axis] - anchor[axis]), std::abs(reach.hi[axis] - anchor[axis]));
    largest[axis] = std::max({std::abs(reach.lo[axis]), std::abs(reach.hi[axis]), std::abs(anchor[axis])});
  }
  return {normal, anchor, offset, kMargin * (glm::dot(magnitude, farthest + largest) + std::abs(offset))};
}

bool TileRegion::Halfspace::surelyOutside(const dvec3& p) const { return glm::dot(normal, p - anchor) - offset < -margin; }

bool TileRegion::Halfspace::surelyOutside(const Aabb& box) const {
  // The box's corner where the value is greatest.
  return surelyOutside({normal.x >= 0 ? box.hi.x : box.lo.x, normal.y >= 0 ? box.hi.y : box.lo.y, normal.z >= 0 ? box.hi.z : box.lo.z});
}

std::optional<TileRegion> TileRegion::of(const CameraTransform& camera, const Aabb& scene, double x0, double y0, double x1, double y1,
                                         const PreparedScene::LeafTriangle* candidate) {
  TileRegion region;
  region.perspective_ = camera.perspective();
  region.eye_ = camera.camera().eye;
  region.forward_ = camera.forward();
  // The four sides: the plane through each two neighbouring corner rays, facing the ray
  // through the rectangle's middle.
  const std::array<Ray, 4> corners = {camera.rayThroughPixel(x0, y0), camera.rayThroughPixel(x1, y0), camera.rayThroughPixel(x1, y1),
                                      camera.rayThroughPixel(x0, y1)};
  const Ray middle = camera.rayThroughPixel((x0 + x1) / 2, (y0 + y1) / 2);
  for (int side = 0; side < 4; ++side) {
    const Ray& from = corners[std::size_t(side)];
    const Ray& to = corners[std::size_t((side + 1) % 4)];
    // Through `from` and along both rays: from the eye under perspective (the origins
    // agree), along the view axis through the near-plane rectangle's edge under
    // orthographic (the directions agree).
    const Cross normal = crossWithMagnitude(from.direction, (to.origin - from.origin) + to.direction);
    const double facing = glm::dot(normal.value, (middle.origin + middle.direction) - from.origin);
    if (!std::isfinite(facing) || facing == 0) return std::nullopt;
    region.halfspaces_[std::size_t(side)] = Halfspace::through(facing > 0 ? normal.value : -normal.value, normal.magnitude, from.origin, 0, scene);
  }
  // Beyond the near plane (a hit before it is no hit), and before the far plane where
  // nothing is met, else on the side of the candidate's plane the rays come from: the
  // eye's under perspective, and under orthographic the side the view axis leaves (every
  // ray that meets the plane ahead of it comes from there).
  const Camera& view = camera.camera();
  Halfspace& nearPlane = region.halfspaces_[4];
  Halfspace& back = region.halfspaces_[5];
  nearPlane = Halfspace::through(region.forward_, glm::abs(region.forward_), region.eye_, view.near, scene);
  if (!candidate) {
    back = Halfspace::through(-region.forward_, glm::abs(region.forward_), region.eye_, -view.far, scene);
  } else {
    region.candidate_ = candidate->id;
    const Cross normal = crossWithMagnitude(candidate->b - candidate->a, candidate->c - candidate->a);
    const dvec3 toward = region.perspective_ ? region.eye_ - candidate->a : -region.forward_;
    const double side = glm::dot(normal.value, toward);
    if (!(std::abs(side) > kMargin * glm::dot(normal.magnitude, glm::abs(toward)))) return std::nullopt;
    back = Halfspace::through(side > 0 ? normal.value : -normal.value, normal.magnitude, candidate->a, 0, scene);
  }
  // The region's eight corners: where each corner ray crosses the near plane and the back
  // one, the near first on every ray. Then the region is their convex hull (the
  // reciprocal of a plane's parameter along the rays is linear across them, so the
  // planes keep their order inside the frustum too).
  for (int i = 0; i < 4; ++i) {
    const Ray& ray = corners[std::size_t(i)];
    // Where the ray crosses a plane: none where it runs along it, or so nearly that the
    // parameter would pass 1e200 (no region then; and no division by zero, nor overflow).
    const auto crossing = [&](const Halfspace& plane) -> std::optional<double> {
      const double toPlane = plane.offset - glm::dot(plane.normal, ray.origin - plane.anchor);
      const double along = glm::dot(plane.normal, ray.direction);
      if (!(std::abs(along) > std::abs(toPlane) * 1e-200)) return std::nullopt;
      return toPlane / along;
    };
    const std::optional<double> nearT = crossing(nearPlane), backT = crossing(back);
    if (!nearT || !backT || !(*nearT < *backT)) return std::nullopt;
    region.corners_[std::size_t(i)] = ray.origin + *nearT * ray.direction;
    region.corners_[std::size_t(i) + 4] = ray.origin + *backT * ray.direction;
  }
  // What the planes of apart() are tested over: every triangle, and these corners.
  region.reach_ = scene;
  for (const dvec3& corner : region.corners_) region.reach_.grow(corner);
  return region;
}

// Whether some plane separates the triangle from the region: one of the region's six
// faces, with the triangle's corners all surely outside; or the triangle's own plane, or
// the plane through one of its edges and the rays' origin (its direction under
// orthographic) on the triangle's side of it, with the region's eight corners all
// surely on the other side. The last are what part a tile from a triangle beside its
// candidate in the same plane, and from the far side of a large triangle it overlooks.
bool TileRegion::apart(const PreparedScene::LeafTriangle& triangle) const {
  const std::array<dvec3, 3> points = {triangle.a, triangle.b, triangle.c};
  for (const Halfspace& face : halfspaces_)
    if (std::all_of(points.begin(), points.end(), [&](const dvec3& p) { return face.surelyOutside(p); })) return true;
  const auto cornersOutside = [&](const Halfspace& plane) {
    return std::all_of(corners_.begin(), corners_.end(), [&](const dvec3& p) { return plane.surelyOutside(p); });
  };
  const Cross normal = crossWithMagnitude(triangle.b - triangle.a, triangle.c - triangle.a);
  const Halfspace ownPlane = Halfspace::through(normal.value, normal.magnitude, triangle.a, 0, reach_);
  if (cornersOutside(ownPlane) || cornersOutside(ownPlane.flipped())) return true;
  for (int edge = 0; edge < 3; ++edge) {
    const dvec3& from = points[std::size_t(edge)];
    const dvec3& to = points[std::size_t((edge + 1) % 3)];
    const dvec3& opposite = points[std::size_t((edge + 2) % 3)];
    const Cross edgeNormal = crossWithMagnitude(to - from, perspective_ ? eye_ - from : forward_);
    const double facing = glm::dot(edgeNormal.value, opposite - from);
    if (facing != 0 && cornersOutside(Halfspace::through(facing > 0 ? edgeNormal.value : -edgeNormal.value, edgeNormal.magnitude, from, 0, reach_)))
      return true;
  }
  return false;
}

bool TileRegion::touchedByAnother(const Bvh& bvh, const std::vector<PreparedScene::LeafTriangle>& triangles, std::int64_t& nodesVisited) const {
  if (bvh.empty()) return false;
  const std::vector<BvhNode>& nodes = bvh.nodes();
  std::array<std::uint32_t, Bvh::kMaxDepth + 1> stack;
  int size = 0;
  stack[size++] = 0;
  while (size > 0) {
    const BvhNode& node = nodes[stack[--size]];
    ++nodesVisited;
    const Aabb box = node.box();
    if (std::any_of(halfspaces_.begin(), halfspaces_.end(), [&](const Halfspace& face) { return face.surelyOutside(box); })) continue;
    if (!node.leaf()) {
      stack[size++] = node.index;
      stack[size++] = node.index + 1;
      continue;
    }
    for (std::uint32_t slot = node.index; slot < node.index + node.count; ++slot)
      if (triangles[slot].id != candidate_ && !apart(triangles[slot])) return true;
  }
  return false;
}

}  // namespace hsr
