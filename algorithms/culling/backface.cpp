// Backface culling, one sign per triangle (backface.hpp has the three variants).
#include "algorithms/culling/backface.hpp"

#include <array>
#include <cmath>
#include <string>

#include "algorithms/culling/culling.hpp"
#include "renderer/geometry/clip.hpp"
#include "renderer/geometry/predicates.hpp"
#include "renderer/steps/why.hpp"

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

// hsr why: what the test found for one triangle, with the number its sign was read from
// (the exact predicates decide the sign; the number is computed again in floating point
// for reading). `twiceArea`: the screen variant's, or NaN when nothing projects.
std::string finding(Variant variant, const dvec3& a, const dvec3& b, const dvec3& c, const CameraTransform& camera, bool kept,
                    double twiceArea) {
  const dvec3 normal = glm::normalize(glm::cross(b - a, c - a));
  switch (variant) {
    case Variant::object:
      if (!camera.perspective()) break;
      return std::string(kept ? "the eye lies in front of its plane, " : "the eye lies behind its plane or in it, ") +
             whyNumber(std::abs(glm::dot(normal, camera.camera().eye - a))) + " from it";
    case Variant::screen:
      if (std::isnan(twiceArea)) return "no corner lies in front of the near plane: nothing projects, so it is left to the clipper";
      return "its projection, clipped at the near plane, runs " + std::string(kept ? "counter-clockwise on the screen (a front face)" : "clockwise on the screen or is flat (a back face)") +
             ", with an area of " + whyNumber(std::abs(twiceArea) / 2) + " square pixels";
    case Variant::viewDirection:
      break;
  }
  // Along the view axis only: what the viewDirection variant tests everywhere, and the
  // object variant under an orthographic view, where every sight line is the axis.
  const double cosine = glm::dot(normal, -camera.forward());
  std::string found = std::string(kept ? "its normal turns toward the eye along the view axis" : "its normal turns away from the eye along the view axis") +
                      " (cosine " + whyNumber(cosine) + ")";
  // Under perspective the sight line to the triangle is not the axis: where the eye
  // itself lies says whether the shortcut was right.
  if (camera.perspective()) {
    const double eyeDistance = glm::dot(normal, camera.camera().eye - a);
    found += std::string("; the eye itself lies ") + (eyeDistance > 0 ? "in front of" : "behind") + " its plane, " + whyNumber(std::abs(eyeDistance)) +
             " from it";
  }
  return found;
}

}  // namespace

VisibleSet cull(const PreparedScene& scene, const CameraTransform& camera, Variant variant, const VisibleSet& in,
                int threads, Stats& stats, StageWitness* why) {
  PhaseTimer timer(stats, "culling: backface");
  const std::vector<dvec3>& positions = scene.positions();
  const std::vector<Triangle>& triangles = scene.triangles();
  const dvec3 eye = camera.camera().eye, towardsEye = -camera.forward();
  const ClipVolume volume(camera, false);

  VisibleSet out = keepTriangles(in, threads, [&] {
    return [&, predicates = ExactPredicates()](std::uint32_t index) mutable {
      const Triangle& t = triangles[index];
      const dvec3 &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
      bool kept = true;
      double twiceArea = NAN;
      switch (variant) {
        case Variant::object:
          // The eye on the front side of the triangle's plane; under orthographic
          // projection every sight line runs along the view axis, so the eye is at
          // infinity behind it and only the direction counts.
          kept = camera.perspective() ? predicates.orient3d(a, b, c, eye) > 0 : predicates.facing(a, b, c, towardsEye) > 0;
          break;
        case Variant::screen: {
          const std::array<ClipVertex, 3> corners = {camera.clipFromWorld(a), camera.clipFromWorld(b), camera.clipFromWorld(c)};
          const std::uint32_t behind[3] = {volume.outside(corners[0]) & kNearPlane, volume.outside(corners[1]) & kNearPlane,
                                           volume.outside(corners[2]) & kNearPlane};
          if (behind[0] & behind[1] & behind[2]) break;  // nothing projects: leave it to the clipper
          twiceArea = pixelArea(clipTriangle(corners, volume, behind[0] | behind[1] | behind[2]), camera);
          kept = twiceArea < 0;
          break;
        }
        case Variant::viewDirection:
          // The textbook shortcut: n . forward < 0, as if every sight line were parallel to
          // the view axis. Under perspective they are not.
          kept = predicates.facing(a, b, c, towardsEye) > 0;
          break;
      }
      if (std::string* found = why ? why->aboutTriangle(index) : nullptr) [[unlikely]]
        *found = finding(variant, a, b, c, camera, kept, twiceArea);
      return kept;
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
    return cull(input.scene, input.camera, knobs.as<Knobs>().variant, input.in, input.threads, input.stats, input.why);
  };
  return entry;
}

}  // namespace hsr::culling::backface
