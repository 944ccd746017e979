// What the painter's tests share: a scene loaded at a test size, and the classification
// of the pixels where a painter's image differs from the exact reference.
#pragma once

#include <cmath>
#include <cstdio>

#include "renderer/metrics.hpp"
#include "renderer/reference.hpp"
#include "test_support.hpp"

namespace hsr::test {

// A scene file loaded and prepared, optionally at another width (same aspect ratio).

// The painter's order is exact, so a non-ambiguous pixel may differ from the reference
// for one of two documented reasons (algorithms/painter/README.md):
//   snapping: the center lies within 1/256 pixel of either triangle's projected boundary;
//   coplanarity: the two triangles meet the pixel's ray within the coplanar tolerance
//     (1e-10 of the depth; 1e-9 here, for the rounding of this check itself), where the
//     painter takes them as one plane and either order.
struct WrongPixels {
  long snapping = 0, coplanar = 0, unexplained = 0;
  long total() const { return snapping + coplanar + unexplained; }
};

inline WrongPixels classifyWrongPixels(const PreparedScene& scene, const Frame& frame, const ReferenceImage& truth) {
  const CameraTransform camera(scene.scene().camera, scene.width(), scene.height());
  WrongPixels result;
  for (std::size_t p = 0; p < frame.pixelCount(); ++p) {
    if (truth.ambiguous[p] || frame.ids[p] == truth.frame.ids[p]) continue;
    const dvec2 center(double(p % std::size_t(frame.width)) + 0.5, double(p / std::size_t(frame.width)) + 0.5);
    if (nearestProjectedEdge(scene, camera, {frame.ids[p], truth.frame.ids[p]}, center) < kSnapDistance) {
      ++result.snapping;
      continue;
    }
    if (frame.ids[p] != 0 && truth.frame.ids[p] != 0) {
      const Ray ray = camera.rayThroughPixel(center.x, center.y);
      const double shown = hitDistance(scene, camera, frame.ids[p] - 1, ray);
      const double exact = hitDistance(scene, camera, truth.frame.ids[p] - 1, ray);
      if (std::abs(shown - exact) <= 1e-9 * std::abs(exact)) {
        ++result.coplanar;
        continue;
      }
    }
    ++result.unexplained;
  }
  return result;
}

}  // namespace hsr::test
