#include "renderer/shading.hpp"

#include <algorithm>
#include <cmath>

#include "renderer/conventions.hpp"
#include "renderer/parallel.hpp"

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

PixelShader::PixelShader(const PreparedScene& scene, const CameraTransform& camera, Stats& stats)
    : scene_(scene), camera_(camera),
      normals_(scene.scene().shading == Shading::lambert ? &scene.cornerNormals(stats) : nullptr) {}

dvec3 PixelShader::shade(std::uint32_t triangle, int x, int y) const {
  const Scene& description = scene_.scene();
  const dvec3 base = dvec3(scene_.instanceOf(triangle).color);
  if (description.shading == Shading::none) return base;
  // Lambert's cosine law, lit from both sides: the normal is turned toward the eye.
  const Ray ray = camera_.rayThroughPixel(x + 0.5, y + 0.5);
  const dvec3 bary = barycentricAlongRay(scene_, triangle, ray);
  const Triangle& t = scene_.triangles()[triangle];
  const dvec3 point = bary.x * scene_.positions()[t[0]] + bary.y * scene_.positions()[t[1]] + bary.z * scene_.positions()[t[2]];
  const dvec3 face = scene_.faceNormal(triangle);
  dvec3 normal = face;
  if (normals_) {
    const auto& corner = (*normals_)[triangle];
    const dvec3 smooth = bary.x * corner[0] + bary.y * corner[1] + bary.z * corner[2];
    if (glm::length(smooth) > 0) normal = glm::normalize(smooth);
  }
  if (glm::dot(face, ray.direction) > 0) normal = -normal;
  double light = description.ambient;
  for (const Light& source : description.lights) {
    const dvec3 toLight = source.kind == Light::Kind::directional ? -source.direction : glm::normalize(source.position - point);
    light += source.intensity * std::max(0.0, glm::dot(normal, toLight));
  }
  return base * light;
}

std::uint8_t channelByte(double value) { return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255)); }

void shadeFrame(const PreparedScene& scene, const CameraTransform& camera, Frame& frame, int threads, Stats& stats) {
  PhaseTimer timer(stats, "shading");
  const PixelShader shader(scene, camera, stats);
  const vec3 background = scene.scene().background;
  std::vector<std::int64_t> invocations(static_cast<std::size_t>(frame.height), 0);
  parallelFor(static_cast<std::size_t>(frame.height), threads, [&](std::size_t row, int) {
    for (int x = 0; x < frame.width; ++x) {
      const std::size_t pixel = row * std::size_t(frame.width) + std::size_t(x);
      std::uint8_t* rgba = &frame.color[4 * pixel];
      rgba[3] = 255;
      if (frame.ids[pixel] == conventions::kBackgroundId) {
        for (int c = 0; c < 3; ++c) rgba[c] = channelByte(background[c]);
        continue;
      }
      ++invocations[row];
      const dvec3 color = shader.shade(frame.ids[pixel] - 1, x, static_cast<int>(row));
      for (int c = 0; c < 3; ++c) rgba[c] = channelByte(color[c]);
    }
  });
  std::int64_t total = 0;
  for (std::int64_t count : invocations) total += count;
  stats.add("shading invocations", total);
}

}  // namespace hsr
