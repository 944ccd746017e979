// Shadow mapping (Williams 1978): render the scene's depth from each light with the
// z-buffer (algorithms/zbuffer, found in the registry like any algorithm), then call a
// point shadowed when it lies farther from the light than the depth the map stored
// where the point lands.
//
// Only opaque surfaces cast shadows (a transparent one lets the light through).
// A directional light looks along its direction with an orthographic view that holds
// the scene's bounding sphere; a point light looks out of a cube of six 90-degree
// views. One depth sample per texel and a constant bias make the two classic errors
// visible: with too little bias a surface shadows itself in stripes (acne, the map's
// samples lie a little in front of the surface between texel centers); with too much,
// shadows come loose from their casters (peter-panning). The bias is measured in texels
// at the receiver, times the receiver's slope to the light (tan of the angle between its
// normal and the light, from 1 to 10), so the same setting holds at every resolution and
// on every face.
#pragma once

#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/shading/shading.hpp"
#include "renderer/util/memory.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::pipeline {

class ShadowMaps : public ShadowTest {
 public:
  // Renders every light's views. Stats: phase "shadow maps", counters "shadow maps
  // rendered", "shadow map texels" (cleared and written: the maps' memory), "shadow map
  // fragments written".
  ShadowMaps(const PreparedScene& scene, const ShadowSettings& settings, int threads, Stats& stats);

  bool shadowed(std::size_t light, const dvec3& point, std::uint32_t triangle) const override;

 private:
  // One view of one light.
  struct View {
    CameraTransform camera;
    PixelBuffer<float> depth;  // the z-buffer's frame.depth: view distance, +infinity where nothing was drawn
    double texelsPerUnit;      // orthographic: texels per world unit; perspective: per unit at distance 1
  };
  const PreparedScene& scene_;
  double biasTexels_;
  std::vector<std::vector<View>> views_;  // per scene light
};

// How many views a light's shadow map has: 1 for a directional light, 6 (a cube) for a point light.
inline int shadowViewCount(const Light& light) { return light.kind == Light::Kind::directional ? 1 : 6; }

}  // namespace hsr::pipeline
