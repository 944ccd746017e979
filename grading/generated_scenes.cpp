#include "grading/generated_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "renderer/scene/mesh.hpp"
#include "renderer/util/portable_math.hpp"

namespace hsr::grading {
namespace {

constexpr double kPi = 3.14159265358979323846;

// splitmix64 (Steele, Lea and Flood 2014): a counter run through a mixing function.
// Every draw is a statement of its own or an element of a braced list, never two
// arguments of one call or two operands of one operator, whose order C++ leaves to the
// compiler: the same seed must make the same scene whatever compiled it.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform(double low, double high) { return low + (high - low) * double(next() >> 11) * 0x1.0p-53; }
  int integer(int low, int high) { return low + int(next() % std::uint64_t(high - low + 1)); }  // both ends included
  bool coin() { return next() >> 63; }
  // A number from 10^low to 10^high, as a mantissa in [1, 10) times a power of ten:
  // multiplications and a division of exact integers, not std::pow, whose last bit
  // differs between libraries.
  double decades(int low, int high) {
    const int exponent = integer(low, high - 1);
    double power = 1;
    for (int k = 0; k < std::abs(exponent); ++k) power *= 10;
    return uniform(1, 10) * (exponent >= 0 ? power : 1 / power);
  }
  // A point in the box from `low` to `high`, its coordinates drawn x, y, z.
  dvec3 point(const dvec3& low, const dvec3& high) {
    const double x = uniform(low.x, high.x), y = uniform(low.y, high.y), z = uniform(low.z, high.z);
    return {x, y, z};
  }
  // A point on the unit sphere, by its latitude's sine and its longitude.
  dvec3 direction() {
    const double z = uniform(-1, 1), angle = uniform(0, 2 * kPi), r = std::sqrt(1 - z * z);
    return {r * portable::cos(angle), z, r * portable::sin(angle)};
  }

