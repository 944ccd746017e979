// A seeded generator of small random scenes for the property tests: the same seed gives
// the same scene on every platform (splitmix64 and our own conversions to doubles; the
// standard distributions differ between libraries). Every draw is its own statement, in
// a fixed order: the order a compiler evaluates a call's arguments in, or an operator's
// operands, is its own (GCC on x86-64 and on arm64 differed, which made the scenes
// differ); the order kept is the one GCC on x86-64 used, so the scenes are those the
// tests have always run.
//
// A scene holds one to four objects, each one of:
//   - a box of random size, turned and placed at random;
//   - a low-polygon sphere;
//   - a soup of random triangles, with the cases exact visibility finds hard mixed in:
//     slivers (a corner almost on the opposite edge), coplanar overlapping pairs, and
//     pairs that pass through each other.
// Half the scenes place their objects in separate cells of a grid instead, so that
// nothing interpenetrates and Appel's method (closed, separate solids) accepts them.
// The camera is perspective or orthographic and looks from outside, from inside an
// object, or along one of a box's faces (the eye in the face's plane).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "renderer/scene/mesh.hpp"
#include "renderer/scene/scene.hpp"

namespace hsr::test {

class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {  // splitmix64
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * double(next() >> 11) * 0x1p-53; }
  int below(int n) { return int(next() % std::uint64_t(n)); }
  bool chance(double p) { return uniform(0, 1) < p; }
  dvec3 point(double extent) { return {uniform(-extent, extent), uniform(-extent, extent), uniform(-extent, extent)}; }
  dvec3 direction() {
    for (;;) {
      const dvec3 d = point(1);
      const double length = glm::length(d);
      if (length > 0.1 && length <= 1) return d / length;
    }
  }

 private:
  std::uint64_t state_;
};

struct RandomScene {
  Scene scene;
  std::string camera;   // "outside", "inside", "along a face"
  bool separate = false;  // objects in separate grid cells: no two interpenetrate
};

namespace detail {

inline Mesh triangleSoup(SeededRandom& random) {
  Mesh mesh;
  const auto add = [&](const dvec3& a, const dvec3& b, const dvec3& c) {
    const auto first = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.triangles.push_back({first, first + 1, first + 2});
  };
  const int count = 1 + random.below(6);
  for (int i = 0; i < count; ++i) {
    const dvec3 a = random.point(1.5), b = random.point(1.5), c = random.point(1.5);
    switch (random.below(4)) {
      case 0: add(a, b, c); break;
      case 1: {  // a sliver
        const dvec3 off = random.direction();
        const double along = random.uniform(0, 1);
        add(a, b, a + along * (b - a) + 1e-6 * off);
        break;
      }
      case 2: {  // a coplanar overlapping pair
        add(a, b, c);
        const double s = random.uniform(0.2, 0.8), t = random.uniform(0.2, 0.8);
        add(a + s * (b - a), c + t * (b - c), c + s * (a - c) + t * (b - a));
        break;
      }
      default: {  // a pair passing through each other: the second pierces the first's plane
        add(a, b, c);
        const dvec3 middle = (a + b + c) / 3.0, normal = glm::normalize(glm::cross(b - a, c - a));
        add(middle + 0.5 * normal, middle - 0.5 * normal + 0.4 * (a - middle), middle - 0.5 * normal + 0.4 * (b - middle));
      }
    }
  }
  return mesh;
}

}  // namespace detail

inline RandomScene randomScene(std::uint64_t seed) {
  SeededRandom random(seed);
  RandomScene result;
  Scene& scene = result.scene;
  scene.width = 32;
  scene.height = 24;
  result.separate = random.chance(0.5);
  const int objects = 1 + random.below(4);
  const dvec3 cells[4] = {{-1.8, 0, -1.8}, {1.8, 0, -1.8}, {-1.8, 0, 1.8}, {1.8, 0, 1.8}};
  for (int i = 0; i < objects; ++i) {
    SceneObject object;
    object.name = "object" + std::to_string(i);
    const int kind = result.separate ? random.below(2) : random.below(3);
    if (kind == 0) {
      object.solid.kind = Solid::Kind::box;
      object.solid.size = {random.uniform(0.2, 1.4), random.uniform(0.2, 1.4), random.uniform(0.2, 1.4)};
      object.mesh = std::make_shared<const Mesh>(makeBox(object.solid.size));
    } else if (kind == 1) {
      object.solid.kind = Solid::Kind::sphere;
      object.solid.radius = random.uniform(0.2, 0.7);
      const int stacks = 4 + random.below(4), slices = 6 + random.below(6);
      object.mesh = std::make_shared<const Mesh>(makeSphere(object.solid.radius, slices, stacks));
    } else {
      object.mesh = std::make_shared<const Mesh>(detail::triangleSoup(random));
    }
    // A separate object stays inside its cell, 1.8 from its center each way: a box's
    // half-diagonal is at most 1.22, and the offset from the center at most 0.52.
    object.transform.rotateDegrees = {random.uniform(0, 360), random.uniform(0, 360), random.uniform(0, 360)};
    object.transform.translate = result.separate ? cells[i] + random.point(0.3) : random.point(1.5);
    const double blue = random.uniform(0.2, 1), green = random.uniform(0.2, 1), red = random.uniform(0.2, 1);
    object.color = vec3(float(red), float(green), float(blue));
    scene.objects.push_back(object);
  }

  Camera& camera = scene.camera;
  if (random.chance(0.25)) {
    camera.projection = Projection::orthographic;
    camera.orthoHeight = random.uniform(2, 8);
  } else {
    camera.fovYDegrees = random.uniform(30, 90);
  }
  camera.near = random.uniform(0.01, 0.5);
  camera.far = 100;
  const SceneObject& first = scene.objects.front();
  const int view = random.below(10);
  if (view == 0) {  // inside the first object, looking anywhere
    result.camera = "inside";
    camera.eye = first.transform.translate + random.point(0.05);
    camera.target = camera.eye + random.direction();
  } else if (view == 1 && first.solid.kind == Solid::Kind::box) {  // in the plane of a box's face, looking along it
    result.camera = "along a face";
    scene.objects.front().transform.rotateDegrees = dvec3(0);  // axis-aligned: the face's plane is y = top
    const double top = first.transform.translate.y + first.solid.size.y / 2;
    camera.eye = {first.transform.translate.x + random.uniform(-4, 4), top, first.transform.translate.z + 5};
    camera.target = {first.transform.translate.x, top, first.transform.translate.z};
  } else {
    result.camera = "outside";
    camera.target = random.point(0.5);
    const double distance = random.uniform(4, 9);
    camera.eye = camera.target + random.direction() * distance;
  }
  if (std::abs(glm::dot(glm::normalize(camera.target - camera.eye), camera.up)) > 0.99) camera.up = {1, 0, 0};
  return result;
}

}  // namespace hsr::test
