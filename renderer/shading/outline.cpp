#include "renderer/shading/outline.hpp"
#include "renderer/util/conventions.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include "renderer/lines/feature_edges.hpp"
#include "renderer/lines/line_drawing.hpp"
#include "renderer/raster/raster.hpp"
#include "renderer/shading/fog.hpp"
#include "renderer/shading/shading.hpp"

namespace hsr {
namespace {

// The part of a world-space segment beyond the near plane (false when none is).
bool clipToNearPlane(const CameraTransform& camera, dvec3& from, dvec3& to) {
  const double near = camera.camera().near * (1 + 1e-9);
  const double dFrom = glm::dot(from - camera.camera().eye, camera.forward());
  const double dTo = glm::dot(to - camera.camera().eye, camera.forward());
  if (dFrom < near && dTo < near) return false;
  if (dFrom < near) from += (near - dFrom) / (dTo - dFrom) * (to - from);
  if (dTo < near) to += (near - dTo) / (dFrom - dTo) * (from - to);
  return true;
}

}  // namespace

void drawOutline(const PreparedScene& scene, const CameraTransform& camera, const OutlineSettings& outline, const FogSettings* fog,
                 Frame& frame, Stats& stats) {
  PhaseTimer timer(stats, "outline");
  const std::vector<std::int8_t> facing = viewFacing(scene, camera, stats);
  const std::vector<FeatureEdge> edges = featureEdges(scene, camera, facing, outline.creaseDegrees, stats);
  const PixelBuffer<float>& viewDistance = frame.distances(&stats);
  const auto farthestNearby = [&](int x, int y) {
    float farthest = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = std::clamp(x + dx, 0, frame.width - 1), ny = std::clamp(y + dy, 0, frame.height - 1);
        farthest = std::max(farthest, viewDistance[std::size_t(ny) * std::size_t(frame.width) + std::size_t(nx)]);
      }
    return farthest;
  };
  constexpr float kNotDrawn = std::numeric_limits<float>::infinity();
  std::vector<float> lineDistance(frame.pixelCount(), kNotDrawn);
  std::int64_t tested = 0;
  for (const FeatureEdge& mesh : edges) {
    dvec3 from = mesh.from, to = mesh.to;
    if (!clipToNearPlane(camera, from, to)) continue;
    ++tested;
    const FeatureEdge edge = projectEdge(camera, from, to, mesh.kind);
    const dvec2 span = edge.pixelTo - edge.pixelFrom;
    const double lengthSquared = glm::dot(span, span);
    rasterizeLine(edge.pixelFrom, edge.pixelTo, kLineWidthPixels, frame.width, frame.height, [&](int x, int y) {
      const dvec2 center(conventions::pixelCenter(x), conventions::pixelCenter(y));
      const double u = lengthSquared > 0 ? std::clamp(glm::dot(center - edge.pixelFrom, span) / lengthSquared, 0.0, 1.0) : 0.0;
      const dvec3 point = glm::mix(from, to, edge.edgeParameter(u));
      const double distance = glm::dot(point - camera.camera().eye, camera.forward());
      if (distance > farthestNearby(x, y) * (1 + 1e-4)) return;
      float& nearest = lineDistance[std::size_t(y) * std::size_t(frame.width) + std::size_t(x)];
      nearest = std::min(nearest, static_cast<float>(distance));
    });
  }
  std::int64_t pixels = 0;
  for (std::size_t pixel = 0; pixel < lineDistance.size(); ++pixel) {
    if (lineDistance[pixel] == kNotDrawn) continue;
    ++pixels;
    const double clear = fog ? fogClearFraction(*fog, lineDistance[pixel]) : 1.0;
    for (int c = 0; c < 3; ++c)
      frame.color[4 * pixel + std::size_t(c)] = channelByte(clear * outline.color[c] + (1 - clear) * (fog ? fog->color[c] : 0.0f));
  }
  stats.add("outline edges", tested);
  stats.add("outline pixels", pixels);
}

}  // namespace hsr
