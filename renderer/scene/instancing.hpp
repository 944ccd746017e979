// Where an object's copies go: its model transform, and how it is copied (a grid, a
// ring, a seeded scatter or a seeded area of boxes), each copy a world-from-object matrix.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/util/math.hpp"

namespace hsr {

// Model transform: scale, then rotate about x, then y, then z (degrees), then translate.
struct Transform {
  dvec3 translate{0};
  dvec3 rotateDegrees{0};
  dvec3 scale{1};
  dmat4 worldFromObject() const;
};

// How an object is copied. Each copy gets its own object id.
struct Instancing {
  enum class Kind { single, grid, ring, scatter, area } kind = Kind::single;
  // grid: count per axis and spacing; copies centered on the object's own position.
  glm::ivec3 gridCount{1};
  dvec3 gridSpacing{0};
  // ring and scatter: copies around `center` (about the y axis).
  int count = 1;
  dvec3 center{0};
  double radius = 0;  // ring: every copy at this distance, facing the center
  // scatter: seeded uniform positions in the annulus [innerRadius, radius] on the xz plane,
  // random yaw, uniform scale in [minScale, maxScale].
  double innerRadius = 0;
  std::uint64_t seed = 1;
  double minScale = 1, maxScale = 1;
  // area: seeded uniform positions in the box [from, to], no rotation, each axis scaled
  // uniformly in [minScales, maxScales] (a city of random boxes).
  dvec3 from{0}, to{0};
  dvec3 minScales{1}, maxScales{1};

  std::size_t copyCount() const;
  std::vector<dmat4> copies() const;  // worldFromObject of each copy, applied after the object's transform
};

}  // namespace hsr
