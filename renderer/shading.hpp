// The shading stage: colors each pixel from the visible id a surface algorithm left
// there (deferred shading: one shading invocation per covered pixel, whatever the
// overdraw). It runs only the work the scene's effects ask for: normals are built only
// for lambert, and stats count "shading invocations" so a test can check what ran.
#pragma once

#include "renderer/camera.hpp"
#include "renderer/frame.hpp"
#include "renderer/prepare.hpp"
#include "renderer/stats.hpp"

namespace hsr {

void shadeFrame(const PreparedScene& scene, const CameraTransform& camera, Frame& frame, int threads, Stats& stats);

// The color of one triangle at one pixel center, before quantizing, as shadeFrame
// computes it: for algorithms that need a surface's color at the moment they draw it
// (the painter's blending of transparent surfaces) rather than once per pixel at the end.
class PixelShader {
 public:
  // Builds the corner normals only when the scene's shading needs them.
  PixelShader(const PreparedScene& scene, const CameraTransform& camera, Stats& stats);
  dvec3 shade(std::uint32_t triangle, int x, int y) const;

 private:
  const PreparedScene& scene_;
  const CameraTransform& camera_;
  const std::vector<std::array<dvec3, 3>>* normals_;
};

// A color channel in [0, 1] as an 8-bit value (clamped, rounded to nearest).
std::uint8_t channelByte(double value);

// Barycentric coordinates (of the triangle's vertices 0, 1, 2) of the point where
// `ray` meets the triangle's plane. Intersecting the eye ray in 3D is exactly
// perspective-correct interpolation (attribute/w and 1/w linear in screen space).
dvec3 barycentricAlongRay(const PreparedScene& scene, std::uint32_t triangle, const Ray& ray);

}  // namespace hsr
