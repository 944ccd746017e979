#include "pipeline/shadow_maps.hpp"

#include <cmath>

#include "algorithms/zbuffer/zbuffer.hpp"

namespace hsr::pipeline {
namespace {

// Any unit vector not parallel to `forward`, for a view's up.
dvec3 upFor(const dvec3& forward) {
  const dvec3 size = glm::abs(forward);
  return size.y < 0.9 * glm::length(forward) ? dvec3(0, 1, 0) : dvec3(1, 0, 0);
}

// The views a light's shadow map is rendered from, holding the sphere (center, radius)
// that bounds the scene.
std::vector<CameraTransform> lightViews(const Light& light, const dvec3& center, double radius, int resolution) {
  std::vector<CameraTransform> views;
  Camera camera;
  if (light.kind == Light::Kind::directional) {
    // From outside the sphere, looking down the light's direction: every caster and
    // receiver lies between the near and far planes.
    camera.projection = Projection::orthographic;
    camera.orthoHeight = 2 * radius;
    camera.eye = center - 2 * radius * light.direction;
    camera.target = center;
    camera.up = upFor(light.direction);
    camera.near = 0.5 * radius;
    camera.far = 3.5 * radius;
    views.emplace_back(camera, resolution, resolution);
    return views;
  }
  // A point light: the six faces of a cube around it, 90 degrees each, reaching the far
  // side of the scene's sphere.
  const double reach = glm::length(light.position - center) + radius;
  camera.fovYDegrees = 90;
  camera.eye = light.position;
  camera.near = 1e-4 * reach;
  camera.far = 1.01 * reach;
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {1.0, -1.0}) {
      dvec3 forward(0);
      forward[axis] = sign;
      camera.target = camera.eye + forward;
      camera.up = upFor(forward);
      views.emplace_back(camera, resolution, resolution);
    }
  return views;
}

}  // namespace

ShadowMaps::ShadowMaps(const PreparedScene& scene, const ShadowSettings& settings, int threads, Stats& stats)
    : scene_(scene), biasTexels_(settings.biasTexels) {
  PhaseTimer timer(stats, "shadow maps");
  const Aabb bounds = scene.bounds();
  const dvec3 center = bounds.empty() ? dvec3(0) : bounds.center();
  const double radius = bounds.empty() ? 1.0 : std::max(0.5 * glm::length(bounds.hi - bounds.lo), 1e-9);
  // Only opaque surfaces cast shadows: a transparent one lets the light through (and
  // tints nothing: there are no colored shadows).
  const VisibleSet casters = trianglesByOpacity(scene, nullptr, true);
  const zbuffer::Knobs float32{.depthFormat = DepthFormat::float32};
  for (const Light& light : scene.scene().lights) {
    std::vector<View>& lightViewsDrawn = views_.emplace_back();
    for (const CameraTransform& view : lightViews(light, center, radius, settings.resolution)) {
      // The visibility pass of the z-buffer, seen from the light; its own counters stay
      // apart so that the camera's pass reads the same with and without shadows.
      Stats mapStats;
      Visibility map{Frame(settings.resolution, settings.resolution), std::nullopt};
      zbuffer::visibility({scene, view, &casters, threads, mapStats}, float32, map);
      stats.add("shadow maps rendered");
      stats.add("shadow map texels", static_cast<std::int64_t>(map.frame.pixelCount()));
      stats.add("shadow map fragments written", mapStats.counter("fragments written"));
      const double texelsPerUnit = view.perspective() ? settings.resolution / 2.0 : settings.resolution / view.camera().orthoHeight;
      map.frame.distances();  // the shadow test compares distances
      lightViewsDrawn.push_back({view, std::move(map.frame.depth), texelsPerUnit});
    }
  }
}

bool ShadowMaps::shadowed(std::size_t light, const dvec3& point, std::uint32_t triangle) const {
  // Across one texel a receiver tilted by theta from the light drifts tan(theta) texels
  // in depth: the bias grows with the slope, up to 10 (87 degrees).
  const double cosine = std::abs(glm::dot(scene_.faceNormal(triangle), towardLight(scene_.scene().lights[light], point)));
  const double slope = std::min(10.0, std::max(1.0, std::sqrt(std::max(0.0, 1 - cosine * cosine)) / std::max(cosine, 0.1)));
  for (const View& view : views_[light]) {
    const ClipVertex clip = view.camera.clipFromWorld(point);
    if (clip.w <= 0) continue;
    const dvec2 pixel = view.camera.pixelFromClip(clip);
    const int size = view.camera.width();
    if (!(pixel.x >= 0 && pixel.x < size && pixel.y >= 0 && pixel.y < size)) continue;  // not in this view (NaN too)
    const float stored = view.depth[std::size_t(pixel.y) * std::size_t(size) + std::size_t(pixel.x)];
    // One texel's width at the point's distance, in world units.
    const double texel = (view.camera.perspective() ? clip.d : 1.0) / view.texelsPerUnit;
    return clip.d > double(stored) + biasTexels_ * slope * texel;
  }
  return false;  // outside every view: nothing was drawn between it and the light
}

}  // namespace hsr::pipeline
