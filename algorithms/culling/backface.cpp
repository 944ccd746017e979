// Backface culling, one sign per triangle (backface.hpp has the three variants).
#include "algorithms/culling/backface.hpp"

#include <array>

#include "algorithms/culling/culling.hpp"
#include "renderer/geometry/clip.hpp"
#include "renderer/geometry/predicates.hpp"

namespace hsr::culling::backface {
namespace {

// Twice the signed area of a polygon in pixel coordinates (the shoelace formula). Rows
// grow downwards, so a polygon that runs counter-clockwise seen from the eye (a front
// face) has a negative area here.
double pixelArea(const ClipPolygon& polygon, const CameraTransform& camera) {
  if (polygon.count < 3) return 0;
  double twiceArea = 0;
  dvec2 previous = camera.pixelFromClip(polygon.vertices[std::size_t(polygon.count - 1)]);
  for (int i = 0; i < polygon.count; ++i) {
    const dvec2 current = camera.pixelFromClip(polygon.vertices[std::size_t(i)]);
    twiceArea += previous.x * current.y - current.x * previous.y;
    previous = current;
  }
  return twiceArea;
}

}  // namespace

VisibleSet cull(const PreparedScene& scene, const CameraTransform& camera, Variant variant, const VisibleSet& in,
                int threads, Stats& stats) {
  PhaseTimer timer(stats, "culling: backface");
  const std::vector<dvec3>& positions = scene.positions();
  const std::vector<Triangle>& triangles = scene.triangles();
  const dvec3 eye = camera.camera().eye, towardsEye = -camera.forward();
  const ClipVolume volume(camera, false);

  VisibleSet out = keepTriangles(in, threads, [&] {
    return [&, predicates = ExactPredicates()](std::uint32_t index) mutable {
      const Triangle& t = triangles[index];
      const dvec3 &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
      switch (variant) {
        case Variant::object:
          // The eye on the front side of the triangle's plane; under orthographic
          // projection every sight line runs along the view axis, so the eye is at
          // infinity behind it and only the direction counts.
          return camera.perspective() ? predicates.orient3d(a, b, c, eye) > 0 : predicates.facing(a, b, c, towardsEye) > 0;
        case Variant::screen: {
          const std::array<ClipVertex, 3> corners = {camera.clipFromWorld(a), camera.clipFromWorld(b), camera.clipFromWorld(c)};
          const std::uint32_t behind[3] = {volume.outside(corners[0]) & kNearPlane, volume.outside(corners[1]) & kNearPlane,
                                           volume.outside(corners[2]) & kNearPlane};
          if (behind[0] & behind[1] & behind[2]) return true;  // nothing projects: leave it to the clipper
          return pixelArea(clipTriangle(corners, volume, behind[0] | behind[1] | behind[2]), camera) < 0;
        }
        case Variant::viewDirection:
          // The textbook shortcut: n . forward < 0, as if every sight line were parallel to
          // the view axis. Under perspective they are not.
          return predicates.facing(a, b, c, towardsEye) > 0;
      }
      return true;
    };
  });
  stats.add("backface: triangles tested", static_cast<std::int64_t>(in.triangles.size()));
  stats.add("backface: triangles culled", static_cast<std::int64_t>(in.triangles.size() - out.triangles.size()));
  return out;
}

StageEntry stage() {
  StageEntry entry = stageEntry("backface", "drop triangles facing away from the eye (right for closed surfaces only)", knobTable());
  entry.mayDropVisible = [](const KnobValues& knobs) { return knobs.as<Knobs>().variant == Variant::viewDirection; };
  entry.run = [](const KnobValues& knobs, const StageInput& input) {
    return cull(input.scene, input.camera, knobs.as<Knobs>().variant, input.in, input.threads, input.stats);
  };
  return entry;
}

}  // namespace hsr::culling::backface
