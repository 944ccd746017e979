#include "renderer/geometry/clip.hpp"

#include "renderer/util/conventions.hpp"

namespace hsr {

ClipVolume::ClipVolume(const CameraTransform& camera, bool clipFarPlane)
    : near(camera.camera().near),
      far(camera.camera().far),
      clipFar(clipFarPlane),
      guardX(conventions::kGuardBandPixels / (0.5 * camera.width())),
      guardY(conventions::kGuardBandPixels / (0.5 * camera.height())) {}

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
