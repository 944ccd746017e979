#include "renderer/scene/instancing.hpp"

#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/util/portable_math.hpp"

namespace hsr {

dmat4 Transform::worldFromObject() const {
  dmat4 m = glm::translate(dmat4(1), translate);
  m = rotate(m, glm::radians(rotateDegrees.z), dvec3(0, 0, 1));
  m = rotate(m, glm::radians(rotateDegrees.y), dvec3(0, 1, 0));
  m = rotate(m, glm::radians(rotateDegrees.x), dvec3(1, 0, 0));
  return glm::scale(m, scale);
}

std::size_t Instancing::copyCount() const {
  switch (kind) {
    case Kind::single: return 1;
    case Kind::grid: return std::size_t(gridCount.x) * std::size_t(gridCount.y) * std::size_t(gridCount.z);
    case Kind::ring:
    case Kind::scatter:
    case Kind::area: return std::size_t(count);
  }
  return 1;
}

std::vector<dmat4> Instancing::copies() const {
  std::vector<dmat4> result;
  // splitmix64: the same copies on every platform (std distributions are not portable).
  std::uint64_t state = seed;
  const auto uniform = [&state]() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  switch (kind) {
    case Kind::single: result.push_back(dmat4(1)); break;
    case Kind::grid: {
      const dvec3 first = -0.5 * dvec3(gridCount - 1) * gridSpacing;
      for (int z = 0; z < gridCount.z; ++z)
        for (int y = 0; y < gridCount.y; ++y)
          for (int x = 0; x < gridCount.x; ++x)
            result.push_back(glm::translate(dmat4(1), first + dvec3(x, y, z) * gridSpacing));
      break;
    }
    case Kind::ring:
      // Copy k sits at angle 2πk/count about the y axis, starting straight ahead of
      // `center` along -z, rotated with its position so it keeps facing the center.
      for (int k = 0; k < count; ++k) {
        const double angle = 2 * std::numbers::pi * k / count;
        dmat4 m = glm::translate(dmat4(1), center);
        m = rotate(m, angle, dvec3(0, 1, 0));
        result.push_back(glm::translate(m, dvec3(0, 0, -radius)));
      }
      break;
    case Kind::scatter:
      for (int k = 0; k < count; ++k) {
        // Uniform over the annulus' area: radius from the square root of a uniform area fraction.
        const double r2 = innerRadius * innerRadius + uniform() * (radius * radius - innerRadius * innerRadius);
        const double angle = 2 * std::numbers::pi * uniform();
        const double yaw = 2 * std::numbers::pi * uniform();
        const double scale = minScale + uniform() * (maxScale - minScale);
        const double r = std::sqrt(r2);
        dmat4 m = glm::translate(dmat4(1), center + dvec3(r * portable::sin(angle), 0, -r * portable::cos(angle)));
        m = rotate(m, yaw, dvec3(0, 1, 0));
        result.push_back(glm::scale(m, dvec3(scale)));
      }
      break;
    case Kind::area:
      for (int k = 0; k < count; ++k) {
        dvec3 position, scale;
        for (int axis = 0; axis < 3; ++axis) position[axis] = from[axis] + uniform() * (to[axis] - from[axis]);
        for (int axis = 0; axis < 3; ++axis) scale[axis] = minScales[axis] + uniform() * (maxScales[axis] - minScales[axis]);
        result.push_back(glm::scale(glm::translate(dmat4(1), position), scale));
      }
      break;
  }
  return result;
}

}  // namespace hsr
