#include "renderer/shading.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/conventions.hpp"
#include "renderer/error.hpp"
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
  const Ray ray = camera.rayThroughPixel(conventions::pixelCenter(x), conventions::pixelCenter(y));
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

}  // namespace hsr
