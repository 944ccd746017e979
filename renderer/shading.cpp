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

void shadeFrame(const PreparedScene& scene, const CameraTransform& camera, Frame& frame, int threads, Stats& stats) {
  PhaseTimer timer(stats, "shading");
  const Scene& description = scene.scene();
  const Shading shading = description.shading;
  const auto* normals = shading == Shading::lambert ? &scene.cornerNormals(stats) : nullptr;

  const auto toByte = [](double value) { return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255)); };
  std::vector<std::int64_t> invocations(static_cast<std::size_t>(frame.height), 0);
  parallelFor(static_cast<std::size_t>(frame.height), threads, [&](std::size_t row, int) {
    for (int x = 0; x < frame.width; ++x) {
      const std::size_t pixel = row * std::size_t(frame.width) + std::size_t(x);
      std::uint8_t* rgba = &frame.color[4 * pixel];
      rgba[3] = 255;
      if (frame.ids[pixel] == conventions::kBackgroundId) {
        for (int c = 0; c < 3; ++c) rgba[c] = toByte(description.background[c]);
        continue;
      }
      ++invocations[row];
      const std::uint32_t triangle = frame.ids[pixel] - 1;
      const dvec3 base = dvec3(scene.instanceOf(triangle).color);
      if (shading == Shading::none) {
        for (int c = 0; c < 3; ++c) rgba[c] = toByte(base[c]);
        continue;
      }
      // Lambert's cosine law, lit from both sides: the normal is turned toward the eye.
      const Ray ray = camera.rayThroughPixel(x + 0.5, double(row) + 0.5);
      const dvec3 bary = barycentricAlongRay(scene, triangle, ray);
      const Triangle& t = scene.triangles()[triangle];
      const dvec3 point = bary.x * scene.positions()[t[0]] + bary.y * scene.positions()[t[1]] + bary.z * scene.positions()[t[2]];
      const dvec3 face = scene.faceNormal(triangle);
      dvec3 normal = face;
      if (normals) {
        const auto& corner = (*normals)[triangle];
        const dvec3 smooth = bary.x * corner[0] + bary.y * corner[1] + bary.z * corner[2];
        if (glm::length(smooth) > 0) normal = glm::normalize(smooth);
      }
      if (glm::dot(face, ray.direction) > 0) normal = -normal;
      double light = description.ambient;
      for (const Light& source : description.lights) {
        const dvec3 toLight =
            source.kind == Light::Kind::directional ? -source.direction : glm::normalize(source.position - point);
        light += source.intensity * std::max(0.0, glm::dot(normal, toLight));
      }
      for (int c = 0; c < 3; ++c) rgba[c] = toByte(base[c] * light);
    }
  });
  std::int64_t total = 0;
  for (std::int64_t count : invocations) total += count;
  stats.add("shading invocations", total);
}

}  // namespace hsr