 private:
  std::uint64_t state_;
};

// A scene of an odd size (61 to 161 by 41 to 101 pixels): sizes a program may get wrong.
Scene oddSized(Random& random) {
  Scene scene;
  scene.width = 2 * random.integer(30, 80) + 1;
  scene.height = 2 * random.integer(20, 50) + 1;
  return scene;
}

Camera perspectiveAt(const dvec3& eye, const dvec3& target, double fovY, double near = 0.1, double far = 100) {
  Camera camera;
  camera.eye = eye;
  camera.target = target;
  camera.fovYDegrees = fovY;
  camera.near = near;
  camera.far = far;
  return camera;
}

void add(Scene& scene, Mesh mesh) {
  SceneObject object;
  object.name = "object" + std::to_string(scene.objects.size());
  object.mesh = std::make_shared<const Mesh>(std::move(mesh));
  scene.objects.push_back(std::move(object));
}

// A mesh turned by `angle` about the y axis, then moved by `offset`: world coordinates
// written into the mesh, so the triangle file holds what was generated.
Mesh placed(Mesh mesh, double angle, const dvec3& offset) {
  const double c = portable::cos(angle), s = portable::sin(angle);
  for (dvec3& p : mesh.positions) p = dvec3(c * p.x + s * p.z, p.y, -s * p.x + c * p.z) + offset;
  return mesh;
}

Mesh triangles(const std::vector<dvec3>& corners) {
  Mesh mesh;
  mesh.positions = corners;
  for (std::uint32_t i = 0; i + 2 < corners.size(); i += 3) mesh.triangles.push_back({i, i + 1, i + 2});
  return mesh;
}

// Boxes and spheres in a cube of side 4 about the origin.
void addBlocks(Scene& scene, Random& random) {
  for (int k = random.integer(4, 8); k > 0; --k) {
    const dvec3 size = random.point(dvec3(0.3), dvec3(1.6));
    const dvec3 at = random.point({-1.6, -1.2, -1.6}, {1.6, 1.2, 1.6});
    add(scene, placed(makeBox(size), random.uniform(0, kPi), at));
  }
  for (int k = random.integer(1, 2); k > 0; --k) {
    const dvec3 at = random.point({-1.4, -1, -1.4}, {1.4, 1, 1.4});
    add(scene, placed(makeSphere(random.uniform(0.4, 0.9), 12, 8), 0, at));
  }
}

Scene visibility(std::uint64_t seed) {
  Random random(seed);
  Scene scene = oddSized(random);
  addBlocks(scene, random);
  const double distance = random.uniform(6, 9);
  const dvec3 eye = distance * random.direction();
  scene.camera = perspectiveAt(eye, {0, 0, 0}, random.uniform(35, 60));
  return scene;
}

Scene orthographic(std::uint64_t seed) {
  Scene scene = visibility(seed);
  scene.camera.projection = Projection::orthographic;
  scene.camera.orthoHeight = 6;
  return scene;
}

// Fans and a grid whose corners lie on pixel centers and corners: many centers lie
// exactly on edges, where only the top-left rule decides. World (x, y) is pixel
// (x + 64, 32 - y) of a 128 x 64 image (both powers of two: every coordinate dyadic).
Scene fillRule(std::uint64_t seed) {
  Random random(seed);
  Scene scene;
  scene.width = 128;
  scene.height = 64;
  scene.camera.projection = Projection::orthographic;
  scene.camera.eye = {0, 0, 10};
  scene.camera.target = {0, 0, 0};
  scene.camera.orthoHeight = 64;
  scene.camera.near = 1;
  scene.camera.far = 100;
  const auto half = [](double v) { return std::round(2 * v) / 2; };  // to the nearest half pixel
  std::vector<dvec3> corners;
  const auto triangle = [&](dvec3 a, dvec3 b, dvec3 c, bool flip) {
    if ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x) == 0) return;  // no area
    if (flip) std::swap(b, c);  // both windings: nothing is culled
    corners.insert(corners.end(), {a, b, c});
  };
  for (int fan = random.integer(2, 4), layer = 0; fan > 0; --fan, ++layer) {
    const double x = half(random.uniform(-50, 50)), y = half(random.uniform(-20, 20));
    const dvec3 center(x, y, -layer);
    const int count = random.integer(5, 9);
    std::vector<double> angles;
    for (int k = 0; k < count; ++k) angles.push_back(random.uniform(0, 2 * kPi));
    std::sort(angles.begin(), angles.end());
    const double radius = random.uniform(6, 20);
    const bool flip = random.coin();
    for (int k = 0; k < count; ++k) {
      const double a0 = angles[std::size_t(k)], a1 = angles[std::size_t((k + 1) % count)];
      const dvec3 p(half(center.x + radius * portable::cos(a0)), half(center.y + radius * portable::sin(a0)), center.z);
      const dvec3 q(half(center.x + radius * portable::cos(a1)), half(center.y + radius * portable::sin(a1)), center.z);
      if (std::fmod(a1 - a0 + 2 * kPi, 2 * kPi) < kPi) triangle(center, p, q, flip);
    }
  }
  // A grid of square cells on pixel centers, each cut along a random diagonal: the
  // diagonals run through centers too.
  const int cell = random.integer(1, 4), columns = random.integer(4, 12), rows = random.integer(3, 8);
  const double left = std::floor(random.uniform(-60, 60 - columns * cell)) + 0.5, bottom = std::floor(random.uniform(-30, 30 - rows * cell)) + 0.5;
  const dvec3 origin(left, bottom, -5);
  for (int i = 0; i < columns; ++i)
    for (int j = 0; j < rows; ++j) {
      const dvec3 a = origin + dvec3(i * cell, j * cell, 0), b = a + dvec3(cell, 0, 0), c = a + dvec3(cell, cell, 0), d = a + dvec3(0, cell, 0);
      if (random.coin()) {
        triangle(a, b, c, false);
        triangle(a, c, d, false);
      } else {
        triangle(a, b, d, false);
        triangle(b, c, d, false);
      }
    }
  // Last, a triangle on the grid's plane across it: exactly as near as the grid, so
  // the grid, drawn first, keeps every center both cover.
  const dvec3 inside = origin + dvec3(std::floor(columns * cell / 2.0), std::floor(rows * cell / 2.0), 0);
  triangle(inside + dvec3(-6, -5, 0), inside + dvec3(7, -3, 0), inside + dvec3(1, 6, 0), random.coin());
  add(scene, triangles(corners));
  return scene;
}

