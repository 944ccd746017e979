// Ray marching, the oldest way to ask a ray what it meets: walk along it from the near
// plane in fixed steps and, at every sample, ask whether the point is inside an object.
// The first object found inside is the one the pixel shows.
//
// What it cannot see is the lesson: an object thinner than the step (or the corner of
// one) can lie wholly between two samples and is skipped. Refinement (bisecting back
// between the last outside and the first inside sample) makes the depth of what was
// found more precise, but cannot find what was skipped.
//
// The inside tests: analytic for the procedural solids (box, sphere, cylinder, cone;
// a grid or height field stands for the solid beneath it), an occupancy grid
// (occupancy.hpp) for meshes. A march finds a point inside an object, not a triangle;
// the pixel is given the object's triangle nearest to that point.
#include "algorithms/ray_casting/march.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "algorithms/ray_casting/cast.hpp"
#include "algorithms/ray_casting/occupancy.hpp"
#include "renderer/rays/bvh.hpp"
#include "renderer/util/portable_math.hpp"

namespace hsr::ray_casting {
namespace {

Aabb sceneBounds(const PreparedScene& scene) {
  Aabb bounds;
  for (const dvec3& p : scene.positions()) bounds.grow(p);
  return bounds;
}

// Where samples are taken: the scene's bounding box grown by one step, so the solid
// beneath a height field at the bottom of the scene is at least a step thick.
Aabb marchBounds(const PreparedScene& scene, double stepLength) {
  Aabb bounds = sceneBounds(scene);
  if (bounds.empty()) return bounds;
  bounds.lo -= stepLength;
  bounds.hi += stepLength;
  return bounds;
}

Aabb transformed(const Aabb& box, const dmat4& transform) {
  Aabb result;
  for (int corner = 0; corner < 8; ++corner)
    result.grow(dvec3(transform * dvec4(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                                        corner & 4 ? box.hi.z : box.lo.z, 1.0)));
  return result;
}

Aabb intersection(const Aabb& a, const Aabb& b) {
  Aabb result{glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)};
  if (result.lo.x > result.hi.x || result.lo.y > result.hi.y || result.lo.z > result.hi.z) return Aabb{};
  return result;
}

// Is an object-space point inside the procedural solid? heightFieldTop caps a height
// field's solid at its mesh's highest vertex, so the solid fits the box the march uses.
bool insideSolid(const Solid& solid, const dvec3& p, double heightFieldTop) {
  switch (solid.kind) {
    case Solid::Kind::box:
      return std::abs(p.x) <= 0.5 * solid.size.x && std::abs(p.y) <= 0.5 * solid.size.y && std::abs(p.z) <= 0.5 * solid.size.z;
    case Solid::Kind::sphere:
      return glm::dot(p, p) <= solid.radius * solid.radius;
    case Solid::Kind::cylinder:
      return std::abs(p.y) <= 0.5 * solid.height && p.x * p.x + p.z * p.z <= solid.radius * solid.radius;
    case Solid::Kind::cone:  // radius shrinks linearly from the base (y = -h/2) to the apex
      return std::abs(p.y) <= 0.5 * solid.height && portable::hypot(p.x, p.z) <= solid.radius * (0.5 - p.y / solid.height);
    case Solid::Kind::heightField:
      return std::abs(p.x) <= 0.5 * solid.footprint.x && std::abs(p.z) <= 0.5 * solid.footprint.y &&
             p.y <= std::min(solid.function.evaluate(p.x, p.z), heightFieldTop);
    case Solid::Kind::none:
      break;
  }
  return false;
}

// The object-space box a solid fits in (a height field's reaches down to `floor`).
Aabb solidBounds(const Solid& solid, double heightFieldTop, double floor) {
  switch (solid.kind) {
    case Solid::Kind::box:
      return {-0.5 * solid.size, 0.5 * solid.size};
    case Solid::Kind::sphere:
      return {dvec3(-solid.radius), dvec3(solid.radius)};
    case Solid::Kind::cylinder:
    case Solid::Kind::cone:
      return {{-solid.radius, -0.5 * solid.height, -solid.radius}, {solid.radius, 0.5 * solid.height, solid.radius}};
    case Solid::Kind::heightField:
      return {{-0.5 * solid.footprint.x, std::min(floor, heightFieldTop), -0.5 * solid.footprint.y},
              {0.5 * solid.footprint.x, heightFieldTop, 0.5 * solid.footprint.y}};
    case Solid::Kind::none:
      break;
  }
  return {};
}

class Marcher {
 public:
  struct Counters {
    std::int64_t samples = 0, insideTests = 0, refinementSteps = 0, voxelsSearched = 0;
    Counters& operator+=(const Counters& other) {
      samples += other.samples;
      insideTests += other.insideTests;
      refinementSteps += other.refinementSteps;
      voxelsSearched += other.voxelsSearched;
      return *this;
    }
    static constexpr const char* kCostUnit = "march samples per ray";
    double cost() const { return double(samples); }
  };

