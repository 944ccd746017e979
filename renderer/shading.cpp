#include "renderer/shading.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/conventions.hpp"
#include "renderer/error.hpp"
#include "renderer/lines.hpp"
#include "renderer/parallel.hpp"
#include "renderer/raster.hpp"

namespace hsr {

dvec3 barycentricAlongRay(const PreparedScene& scene, std::uint32_t triangle, const Ray& ray) {
  const Triangle& t = scene.triangles()[triangle];
  const dvec3 a = scene.positions()[t[0]], b = scene.positions()[t[1]], c = scene.positions()[t[2]];
  // Möller–Trumbore without the inside test: the pixel center may sit a hair outside
  // the triangle (it was covered after snapping to 1/256 pixel), so clamp the result.
  const dvec3 e1 = b - a, e2 = c - a;
  const dvec3 p = glm::cross(ray.direction, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-300) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  const dvec3 s = ray.origin - a;
  const double u = glm::dot(s, p) / det;
  const double v = glm::dot(ray.direction, glm::cross(s, e1)) / det;
  dvec3 bary(1 - u - v, u, v);
  bary = glm::clamp(bary, 0.0, 1.0);
  return bary / (bary.x + bary.y + bary.z);
}

SurfacePoint surfacePoint(const PreparedScene& scene, const CameraTransform& camera, std::uint32_t triangle, int x, int y,
                          const std::vector<std::array<dvec3, 3>>* cornerNormals) {
  const Ray ray = camera.rayThroughPixel(x + 0.5, y + 0.5);
  const dvec3 bary = barycentricAlongRay(scene, triangle, ray);
  const Triangle& t = scene.triangles()[triangle];
  SurfacePoint point;
  point.position = bary.x * scene.positions()[t[0]] + bary.y * scene.positions()[t[1]] + bary.z * scene.positions()[t[2]];
  point.toViewer = -glm::normalize(ray.direction);
  const dvec3 face = scene.faceNormal(triangle);
  point.normal = face;
  if (cornerNormals) {
    const auto& corner = (*cornerNormals)[triangle];
    const dvec3 smooth = bary.x * corner[0] + bary.y * corner[1] + bary.z * corner[2];
    if (glm::length(smooth) > 0) point.normal = glm::normalize(smooth);
  }
  // Lit from both sides: a surface seen from behind shades as its front would.
  if (glm::dot(face, point.toViewer) < 0) point.normal = -point.normal;
  return point;
}

dvec3 towardLight(const Light& light, const dvec3& point) {
  return light.kind == Light::Kind::directional ? -light.direction : glm::normalize(light.position - point);
}

ShadingCounts& ShadingCounts::operator+=(const ShadingCounts& other) {
  invocations += other.invocations;
  specularTerms += other.specularTerms;
  shadowLookups += other.shadowLookups;
  shadowedLookups += other.shadowedLookups;
  return *this;
}

void ShadingCounts::addTo(Stats& stats) const {
  stats.add("shading invocations", invocations);
  if (specularTerms) stats.add("specular terms", specularTerms);
  if (shadowLookups) stats.add("shadow lookups", shadowLookups);
  if (shadowedLookups) stats.add("shadowed lookups", shadowedLookups);
}

PixelShader::PixelShader(const PreparedScene& scene, const CameraTransform& camera, Stats& stats, const ShadowTest* shadows)
    : scene_(scene), camera_(camera),
      normals_(scene.scene().effects.smoothNormals() ? &scene.cornerNormals(stats) : nullptr),
      shadows_(scene.scene().effects.shadows ? shadows : nullptr) {
  HSR_CHECK(!scene.scene().effects.shadows || shadows);
}

dvec3 PixelShader::shade(std::uint32_t triangle, int x, int y, ShadingCounts& counts) const {
  ++counts.invocations;
  const Scene& description = scene_.scene();
  const Instance& instance = scene_.instanceOf(triangle);
  const dvec3 base = dvec3(instance.color);
  if (!description.effects.lit()) return base;
  const SurfacePoint point = surfacePoint(scene_, camera_, triangle, x, y, normals_);
  const SceneObject& material = description.objects[instance.object];
  const bool specular = description.effects.shading == Shading::phong;
  // Phong's model (1975) with Blinn's half-vector (1977): ambient, plus per light that
  // reaches the point Lambert's cosine law and a white highlight.
  double diffuse = description.ambient, highlight = 0;
  for (std::size_t i = 0; i < description.lights.size(); ++i) {
    const Light& light = description.lights[i];
    const dvec3 toLight = towardLight(light, point.position);
    const double cosine = glm::dot(point.normal, toLight);
    if (cosine <= 0) continue;  // the light is behind the surface: no shadow test needed
    if (shadows_) {
      ++counts.shadowLookups;
      if (shadows_->shadowed(i, point.position, triangle)) {
        ++counts.shadowedLookups;
        continue;
      }
    }
    diffuse += light.intensity * cosine;
    if (specular) {
      ++counts.specularTerms;
      const dvec3 half = glm::normalize(toLight + point.toViewer);
      highlight += light.intensity * material.reflectivity * std::pow(std::max(0.0, glm::dot(point.normal, half)), material.shininess);
    }
  }
  return base * diffuse + dvec3(highlight);
}

std::uint8_t channelByte(double value) { return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255)); }

