// GLM aliases and the few exact helpers the rasterizer and its tests share.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

#include "renderer/util/portable_math.hpp"

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

// m times the rotation by `angle` radians about `axis`: glm::rotate's formula, term for
// term, with the sine and cosine that are the same bits on every target
// (portable_math.hpp) where glm's would be the C library's.
inline dmat4 rotate(const dmat4& m, double angle, const dvec3& axis) {
  const double c = portable::cos(angle), s = portable::sin(angle);
  const dvec3 unit = glm::normalize(axis), temp = (1 - c) * unit;
  dmat4 rotation;
  rotation[0][0] = c + temp[0] * unit[0];
  rotation[0][1] = temp[0] * unit[1] + s * unit[2];
  rotation[0][2] = temp[0] * unit[2] - s * unit[1];
  rotation[1][0] = temp[1] * unit[0] - s * unit[2];
  rotation[1][1] = c + temp[1] * unit[1];
  rotation[1][2] = temp[1] * unit[2] + s * unit[0];
  rotation[2][0] = temp[2] * unit[0] + s * unit[1];
  rotation[2][1] = temp[2] * unit[1] - s * unit[0];
  rotation[2][2] = c + temp[2] * unit[2];
  dmat4 result;
  result[0] = m[0] * rotation[0][0] + m[1] * rotation[0][1] + m[2] * rotation[0][2];
  result[1] = m[0] * rotation[1][0] + m[1] * rotation[1][1] + m[2] * rotation[1][2];
  result[2] = m[0] * rotation[2][0] + m[1] * rotation[2][1] + m[2] * rotation[2][2];
  result[3] = m[3];
  return result;
}

}  // namespace hsr
