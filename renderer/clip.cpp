#include "renderer/clip.hpp"

#include "renderer/conventions.hpp"

namespace hsr {

ClipVolume::ClipVolume(const CameraTransform& camera, bool clipFarPlane)
    : near(camera.camera().near),
      far(camera.camera().far),
      clipFar(clipFarPlane),
      guardX(conventions::kGuardBandPixels / (0.5 * camera.width())),
      guardY(conventions::kGuardBandPixels / (0.5 * camera.height())) {}

double ClipVolume::distance(const ClipVertex& v, ClipPlane plane) const {
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
  return 0;
}

std::uint32_t ClipVolume::outside(const ClipVertex& v) const {
  // One call per plane with a constant argument: each inlines to its plane equation,
  // and the result is straight-line code (this runs once per vertex per frame).
  const auto bit = [&](ClipPlane plane) { return distance(v, plane) < 0 ? std::uint32_t(plane) : 0u; };
  return bit(kNearPlane) | (clipFar ? bit(kFarPlane) : 0u) | bit(kGuardLeft) | bit(kGuardRight) | bit(kGuardBottom) |
         bit(kGuardTop) | bit(kViewLeft) | bit(kViewRight) | bit(kViewBottom) | bit(kViewTop);
}

ClipPolygon clipTriangle(const std::array<ClipVertex, 3>& triangle, const ClipVolume& volume, std::uint32_t planes) {
  ClipPolygon polygon;
  polygon.count = 3;
  std::copy(triangle.begin(), triangle.end(), polygon.vertices.begin());
  for (std::uint32_t plane = kNearPlane; plane <= kGuardTop && polygon.count > 0; plane <<= 1) {
    if (!(planes & plane)) continue;
    // Sutherland–Hodgman: walk the edges, keep inside vertices, and add the crossing
    // point of every edge that enters or leaves the half-space.
    ClipPolygon kept;
    for (int i = 0; i < polygon.count; ++i) {
      const ClipVertex& a = polygon.vertices[i];
      const ClipVertex& b = polygon.vertices[(i + 1) % polygon.count];
      const double da = volume.distance(a, static_cast<ClipPlane>(plane));
      const double db = volume.distance(b, static_cast<ClipPlane>(plane));
      if (da >= 0) kept.vertices[kept.count++] = a;
      if ((da >= 0) != (db >= 0)) {
        const double s = da / (da - db);
        kept.vertices[kept.count++] = {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), a.d + s * (b.d - a.d),
                                       a.w + s * (b.w - a.w)};
      }
    }
    polygon = kept;
  }
  return polygon;
}

}  // namespace hsr
