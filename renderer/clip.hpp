// Homogeneous clipping (Sutherland–Hodgman in clip space). The near plane is always
// clipped, so a triangle reaching behind the eye is cut there, never projected through
// the eye and wrapped around. x and y are clipped only at the guard band, far outside
// the image: the rasterizer's bounding box does the rest, and most triangles that
// cross an image edge are never clipped at all.
#pragma once

#include <array>
#include <cstdint>

#include "renderer/camera.hpp"

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
  double distance(const ClipVertex& v, ClipPlane plane) const;
  std::uint32_t outside(const ClipVertex& v) const;  // the planes v is strictly outside of
};

// A convex polygon; each clipping plane adds at most one vertex to a triangle.
struct ClipPolygon {
  std::array<ClipVertex, 9> vertices;
  int count = 0;
};

// Clips a triangle against the planes in `planes` (a subset of kClippingPlanes).
ClipPolygon clipTriangle(const std::array<ClipVertex, 3>& triangle, const ClipVolume& volume, std::uint32_t planes);

}  // namespace hsr
