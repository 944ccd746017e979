// The painter's algorithm, top to bottom: screen geometry, an order, the painting.
#include "algorithms/painter/painter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "algorithms/painter/bsp.hpp"
#include "algorithms/painter/paint.hpp"

namespace hsr::painter {

std::string refusal(const PreparedScene& scene, const Knobs& knobs) {
  const double n = static_cast<double>(scene.triangleCount());
  char text[256];
  if (knobs.variant == Variant::newell) {
    // Newell compares every pair whose depth ranges overlap: up to n(n - 1)/2 of them.
    const double pairs = n * (n - 1) / 2;
    if (pairs <= knobs.budget) return "";
    std::snprintf(text, sizeof text,
                  "newell may test %.3g triangle pairs (%zu triangles), more than --knob budget=%.3g; raise it, or use "
                  "--variant bsp",
                  pairs, scene.triangleCount(), knobs.budget);
    return text;
  }
  if (knobs.variant == Variant::bsp) {
    // Each polygon is classified once per level of a tree about log2(n) deep, and
    // splitting multiplies the polygons by about log2(n) more on curved meshes: the
    // estimate n log2(n)^2 is within a factor of 4 of the counted classifications on the
    // shipped scenes (algorithms/painter/README.md).
    const double levels = std::log2(std::max(2.0, n));
    const double work = n * levels * levels;
    if (work <= knobs.buildBudget) return "";
    std::snprintf(text, sizeof text,
                  "building the bsp tree of %zu triangles takes about %.3g plane-side tests, more than --knob "
                  "build-budget=%.3g; raise it (about 10 s per 1e8 on one core)",
                  scene.triangleCount(), work, knobs.buildBudget);
    return text;
  }
  return "";
}

Frame run(const PreparedScene& scene, const Knobs& knobs, int threads, Stats& stats, const VisibleSet* visible) {
  // Step 1: the screen triangles, clipped at the near and far planes as the reference
  // sees the scene. Sort and Newell order them by their corners.
  const bool needsCorners = knobs.variant != Variant::bsp;
  const ScreenGeometry geometry = buildScreenTriangles(scene, {.keepCorners = needsCorners, .submitted = visible}, threads, stats);
  // Step 2: back to front.
  PaintOrder order;
  switch (knobs.variant) {
    case Variant::sort: order = sortOrder(geometry, knobs.key, stats); break;
    case Variant::newell: order = newellOrder(scene, geometry, knobs, stats); break;
    case Variant::bsp: order = BspTree(scene, knobs, stats).backToFront(scene, geometry, stats); break;
  }
  // Step 3: paint.
  Frame frame = paint(scene, geometry, order, threads, stats);
  frame.partial = order.partial;
  return frame;
}

}  // namespace hsr::painter
