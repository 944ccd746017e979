// VisibleSet: what the culling stages (algorithms/culling) hand on to a surface
// algorithm: the triangles still to draw. A stage only ever removes triangles, and never
// reorders them, so the algorithm draws the survivors in the same submission order (and
// breaks depth ties the same way) as it would draw the whole scene.
#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

#include "renderer/scene/prepare.hpp"

namespace hsr {

struct VisibleSet {
  std::vector<std::uint32_t> triangles;  // global triangle ids, ascending

  static VisibleSet everything(const PreparedScene& scene) {
    VisibleSet set;
    set.triangles.resize(scene.triangleCount());
    std::iota(set.triangles.begin(), set.triangles.end(), 0u);
    return set;
  }
};

// The triangles of `submitted` (all when null) whose object is opaque (opacity 1), or
// transparent: the z-buffer's depth pass and sorted pass, and the shadow maps' casters.
inline VisibleSet trianglesByOpacity(const PreparedScene& scene, const VisibleSet* submitted, bool opaque) {
  VisibleSet result;
  const auto keep = [&](std::uint32_t triangle) {
    if ((scene.instanceOf(triangle).opacity >= 1) == opaque) result.triangles.push_back(triangle);
  };
  if (submitted) {
    for (const std::uint32_t triangle : submitted->triangles) keep(triangle);
  } else {
    for (std::uint32_t triangle = 0; triangle < scene.triangleCount(); ++triangle) keep(triangle);
  }
  return result;
}

}  // namespace hsr
