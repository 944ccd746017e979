// VisibleSet: what the culling stages (algorithms/culling) hand on to a surface
// algorithm: the triangles still to draw. A stage only ever removes triangles, and never
// reorders them, so the algorithm draws the survivors in the same submission order (and
// breaks depth ties the same way) as it would draw the whole scene.
#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

#include "renderer/prepare.hpp"

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

}  // namespace hsr
