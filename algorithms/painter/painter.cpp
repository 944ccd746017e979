// The painter's algorithm, top to bottom: screen geometry, an order, the painting.
#include "algorithms/painter/painter.hpp"

#include "algorithms/painter/bsp.hpp"
#include "algorithms/painter/paint.hpp"

namespace hsr::painter {

std::string refusal(const PreparedScene& scene, const Knobs& knobs) {
  if (knobs.variant != Variant::newell) return "";
  // Newell compares every pair whose depth ranges overlap: up to n(n - 1)/2 of them.
  const double n = static_cast<double>(scene.triangleCount());
  const double pairs = n * (n - 1) / 2;
  if (pairs <= knobs.budget) return "";
  char text[256];
  std::snprintf(text, sizeof text,
                "painter newell may test %.3g triangle pairs (%zu triangles), more than --knob budget=%.3g; "
                "raise the budget or use --variant bsp",
                pairs, scene.triangleCount(), knobs.budget);
  return text;
}

Frame run(const PreparedScene& scene, const Knobs& knobs, int threads, Stats& stats) {
  // Step 1: the screen triangles, clipped at the near and far planes as the reference
  // sees the scene. Sort and Newell order them by their corners.
  const bool needsCorners = knobs.variant != Variant::bsp;
  const ScreenGeometry geometry = buildScreenTriangles(scene, true, threads, stats, needsCorners);
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
