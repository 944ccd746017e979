// Which of an algorithm's differences from the exact reference its documented
// tolerances excuse. Every exact algorithm may show another triangle than the reference
// at a pixel the reference decides uniquely for one of two reasons (each algorithm's
// README, "Agreement with the reference"):
//   snapping: the pixel center lies within 1/256 pixel of either triangle's projected
//     outline (the rasterizer snaps vertices to 1/256 pixel, which moves an edge by at
//     most sqrt(2)/512 pixel);
//   depth tie: both triangles meet the pixel's ray at depths the algorithm cannot order
//     (a depth format's resolution, or rounding for the exact ones).
// Every other differing pixel is unexplained: a bug. The tests judge the shipped
// algorithms this way, and hsr grade a student's (grading/).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/raster/depth.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/scene/prepare.hpp"

namespace hsr {

inline double distanceToSegment(const dvec2& p, const dvec2& a, const dvec2& b) {
  const dvec2 ab = b - a;
  const double along = glm::dot(ab, ab) > 0 ? std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0) : 0.0;
  return glm::length(p - (a + along * ab));
}

// The outline in pixel coordinates of the part of a triangle in front of the near
// plane: its corners there, and where its edges cross the plane (the rasterizer clips
// there, so a triangle cut by the plane has an edge along the cut). Empty when the whole
// triangle is behind the plane.
inline std::vector<dvec2> projectedOutline(const PreparedScene& scene, const CameraTransform& camera, std::uint32_t triangle) {
  const double near = camera.camera().near;
  std::vector<dvec2> outline;
  for (int k = 0; k < 3; ++k) {
    const dvec3 a = scene.positions()[scene.triangles()[triangle][std::size_t(k)]];
    const dvec3 b = scene.positions()[scene.triangles()[triangle][std::size_t((k + 1) % 3)]];
    const ClipVertex va = camera.clipFromWorld(a), vb = camera.clipFromWorld(b);
    if (va.d >= near) outline.push_back(camera.pixelFromClip(va));
    if ((va.d >= near) != (vb.d >= near)) {
      outline.push_back(camera.pixelFromClip(camera.clipFromWorld(a + (va.d - near) / (va.d - vb.d) * (b - a))));
    }
  }
  return outline;
}

// Distance in pixels from a point to a triangle's projected (near-clipped) boundary;
// +infinity when the triangle is wholly behind the near plane.
inline double distanceToProjectedEdges(const PreparedScene& scene, const CameraTransform& camera, std::uint32_t triangle,
                                       const dvec2& point) {
  const std::vector<dvec2> outline = projectedOutline(scene, camera, triangle);
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < outline.size(); ++k)
    nearest = std::min(nearest, distanceToSegment(point, outline[k], outline[(k + 1) % outline.size()]));
  return nearest;
}

// Snapping vertices to 1/256 pixel moves an edge by at most sqrt(2)/512 pixel: a pixel
// center nearer than this to a triangle's projected boundary may be covered or not.
inline constexpr double kSnapDistance = 1.0 / 256;

// The smallest distance from a point to the projected boundary of any of the triangles
// with these ids (global index + 1; 0 is skipped).
inline double nearestProjectedEdge(const PreparedScene& scene, const CameraTransform& camera,
                                   std::initializer_list<std::uint32_t> ids, const dvec2& point) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const std::uint32_t id : ids)
    if (id != 0) nearest = std::min(nearest, distanceToProjectedEdges(scene, camera, id - 1, point));
  return nearest;
}

// Where a ray meets a triangle's plane: the point's barycentric coordinates u and v (it
// lies in the triangle when u, v >= 0 and u + v <= 1) and its view distance
// (Moller-Trumbore in double; for classifying the few pixels where algorithms differ).
struct PlaneHit {
  double u, v, distance;
};
inline PlaneHit planeHit(const PreparedScene& scene, const CameraTransform& camera, std::uint32_t triangle, const Ray& ray) {
  const Triangle& t = scene.triangles()[triangle];
  const dvec3 a = scene.positions()[t[0]], e1 = scene.positions()[t[1]] - a, e2 = scene.positions()[t[2]] - a;
  const dvec3 p = glm::cross(ray.direction, e2);
  const double det = glm::dot(e1, p);
  const dvec3 s = ray.origin - a;
  const double along = glm::dot(e2, glm::cross(s, e1)) / det;
  return {glm::dot(s, p) / det, glm::dot(ray.direction, glm::cross(s, e1)) / det,
          glm::dot(ray.origin + along * ray.direction - camera.camera().eye, camera.forward())};
}

// The view distance at which a ray meets a triangle, or NaN when it misses it.
inline double hitDistance(const PreparedScene& scene, const CameraTransform& camera, std::uint32_t triangle, const Ray& ray) {
  const auto [u, v, distance] = planeHit(scene, camera, triangle, ray);
  return u >= 0 && v >= 0 && u + v <= 1 ? distance : NAN;
}

