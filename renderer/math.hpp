// GLM aliases and the few exact helpers the rasterizer and its tests share.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

namespace hsr {

using glm::dmat3;
using glm::dmat4;
using glm::dvec2;
using glm::dvec3;
using glm::dvec4;
using glm::vec3;

using Triangle = std::array<std::uint32_t, 3>;  // vertex indices, counter-clockwise = front

// Coordinates beyond this are refused on input (scenes and OBJ files): no scene needs
// them, and the float stages (tinyobjloader's storage, depth buffers) stay finite.
inline constexpr double kMaxCoordinate = 1e12;

// Twice the signed area of (a, b, c) in a y-down image: positive when the three points
// run clockwise on screen. Exact for the fixed-point coordinates the rasterizer uses.
inline std::int64_t orient2d(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by,
                             std::int64_t cx, std::int64_t cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

// 1 / d per axis, and +-infinity (by d's sign) for a zero component without dividing by
// zero: the reciprocal ray tests use, with floating-point exceptions trapped or not.
inline dvec3 inverseOf(const dvec3& d) {
  dvec3 inverse;
  for (int axis = 0; axis < 3; ++axis)
    inverse[axis] = d[axis] != 0 ? 1.0 / d[axis] : std::copysign(std::numeric_limits<double>::infinity(), d[axis]);
  return inverse;
}

}  // namespace hsr