  Marcher(const PreparedScene& scene, const Knobs& knobs, Stats& stats)
      : step_(marchStepLength(scene, knobs.step)), refine_(knobs.refine), bounds_(marchBounds(scene, step_)) {
    if (bounds_.empty()) return;
    // Step 1: one occupancy grid per object, shared by its copies. Meshes are tested
    // against it; every object uses it to name the triangle nearest to a point.
    {
      PhaseTimer timer(stats, "occupancy grids");
      for (const SceneObject& object : scene.scene().objects) {
        double top = -std::numeric_limits<double>::infinity();
        for (const dvec3& p : object.mesh->positions) top = std::max(top, p.y);
        objects_.push_back({&object, std::make_unique<OccupancyGrid>(*object.mesh, knobs.grid), top});
        stats.add("occupancy voxels", objects_.back().grid->voxelCount());
        stats.add("occupancy surface voxels", objects_.back().grid->surfaceVoxels());
      }
    }
    // Step 2: every copy's world box (clipped to where samples are taken) in a BVH, so a
    // sample asks only the copies whose boxes hold it.
    std::vector<Aabb> boxes;
    for (const Instance& instance : scene.instances()) {
      const ObjectGrid& object = objects_[instance.object];
      const dmat4 objectFromWorld = glm::inverse(instance.worldFromObject);
      const Aabb local = object.object->solid.kind == Solid::Kind::none
                             ? object.grid->bounds()
                             : solidBounds(object.object->solid, object.heightFieldTop, transformed(bounds_, objectFromWorld).lo.y);
      copies_.push_back({objectFromWorld, instance.object, instance.firstTriangle});
      boxes.push_back(intersection(transformed(local, instance.worldFromObject), bounds_));
    }
    copyBoxes_ = boxes;
    copyBvh_ = Bvh(boxes);
  }

  // history: hsr why's events at this pixel (every sample, and the triangle named), or
  // null (renderer/steps/why.hpp).
  Hit trace(const PixelRay& pixel, Counters& counters, std::vector<PixelEvent>* history = nullptr) const {
    Hit nearest;
    const auto [first, last] = clipToBounds(pixel);
    if (first > last) return nearest;
    // Step 3: samples at tNear + k * step (in world units along the ray): anchored at
    // the near plane, started at the first one inside the march box.
    const double stepT = step_ / glm::length(pixel.ray.direction);
    double k = std::max(0.0, std::ceil((first - pixel.tNear) / stepT));
    bool previousTested = false;  // was the sample before this one taken (and found outside)?
    for (;; ++k, previousTested = true) {
      const double t = pixel.tNear + k * stepT;
      if (t > last) return nearest;
      ++counters.samples;
      const dvec3 point = pixel.at(t);
      // Step 4: every copy holding the sample is a candidate; refinement finds where the
      // ray entered each, and the nearest entry wins (the lower copy on a tie).
      std::uint32_t entered = 0;
      double entry = 0;
      bool found = false;
      forEachCopyHolding(point, [&](std::uint32_t copy) {
        ++counters.insideTests;
        if (!inside(copy, point)) return;
        const double surface = previousTested ? refine(copy, pixel, t - stepT, t, counters) : t;
        if (!found || surface < entry || (surface == entry && copy < entered)) entered = copy, entry = surface, found = true;
      });
      if (history) [[unlikely]] witnessSample(k, t, found, entry, pixel, *history);
      if (!found) continue;
      // Step 5: name the entered object's triangle nearest to the point found (a search
      // that grows with how deep inside the point is: refinement makes it cheaper).
      const Copy& copy = copies_[entered];
      const ObjectGrid& object = objects_[copy.object];
      const dvec3 local = dvec3(copy.objectFromWorld * dvec4(pixel.at(entry), 1.0));
      nearest.id = copy.firstTriangle + object.grid->nearestTriangle(*object.object->mesh, local, counters.voxelsSearched) + 1;
      nearest.t = entry;
      if (history) [[unlikely]]
        history->push_back({nearest.id, "named: the triangle of that object nearest to where the ray entered it",
                            "searched in the object's occupancy grid", pixel.distance(entry), true, {}});
      return nearest;
    }
  }

 private:
  struct ObjectGrid {
    const SceneObject* object;
    std::unique_ptr<OccupancyGrid> grid;
    double heightFieldTop;
  };
  struct Copy {
    dmat4 objectFromWorld;
    std::uint32_t object, firstTriangle;
  };

  // hsr why: a sample at parameter t, outside every copy, or inside one, which the ray
  // entered at parameter `entry` (refined, or the sample itself).
  void witnessSample(double k, double t, bool found, double entry, const PixelRay& pixel,
                     std::vector<PixelEvent>& history) const {
    char detail[160] = "no object's inside test holds there";
    if (found)
      std::snprintf(detail, sizeof detail, "the ray entered the object at distance %.9g%s", pixel.distance(entry),
                    entry == t ? " (the sample's: not refined)" : " (refined between this sample and the last)");
    history.push_back({conventions::kBackgroundId, found ? "inside an object: the march stops" : "outside every object: the march goes on",
                       detail, pixel.distance(t), false, "sample " + std::to_string(static_cast<long long>(k))});
  }

