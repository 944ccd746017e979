// Appel's quantitative invisibility, checked against its definition (lines_test and the
// random-scene property tests share it).
#pragma once

#include <algorithm>
#include <cstdlib>
#include <string>

#include "renderer/geometry/camera.hpp"
#include "renderer/lines/feature_edges.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::test {

// An independent count of the front faces in front of a point: every front-facing
// triangle the sight line crosses before the point, in plain double precision (callers
// test points away from every projected edge).
inline int frontFacesInFront(const PreparedScene& scene, const CameraTransform& camera, const dvec3& x) {
  const dvec3 origin = camera.perspective() ? camera.camera().eye : x - camera.forward() * 1e6;
  const dvec3 direction = x - origin;
  int count = 0;
  for (std::size_t t = 0; t < scene.triangleCount(); ++t) {
    const Triangle& tri = scene.triangles()[t];
    const dvec3 &a = scene.positions()[tri[0]], &b = scene.positions()[tri[1]], &c = scene.positions()[tri[2]];
    const dvec3 normal = glm::cross(b - a, c - a);
    if (glm::dot(normal, origin - a) <= 0) continue;  // not facing the viewer
    const double along = glm::dot(normal, direction);
    if (along == 0) continue;
    const double hit = glm::dot(normal, a - origin) / along;
    if (hit <= 0 || hit >= 1 - 1e-9) continue;
    const dvec3 p = origin + hit * direction;
    if (glm::dot(glm::cross(b - a, p - a), normal) >= 0 && glm::dot(glm::cross(c - b, p - b), normal) >= 0 &&
        glm::dot(glm::cross(a - c, p - c), normal) >= 0)
      ++count;
  }
  return count;
}

struct QiCheck {
  long counted = 0;     // pieces whose QI was recounted independently
  long violations = 0;  // invariants broken (below)
  int maximum = 0;      // the largest QI drawn
  std::string firstViolation;
};

// The invariants of a drawing by Appel's method (`stats`: that drawing's counters):
//   - every edge's QI at its start agrees with its vertex's (the "QI mismatches" counter)
//     and no QI goes negative (the "negative QI" counter, and every piece's own QI);
//   - along an edge, the QI changes only at a crossing, and by exactly one;
//   - inside a piece at least two pixels long, the QI is the count of front faces in
//     front of its middle (frontFacesInFront).
inline QiCheck checkQiInvariants(const PreparedScene& scene, const LineSet& lines, const Stats& stats) {
  const CameraTransform& camera = scene.camera();
  QiCheck check;
  const auto violated = [&](const std::string& what) {
    if (check.violations++ == 0) check.firstViolation = what;
  };
  if (stats.counter("QI mismatches") != 0) violated(std::to_string(stats.counter("QI mismatches")) + " QI mismatches");
  if (stats.counter("negative QI") != 0) violated(std::to_string(stats.counter("negative QI")) + " negative QI");
  for (std::size_t i = 0; i < lines.segments.size(); ++i) {
    const LineSegment& piece = lines.segments[i];
    const std::string where = "edge " + std::to_string(piece.edge) + " piece " + std::to_string(i);
    if (piece.qi < 0) violated(where + ": QI " + std::to_string(piece.qi));
    check.maximum = std::max(check.maximum, piece.qi);
    if (i + 1 < lines.segments.size() && lines.segments[i + 1].edge == piece.edge &&
        std::abs(lines.segments[i + 1].qi - piece.qi) != 1)
      violated(where + ": QI steps from " + std::to_string(piece.qi) + " to " + std::to_string(lines.segments[i + 1].qi));
    const FeatureEdge& edge = lines.edges[piece.edge];
    if ((piece.end - piece.begin) * edge.lengthPixels() < 2) continue;
    const double s = edge.edgeParameter((piece.begin + piece.end) / 2);
    const int counted = frontFacesInFront(scene, camera, edge.from + s * (edge.to - edge.from));
    if (piece.qi != counted) violated(where + ": QI " + std::to_string(piece.qi) + ", front faces in front " + std::to_string(counted));
    ++check.counted;
  }
  return check;
}

}  // namespace hsr::test
