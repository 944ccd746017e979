// Homogeneous clipping (Sutherland–Hodgman in clip space). The near plane is always
// clipped, so a triangle reaching behind the eye is cut there, never projected through
// the eye and wrapped around. x and y are clipped only at the guard band, far outside
// the image: the rasterizer's bounding box does the rest, and most triangles that
// cross an image edge are never clipped at all.
#pragma once

#include <array>
#include <cstdint>

#include "renderer/geometry/camera.hpp"

namespace hsr {

// Each plane is a half-space "distance >= 0" of a clip vertex.
enum ClipPlane : std::uint32_t {
  kNearPlane = 1u << 0,
  kFarPlane = 1u << 1,
  kGuardLeft = 1u << 2,
  kGuardRight = 1u << 3,
  kGuardBottom = 1u << 4,
  kGuardTop = 1u << 5,
  kViewLeft = 1u << 6,  // the image's own edges: used only to reject triangles wholly outside
  kViewRight = 1u << 7,
  kViewBottom = 1u << 8,
  kViewTop = 1u << 9,
};
inline constexpr std::uint32_t kClippingPlanes = kNearPlane | kFarPlane | kGuardLeft | kGuardRight | kGuardBottom | kGuardTop;

struct ClipVolume {
  double near, far;
  bool clipFar;
  double guardX, guardY;  // guard band half-width and half-height in NDC units

  ClipVolume(const CameraTransform& camera, bool clipFar);

  // How far inside the plane a vertex lies (negative: outside), for one vertex or four in
  // lanes (Real as in ClipCoordinates).
  template <typename Real>
  HSR_INLINE Real distance(const ClipCoordinates<Real>& v, ClipPlane plane) const {
    switch (plane) {
      case kNearPlane: return v.d - near;
      case kFarPlane: return far - v.d;
      case kGuardLeft: return guardX * v.w + v.x;
      case kGuardRight: return guardX * v.w - v.x;
      case kGuardBottom: return guardY * v.w + v.y;
      case kGuardTop: return guardY * v.w - v.y;
      case kViewLeft: return v.w + v.x;
      case kViewRight: return v.w - v.x;
      case kViewBottom: return v.w + v.y;
      case kViewTop: return v.w - v.y;
    }
    return broadcast<Real>(0);
  }

  // The planes v is strictly outside of, as bits: a std::uint32_t for one vertex, a
  // Mask4 holding each lane's bits for four. One call per plane with a constant
  // argument: each inlines to its plane equation, and the result is straight-line code
  // (this runs once per vertex per frame).
  template <typename Real>
  HSR_INLINE auto outside(const ClipCoordinates<Real>& v) const {
    auto bits = bitOutside(v, kNearPlane) | bitOutside(v, kGuardLeft) | bitOutside(v, kGuardRight) | bitOutside(v, kGuardBottom) |
                bitOutside(v, kGuardTop) | bitOutside(v, kViewLeft) | bitOutside(v, kViewRight) | bitOutside(v, kViewBottom) |
                bitOutside(v, kViewTop);
    if (clipFar) bits |= bitOutside(v, kFarPlane);
    return bits;
  }

 private:
  // The plane's bit where v lies strictly outside it. (A function, not a lambda: a
  // lambda is not always inlined, and one compiled for the baseline, returning four
  // lanes to an AVX2 caller, would disagree with it on where they are passed.)
  template <typename Real>
  HSR_INLINE auto bitOutside(const ClipCoordinates<Real>& v, ClipPlane plane) const {
    return bitWhereNegative(distance(v, plane), plane);
  }
  HSR_INLINE static std::uint32_t bitWhereNegative(double distance, ClipPlane plane) { return distance < 0 ? std::uint32_t(plane) : 0u; }
  HSR_INLINE static Mask4 bitWhereNegative(Double4 distance, ClipPlane plane) { return (distance < 0.0) & std::int64_t(plane); }
};

// A convex polygon; each clipping plane adds at most one vertex to a triangle.
struct ClipPolygon {
  std::array<ClipVertex, 9> vertices;
  int count = 0;
};

// Clips a triangle against the planes in `planes` (a subset of kClippingPlanes).
ClipPolygon clipTriangle(const std::array<ClipVertex, 3>& triangle, const ClipVolume& volume, std::uint32_t planes);

}  // namespace hsr
