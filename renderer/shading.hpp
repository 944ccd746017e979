// Shading: each pixel colored from the visible id a surface algorithm left there
// (deferred shading: one shading invocation per covered pixel, whatever the overdraw),
// with the lighting the scene's effects ask for (renderer/fog and renderer/outline are
// the image passes after it). Each piece of work runs only when the effects ask for it,
// and is counted, so a test can check that a scene without an effect spends nothing on it:
//   "shading invocations"  one per shaded pixel (or per blended write, when transparency blends)
//   "normals computed"     corner normals, only for lambert and phong (renderer/prepare)
//   "specular terms"       Blinn-Phong highlights evaluated (phong only)
//   "shadow lookups"       shadow tests (only with shadows), "shadowed lookups" those in shadow
#pragma once

#include "renderer/camera.hpp"
#include "renderer/frame.hpp"
#include "renderer/prepare.hpp"
#include "renderer/stats.hpp"

namespace hsr {

// How shading learns whether a lit point is in shadow: a shadow map
// (algorithms/effects) or exact shadow rays (renderer/reference). Called from many
// threads at once.
class ShadowTest {
 public:
  virtual ~ShadowTest() = default;
  // Is `point`, on triangle `triangle` (global index) and facing the light, hidden from
  // scene light `light` by some other surface?
  virtual bool shadowed(std::size_t light, const dvec3& point, std::uint32_t triangle) const = 0;
};

// What one shading call did, summed per row and added to Stats once.
struct ShadingCounts {
  std::int64_t invocations = 0, specularTerms = 0, shadowLookups = 0, shadowedLookups = 0;
  ShadingCounts& operator+=(const ShadingCounts& other);
  void addTo(Stats& stats) const;
};

// The color of one triangle at one pixel center, before quantizing.
class PixelShader {
 public:
  // Builds the corner normals only when the shading interpolates them. `shadows` is
  // consulted only when the scene declares shadows (it must then be given).
  PixelShader(const PreparedScene& scene, const CameraTransform& camera, Stats& stats, const ShadowTest* shadows = nullptr);
  dvec3 shade(std::uint32_t triangle, int x, int y, ShadingCounts& counts) const;

 private:
  const PreparedScene& scene_;
  const CameraTransform& camera_;
  const std::vector<std::array<dvec3, 3>>* normals_;
  const ShadowTest* shadows_;
};

// The surface point a pixel center shows on a triangle, and the triangle's normal there
// (interpolated when `cornerNormals` is given), turned toward the viewer: what both
// shading and the shadow error measure at.
struct SurfacePoint {
  dvec3 position, normal, toViewer;  // toViewer: unit
};
SurfacePoint surfacePoint(const PreparedScene& scene, const CameraTransform& camera, std::uint32_t triangle, int x, int y,
                          const std::vector<std::array<dvec3, 3>>* cornerNormals);
// The unit direction from a point toward a light.
dvec3 towardLight(const Light& light, const dvec3& point);

// Phase "shading": every covered pixel of frame.ids shaded, the background filled.
void shadeFrame(const PreparedScene& scene, Frame& frame, const PixelShader& shader,
                int threads, Stats& stats);

// A color channel in [0, 1] as an 8-bit value (clamped, rounded to nearest).
std::uint8_t channelByte(double value);

// Barycentric coordinates (of the triangle's vertices 0, 1, 2) of the point where
// `ray` meets the triangle's plane. Intersecting the eye ray in 3D is exactly
// perspective-correct interpolation (attribute/w and 1/w linear in screen space).
dvec3 barycentricAlongRay(const PreparedScene& scene, std::uint32_t triangle, const Ray& ray);

}  // namespace hsr