// An exact algorithm's depth tolerance: whether two view distances at a pixel center are
// too close for it to order. The painter's and ray casting's: coplanar up to rounding
// (the painter's, a few roundings of the placements, renderer/geometry/rounding.hpp, far under
// 1e-12 of the depth in these scenes); 1e-9 here, for the rounding of this check itself
// (plain double Moller-Trumbore).
using DepthTie = std::function<bool(double shown, double exact)>;
inline bool coplanar(double shown, double exact) { return std::abs(shown - exact) <= 1e-9 * std::abs(exact); }

// The z-buffer's, for a depth format: the two depths, stored in the format, are at most
// two of its steps apart (the fragment's plane and the reference's ray round differently).
inline DepthTie depthFormatTie(DepthFormat format, const CameraTransform& camera) {
  const DepthEncoding encoding = depthEncoding(format, camera);
  return [format, camera, encoding](double shown, double exact) {
    return withDepthFormat(format, [&]<typename Format>() {
      auto nearer = Format::store(encoding.z(camera.screenAffineDepth(shown)));
      auto farther = Format::store(encoding.z(camera.screenAffineDepth(exact)));
      if (Format::nearer(farther, nearer)) std::swap(nearer, farther);
      for (int step = 0; step <= 2; ++step, nearer = Format::towardFar(nearer))
        if (nearer == farther) return true;
      return false;
    });
  };
}
inline DepthTie float32DepthTie(const CameraTransform& camera) { return depthFormatTie(DepthFormat::float32, camera); }

// An exact algorithm may show another triangle than the reference at a non-ambiguous
// pixel for one of two documented reasons (each algorithm's README):
//   snapping: the center lies within 1/256 pixel of either triangle's projected outline;
//   depth tie: both triangles meet the pixel's ray at depths the algorithm cannot order.
// Every other differing pixel is unexplained: a bug.
struct WrongPixels {
  long snapping = 0, depthTie = 0, unexplained = 0;
  std::string firstUnexplained;  // "pixel x,y shows id a, exactly id b", for the failure message
  long total() const { return snapping + depthTie + unexplained; }
};

// Classifies the pixels where `shown` differs from `exact` (ids, 0 = background) and
// `ambiguous` is 0.
// `tiedOrder`, when given, excuses a pixel where the two ids' order is a tie for the
// algorithm's own ordering (the depth sort's keys), as a depth tie. `rendered`, when
// given, is the scene the frame was drawn from, with `idsPerOriginal` of its triangles
// in place of each of `scene`'s (a subdivision): snapping moves its triangles' edges too.
inline WrongPixels classifyDifferences(const PreparedScene& scene, std::span<const std::uint32_t> shown,
                                       std::span<const std::uint32_t> exact, std::span<const std::uint8_t> ambiguous,
                                       const DepthTie& tied,
                                       const std::function<bool(std::uint32_t, std::uint32_t)>& tiedOrder = nullptr,
                                       const PreparedScene* rendered = nullptr, std::uint32_t idsPerOriginal = 1) {
  const CameraTransform& camera = scene.camera();
  const auto nearestRenderedEdge = [&](std::initializer_list<std::uint32_t> ids, const dvec2& center) {
    double nearest = std::numeric_limits<double>::infinity();
    if (!rendered) return nearest;
    const CameraTransform& renderedCamera = rendered->camera();
    for (const std::uint32_t id : ids)
      for (std::uint32_t k = 0; id != 0 && k < idsPerOriginal; ++k)
        nearest = std::min(nearest, distanceToProjectedEdges(*rendered, renderedCamera, (id - 1) * idsPerOriginal + k, center));
    return nearest;
  };
  WrongPixels result;
  for (std::size_t p = 0; p < shown.size(); ++p) {
    if (ambiguous[p] || shown[p] == exact[p]) continue;
    const dvec2 center(double(p % std::size_t(scene.width())) + 0.5, double(p / std::size_t(scene.width())) + 0.5);
    if (nearestProjectedEdge(scene, camera, {shown[p], exact[p]}, center) < kSnapDistance ||
        nearestRenderedEdge({shown[p], exact[p]}, center) < kSnapDistance) {
      ++result.snapping;
      continue;
    }
    if (shown[p] != 0 && exact[p] != 0) {
      const Ray ray = camera.rayThroughPixel(center.x, center.y);
      const double shownDistance = hitDistance(scene, camera, shown[p] - 1, ray);
      const double exactDistance = hitDistance(scene, camera, exact[p] - 1, ray);
      if ((std::isfinite(shownDistance) && std::isfinite(exactDistance) && tied(shownDistance, exactDistance)) ||
          (tiedOrder && tiedOrder(shown[p], exact[p]))) {
        ++result.depthTie;
        continue;
      }
    }
    if (result.unexplained++ == 0)
      result.firstUnexplained = "pixel " + std::to_string(p % std::size_t(scene.width())) + "," +
                                std::to_string(p / std::size_t(scene.width())) + " shows id " + std::to_string(shown[p]) +
                                ", exactly id " + std::to_string(exact[p]);
  }
  return result;
}

inline WrongPixels classifyWrongPixels(const PreparedScene& scene, const Frame& frame, const ReferenceImage& truth,
                                       const DepthTie& tied = coplanar) {
  return classifyDifferences(scene, frame.ids, truth.frame.ids, truth.ambiguous, tied);
}


}  // namespace hsr