void shadeFrame(const PreparedScene& scene, Frame& frame, const PixelShader& shader,
                int threads, Stats& stats) {
  PhaseTimer timer(stats, "shading");
  const vec3 background = scene.scene().background;
  std::vector<ShadingCounts> counts(static_cast<std::size_t>(frame.height));
  parallelFor(static_cast<std::size_t>(frame.height), threads, [&](std::size_t row, int) {
    ShadingCounts rowCounts;
    for (int x = 0; x < frame.width; ++x) {
      const std::size_t pixel = row * std::size_t(frame.width) + std::size_t(x);
      std::uint8_t* rgba = &frame.color[4 * pixel];
      rgba[3] = 255;
      if (frame.ids[pixel] == conventions::kBackgroundId) {
        for (int c = 0; c < 3; ++c) rgba[c] = channelByte(background[c]);
        continue;
      }
      const dvec3 color = shader.shade(frame.ids[pixel] - 1, x, static_cast<int>(row), rowCounts);
      for (int c = 0; c < 3; ++c) rgba[c] = channelByte(color[c]);
    }
    counts[row] = rowCounts;
  });
  ShadingCounts total;
  for (const ShadingCounts& row : counts) total += row;
  total.addTo(stats);
}

double fogClearFraction(const FogSettings& fog, double distance) {
  if (fog.kind == FogSettings::Kind::exponential) return std::exp(-fog.density * distance);
  return std::clamp((fog.end - distance) / (fog.end - fog.start), 0.0, 1.0);
}

namespace {

// Depth cueing: a surface's color blended toward the fog color by its view distance,
// so that nearer things stand out. The background is already the far end.
void applyFog(const FogSettings& fog, Frame& frame, int threads, Stats& stats) {
  PhaseTimer timer(stats, "fog");
  std::vector<std::int64_t> blends(static_cast<std::size_t>(frame.height), 0);
  parallelFor(static_cast<std::size_t>(frame.height), threads, [&](std::size_t row, int) {
    for (int x = 0; x < frame.width; ++x) {
      const std::size_t pixel = row * std::size_t(frame.width) + std::size_t(x);
      if (frame.ids[pixel] == conventions::kBackgroundId) continue;
      const double clear = fogClearFraction(fog, frame.depth[pixel]);
      std::uint8_t* rgba = &frame.color[4 * pixel];
      for (int c = 0; c < 3; ++c) rgba[c] = channelByte(clear * rgba[c] / 255.0 + (1 - clear) * fog.color[c]);
      ++blends[row];
    }
  });
  std::int64_t total = 0;
  for (std::int64_t count : blends) total += count;
  stats.add("fog blends", total);
}

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

// Feature edges (renderer/lines: boundaries, silhouettes, creases) drawn over the image
// where the surface the frame shows does not hide them. A 1.5-pixel line covers pixels
// on both sides of its edge, and on a crease or a silhouette one side shows the face
// beyond it, so an edge point counts as seen when it is no farther than the farthest
// surface within one pixel: edges on visible faces are drawn whole, edges behind a face
// are not (up to one pixel from that face's own outline). Under fog, a line fades with
// the distance of its nearest edge point at the pixel, as the surfaces did.
void drawOutline(const PreparedScene& scene, const CameraTransform& camera, const OutlineSettings& outline, const FogSettings* fog,
                 Frame& frame, Stats& stats) {
  PhaseTimer timer(stats, "outline");
  const std::vector<std::int8_t> facing = viewFacing(scene, camera, stats);
  const std::vector<FeatureEdge> edges = featureEdges(scene, camera, facing, outline.creaseDegrees, stats);
  const auto farthestNearby = [&](int x, int y) {
    float farthest = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = std::clamp(x + dx, 0, frame.width - 1), ny = std::clamp(y + dy, 0, frame.height - 1);
        farthest = std::max(farthest, frame.depth[std::size_t(ny) * std::size_t(frame.width) + std::size_t(nx)]);
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
      const dvec2 center(x + 0.5, y + 0.5);
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

}  // namespace

void applyImageEffects(const PreparedScene& scene, const CameraTransform& camera, Frame& frame, int threads, Stats& stats) {
  const Effects& effects = scene.scene().effects;
  if (effects.fog) applyFog(effects.fogSettings, frame, threads, stats);
  if (effects.outline) drawOutline(scene, camera, effects.outlineSettings, effects.fog ? &effects.fogSettings : nullptr, frame, stats);
}

}  // namespace hsr