  // The ray's parameters inside the march box and between the near and far planes.
  std::pair<double, double> clipToBounds(const PixelRay& pixel) const {
    double first = pixel.tNear, last = pixel.tFar;
    for (int axis = 0; axis < 3; ++axis) {
      const double origin = pixel.ray.origin[axis], direction = pixel.ray.direction[axis];
      if (direction == 0) {
        if (origin < bounds_.lo[axis] || origin > bounds_.hi[axis]) return {1, 0};
        continue;
      }
      double enter = (bounds_.lo[axis] - origin) / direction, leave = (bounds_.hi[axis] - origin) / direction;
      if (enter > leave) std::swap(enter, leave);
      first = std::max(first, enter);
      last = std::min(last, leave);
    }
    return {first, last};
  }

  template <typename Visit>
  void forEachCopyHolding(const dvec3& point, Visit&& visit) const {
    const std::vector<BvhNode>& nodes = copyBvh_.nodes();
    const auto holds = [&](const BvhNode& node) {
      for (int axis = 0; axis < 3; ++axis)
        if (point[axis] < node.bounds[0][axis] || point[axis] > node.bounds[1][axis]) return false;
      return true;
    };
    std::array<std::uint32_t, Bvh::kMaxDepth + 1> stack;
    int size = 0;
    if (!copyBvh_.empty() && holds(nodes[0])) stack[size++] = 0;
    while (size > 0) {
      const BvhNode& node = nodes[stack[--size]];
      if (!node.leaf()) {
        for (const std::uint32_t child : {node.index, node.index + 1})
          if (holds(nodes[child])) stack[size++] = child;
        continue;
      }
      for (std::uint32_t slot = node.index; slot < node.index + node.count; ++slot) {
        const std::uint32_t copy = copyBvh_.order()[slot];
        const Aabb& box = copyBoxes_[copy];
        if (glm::all(glm::greaterThanEqual(point, box.lo)) && glm::all(glm::lessThanEqual(point, box.hi))) visit(copy);
      }
    }
  }

  bool inside(std::uint32_t copyIndex, const dvec3& world) const {
    const Copy& copy = copies_[copyIndex];
    const ObjectGrid& object = objects_[copy.object];
    const dvec3 local = dvec3(copy.objectFromWorld * dvec4(world, 1.0));
    if (object.object->solid.kind == Solid::Kind::none) return object.grid->occupied(local);
    return insideSolid(object.object->solid, local, object.heightFieldTop);
  }

  // Bisection between a parameter known outside the copy and one known inside it: the
  // inside end after `refine_` halvings (the classic march, refine 0, reports the sample).
  double refine(std::uint32_t copy, const PixelRay& pixel, double outside, double insideT, Counters& counters) const {
    for (int i = 0; i < refine_; ++i) {
      ++counters.refinementSteps;
      const double middle = 0.5 * (outside + insideT);
      (inside(copy, pixel.at(middle)) ? insideT : outside) = middle;
    }
    return insideT;
  }

  double step_;
  int refine_;
  Aabb bounds_;
  std::vector<ObjectGrid> objects_;
  std::vector<Copy> copies_;
  std::vector<Aabb> copyBoxes_;
  Bvh copyBvh_;
};

}  // namespace

double marchStepLength(const PreparedScene& scene, const KnobNumber& step) {
  if (!step.percent) return step.value;
  const Aabb bounds = sceneBounds(scene);
  const double diagonal = bounds.empty() ? 0.0 : glm::length(bounds.hi - bounds.lo);
  // A scene of one point has no size; any positive step serves.
  return diagonal > 0 ? diagonal * step.value / 100 : step.value / 100;
}

double marchSamplesPerRay(const PreparedScene& scene, const KnobNumber& step) {
  const double length = marchStepLength(scene, step);
  const Aabb bounds = marchBounds(scene, length);
  return bounds.empty() ? 0.0 : glm::length(bounds.hi - bounds.lo) / length + 1;
}

void march(const PreparedScene& scene, const Knobs& knobs, const CameraTransform& camera, int threads, Frame& frame,
           Stats& stats, const Recording* recording, PixelWitness* why) {
  const Marcher marcher(scene, knobs, stats);
  PhaseTimer timer(stats, "ray casting");
  const auto counters = castRays(marcher, camera, threads, frame, recording, why);
  stats.add("march samples", counters.samples);
  stats.add("inside tests", counters.insideTests);
  stats.add("refinement steps", counters.refinementSteps);
  stats.add("nearest-triangle voxels searched", counters.voxelsSearched);
}

}  // namespace hsr::ray_casting
