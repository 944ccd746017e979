// Shading: each pixel colored from the visible id a surface algorithm left there
// (deferred shading: one shading invocation per covered pixel, whatever the overdraw),
// with the lighting the scene's effects ask for (renderer/shading/fog and renderer/shading/outline are
// the image passes after it). Each piece of work runs only when the effects ask for it,
// and is counted, so a test can check that a scene without an effect spends nothing on it:
//   "shading invocations"  one per shaded pixel (or per blended write, when transparency blends)
//   "shading set-ups"      triangles set up for shading: each triangle shaded, once
//   "normals computed"     corner normals of the triangles set up, only for lambert and
//                          phong ("normals from the mesh" where the OBJ gave them)
//   "specular terms"       Blinn-Phong highlights evaluated (phong only)
//   "shadow lookups"       shadow tests (only with shadows), "shadowed lookups" those in shadow
//
// How a pixel is shaded, as a hardware rasterizer does it: once per triangle, a set-up
// (the planes of its barycentric weights over the screen, its corner normals turned
// toward the viewer, its material); then per pixel three plane evaluations, one
// division, and the lighting. The set-up is exact in double; the per-pixel work runs in
// the precision Real: float for every rasterizing algorithm (PixelShader<float>), double
// for the exact reference (PixelShader<double>). README "Speed" gives the cost of each
// and tests/renderer/shading/shading_test.cpp bounds the float shader's error against the double
// one.
#pragma once

#include <algorithm>
#include <span>

#include "renderer/geometry/camera.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/stats.hpp"

namespace hsr {

// How shading learns whether a lit point is in shadow: a shadow map
// (pipeline/shadow_maps) or exact shadow rays (renderer/reference/reference). Called from many
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

// The surface point a pixel center shows on a triangle (world space), the normal shading
// uses there (interpolated under lambert and phong), turned toward the viewer, and the
// unit direction toward the viewer: what both shading and the shadow error measure at.
struct SurfacePoint {
  dvec3 position, normal, toViewer;
};

// The unit direction from a world point toward a light.
dvec3 towardLight(const Light& light, const dvec3& point);

template <class Real>
class PixelShader {
 public:
  using Color = glm::vec<3, Real>;
  // `shadows` is consulted only when the scene declares shadows (it must then be given).
  PixelShader(const PreparedScene& scene, const CameraTransform& camera, const ShadowTest* shadows = nullptr);

  // Sets up these triangles (repeats and triangles already set up are skipped), in
  // parallel: shade() may then be called for them.
  void setUp(std::span<const std::uint32_t> triangles, int threads, Stats& stats);
  // Sets up every triangle the frame shows.
  void setUpShownIn(const Frame& frame, int threads, Stats& stats);

  struct TriangleSetUp {
    // The barycentric weights of the corners, before dividing by their sum, are linear in
    // the pixel coordinates (each is the eye ray's triple product with the far edge):
    // weights(px, py) = weightsAt0 + px weightsPerX + py weightsPerY. Dividing by the sum
    // gives exactly perspective-correct interpolation.
    dvec3 weightsAt0, weightsPerX, weightsPerY;
    glm::vec<3, Real> corner[3];  // relative to the eye: precise however far the scene lies from the origin
    glm::vec<3, Real> normal[3];  // per corner (lambert and phong only)
    glm::vec<3, Real> face;       // the unit face normal
    // Which side of the triangle a pixel's eye ray sees: the sign of
    // facingAt0 + px facingPerX + py facingPerY (positive: the front).
    Real facingAt0, facingPerX, facingPerY;
    glm::vec<3, Real> color;
    Real reflectivity, shininess;
    std::uint32_t triangle;
  };
  const TriangleSetUp& setUpOf(std::uint32_t triangle) const { return setUps_[slotOf_[triangle] - 1]; }

  // The colors, before quantizing, of `count` (at most kRun) pixels of row y from firstX
  // on, all showing one set-up triangle. A run at a time, so that each step is one loop
  // over the run's pixels that the compiler turns into vector instructions.
  static constexpr int kRun = 64;
  struct RunColors {  // one array per channel, so that the conversion to bytes is one vector loop too
    Real r[kRun], g[kRun], b[kRun];
    Color at(int i) const { return {r[i], g[i], b[i]}; }
  };
  void shadeRun(const TriangleSetUp& setUp, int y, int firstX, int count, RunColors& colors, ShadingCounts& counts) const;
  // One pixel of a set-up triangle.
  Color shade(std::uint32_t triangle, int x, int y, ShadingCounts& counts) const;
  SurfacePoint surfacePoint(std::uint32_t triangle, int x, int y) const;

 private:
  using Vec = glm::vec<3, Real>;
  struct LightSource {
    bool directional;
    Vec towardLight;  // directional: unit
    Vec position;     // point: relative to the eye
    Real intensity;
  };
  // A run's surface points, one array per coordinate.
  struct RunPoints {
    Real b0[kRun], b1[kRun], b2[kRun];  // barycentric coordinates
    Real nx[kRun], ny[kRun], nz[kRun];  // unit normal, facing the viewer
    Vec position(const TriangleSetUp& setUp, int i) const;  // relative to the eye
  };

  TriangleSetUp makeSetUp(std::uint32_t triangle, const VertexTriangles* around, std::int64_t& fromMesh) const;
  void setUpClaimed(const std::vector<std::uint32_t>& claimed, int threads, Stats& stats);
  void interpolateRun(const TriangleSetUp& setUp, int y, int firstX, int count, RunPoints& points) const;
  Vec toViewer(const Vec& position) const;

  const PreparedScene& scene_;
  const CameraTransform camera_;
  const ShadowTest* shadows_;
  bool smooth_, lit_, specular_;
  Real ambient_;
  Ray sampleRays_[3];  // through pixels (0, 0), (1, 0), (0, 1), origins relative to the eye
  std::vector<LightSource> lights_;
  std::vector<std::uint32_t> slotOf_;  // per triangle: 1 + its index in setUps_, 0 before it is set up
  std::vector<TriangleSetUp> setUps_;
};

extern template class PixelShader<float>;
extern template class PixelShader<double>;

// Phase "shading": every triangle the frame shows set up, every covered pixel shaded,
// the background filled.
template <class Real>
void shadeFrame(const PreparedScene& scene, Frame& frame, PixelShader<Real>& shader, int threads, Stats& stats);

// A color channel in [0, 1] as an 8-bit value (clamped, rounded to nearest).
template <class Real>
std::uint8_t channelByte(Real value) {
  return static_cast<std::uint8_t>(std::clamp(value, Real(0), Real(1)) * 255 + Real(0.5));
}

}  // namespace hsr