// A floor and walls that run past the eye, and triangles with a corner behind it.
Scene nearPlane(std::uint64_t seed) {
  Random random(seed);
  Scene scene = oddSized(random);
  const double floorY = -random.uniform(0.5, 1.5), wallX = random.uniform(1, 3);
  add(scene, triangles({{-20, floorY, 10}, {20, floorY, 10}, {20, floorY, -40}, {-20, floorY, 10}, {20, floorY, -40}, {-20, floorY, -40}}));
  add(scene, triangles({{-wallX, -5, 8}, {-wallX, -5, -30}, {-wallX, 6, -30}, {-wallX, -5, 8}, {-wallX, 6, -30}, {-wallX, 6, 8}}));
  std::vector<dvec3> corners;
  for (int k = random.integer(3, 6); k > 0; --k) {
    corners.push_back({random.uniform(-2, 2), random.uniform(-1, 1), random.uniform(0.5, 3)});  // behind the eye
    corners.push_back({random.uniform(-3, 3), random.uniform(-1, 2), -random.uniform(1, 8)});
    corners.push_back({random.uniform(-3, 3), random.uniform(-1, 2), -random.uniform(1, 8)});
  }
  // A visor from a third of the near distance to four times it, across the middle of
  // the view: what lies between the eye and the near plane must not be drawn.
  const double near = random.uniform(0.05, 0.5), top = random.uniform(-0.2, 0.2) * near;
  const dvec3 a(-3 * near, top, -0.3 * near), b(3 * near, top, -0.3 * near), c(12 * near, -2 * near, -4 * near), d(-12 * near, -2 * near, -4 * near);
  corners.insert(corners.end(), {a, d, c, a, c, b});
  add(scene, triangles(corners));
  addBlocks(scene, random);
  const dvec3 target = random.point({-0.5, -0.3, -1}, {0.5, 0.1, -1});
  const double fovY = random.uniform(50, 80);
  scene.camera = perspectiveAt({0, 0, 0}, target, fovY, near);
  return scene;
}

// The blocks and their camera, all moved 10^4 to 10^7 from the origin.
Scene farFromOrigin(std::uint64_t seed) {
  Scene scene = visibility(seed);
  Random random(seed ^ 0xF00D);
  const double distance = random.decades(4, 7);
  const dvec3 offset = distance * random.direction();
  for (SceneObject& object : scene.objects) {
    Mesh mesh = *object.mesh;
    for (dvec3& p : mesh.positions) p += offset;
    object.mesh = std::make_shared<const Mesh>(std::move(mesh));
  }
  scene.camera.eye += offset;
  scene.camera.target += offset;
  return scene;
}

// Overlapping rectangles on a few planes z = constant: exactly coplanar, so the
// reference certifies the ties, and any of the tied triangles is right there.
Scene coplanar(std::uint64_t seed) {
  Random random(seed);
  Scene scene = oddSized(random);
  std::vector<dvec3> corners;
  const double planes[3] = {-0.5, 0, 0.25};
  for (int k = random.integer(6, 12); k > 0; --k) {
    const double z = planes[random.integer(0, 2)];
    const double x0 = std::round(random.uniform(-3, 2) * 8) / 8, y0 = std::round(random.uniform(-2, 1) * 8) / 8;
    const double x1 = x0 + std::round(random.uniform(0.5, 3) * 8) / 8, y1 = y0 + std::round(random.uniform(0.5, 2) * 8) / 8;
    corners.insert(corners.end(), {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y0, z}, {x1, y1, z}, {x0, y1, z}});
  }
  add(scene, triangles(corners));
  scene.camera = perspectiveAt({random.uniform(-2, 2), random.uniform(-1.5, 1.5), random.uniform(5, 8)}, {0, 0, 0}, 50);
  return scene;
}

// Long, thin triangles (a width of 10^-3 to 10^-6 of their length) over a backdrop.
Scene slivers(std::uint64_t seed) {
  Random random(seed);
  Scene scene = oddSized(random);
  std::vector<dvec3> corners = {{-4, -3, -2}, {4, -3, -2}, {4, 3, -2}, {-4, -3, -2}, {4, 3, -2}, {-4, 3, -2}};
  for (int k = random.integer(8, 16); k > 0; --k) {
    const dvec3 a = random.point({-3, -2, -1.5}, {3, 2, 1});
    const double length = random.uniform(2, 5);
    const dvec3 along = length * random.direction();
    const dvec3 side = glm::normalize(glm::cross(along, random.direction()));
    const dvec3 across = side * length * random.decades(-6, -3);
    corners.insert(corners.end(), {a, a + along, a + 0.5 * along + across});
  }
  add(scene, triangles(corners));
  scene.camera = perspectiveAt({random.uniform(-1, 1), random.uniform(-1, 1), 7}, {0, 0, 0}, 55);
  return scene;
}

// Large triangles through one another: no order of whole triangles is right.
Scene interpenetrating(std::uint64_t seed) {
  Random random(seed);
  Scene scene = oddSized(random);
  std::vector<dvec3> corners;
  for (int k = random.integer(6, 12) * 3; k > 0; --k) corners.push_back({random.uniform(-2, 2), random.uniform(-1.5, 1.5), random.uniform(-2, 2)});
  add(scene, triangles(corners));
  const double distance = random.uniform(6, 8);
  scene.camera = perspectiveAt(distance * random.direction(), {0, 0, 0}, 50);
  return scene;
}

// Three to five tilted bars around a center, each crossing its neighbours near their
// ends: cyclic overlaps, which no order of whole bars can draw.
Scene cycles(std::uint64_t seed) {
  Random random(seed);
  Scene scene = oddSized(random);
  std::vector<dvec3> corners;
  const int bars = random.integer(3, 5);
  const double start = random.uniform(0, 2 * kPi), tilt = random.uniform(0.15, 0.4);
  for (int k = 0; k < bars; ++k) {
    const double angle = start + 2 * kPi * k / bars;
    const dvec3 center(0.7 * portable::cos(angle), 0.7 * portable::sin(angle), 0);
    const dvec3 along(portable::cos(angle + 1.9), portable::sin(angle + 1.9), 0), across(-along.y, along.x, 0);
    const dvec3 a = center - 2.0 * along + dvec3(0, 0, tilt), b = center + 2.0 * along - dvec3(0, 0, tilt);
    const dvec3 w = 0.3 * across;
    corners.insert(corners.end(), {a - w, b - w, b + w, a - w, b + w, a + w});
  }
  add(scene, triangles(corners));
  scene.camera = perspectiveAt({random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(5, 7)}, {0, 0, 0}, 60);
  return scene;
}

// Boxes before, across and beyond a far plane 6 to 12 away, on a floor running past it:
// nothing beyond the far plane may be drawn.
Scene farPlane(std::uint64_t seed) {
  Random random(seed);
  Scene scene = oddSized(random);
  const double far = random.uniform(6, 12), floorY = -random.uniform(0.8, 1.5);
  add(scene, triangles({{-30, floorY, 5}, {30, floorY, 5}, {30, floorY, -60}, {-30, floorY, 5}, {30, floorY, -60}, {-30, floorY, -60}}));
  for (int k = random.integer(5, 9); k > 0; --k) {
    const dvec3 size = random.point(dvec3(0.5), dvec3(2));
    const double depth = random.uniform(0.4, 1.6) * far;
    const double across = random.uniform(-0.5, 0.5) * depth;
    add(scene, placed(makeBox(size), random.uniform(0, kPi), {across, floorY + size.y / 2, -depth}));
  }
  const double fovY = random.uniform(40, 70);
  scene.camera = perspectiveAt({0, 0, 0}, {0, -0.1, -1}, fovY, 0.1, far);
  return scene;
}

// A wall of boxes 4 away with gaps of a few pixels, and small boxes and spheres behind
// it, some seen only through a gap: what an occlusion culler must keep.
Scene occlusion(std::uint64_t seed) {
  Random random(seed);
  Scene scene = oddSized(random);
  for (double x = -4; x < 4;) {
    const double width = random.uniform(0.5, 1.5), height = random.uniform(1.5, 3);
    add(scene, placed(makeBox({width, height, 0.3}), 0, {x + width / 2, height / 2 - 1.2, -4}));
    x += width + random.uniform(0.02, 0.1);
  }
  for (int k = random.integer(8, 16); k > 0; --k) {
    const dvec3 at = random.point({-3, -1, -12}, {3, 1.2, -6});
    const double size = random.uniform(0.15, 0.6);
    add(scene, placed(random.coin() ? makeBox(dvec3(size)) : makeSphere(size / 2, 10, 6), 0, at));
  }
  const double fovY = random.uniform(40, 60);
  scene.camera = perspectiveAt({0, 0, 0}, {0, 0, -1}, fovY);
  return scene;
}

}  // namespace

const std::vector<SceneGenerator>& sceneGenerators() {
  static const std::vector<SceneGenerator> generators = {
      {"visibility", "boxes and spheres under perspective, at an odd size", visibility, false, true},
      {"orthographic", "boxes and spheres under an orthographic camera", orthographic, false, true},
      {"fill-rule", "fans and a grid with pixel centers exactly on shared edges", fillRule, true},
      {"near-plane", "a floor, a wall and triangles reaching behind the eye", nearPlane},
      {"far-from-origin", "boxes and spheres 10^4 to 10^7 from the origin", farFromOrigin, false, true},
      {"coplanar", "overlapping rectangles on shared planes", coplanar},
      {"slivers", "triangles 10^3 to 10^6 times longer than wide", slivers},
      {"interpenetrating", "large triangles through one another", interpenetrating},
      {"cycles", "tilted bars overlapping cyclically", cycles},
      {"far-plane", "boxes before, across and beyond the far plane, on a floor running past it", farPlane},
      {"occlusion", "a wall with gaps of a few pixels and objects behind it", occlusion},
  };
  return generators;
}

}  // namespace hsr::grading
