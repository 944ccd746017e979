// Frustum culling (frustum.hpp has the variants and why two of them are wrong).
#include "algorithms/culling/frustum.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "algorithms/culling/culling.hpp"

namespace hsr::culling::frustum {

ViewVolume::ViewVolume(const PreparedScene& scene, const CameraTransform& camera) : planes(camera.frustumPlanes()) {
  double magnitude = 0;
  for (const Instance& instance : scene.instances())
    magnitude = std::max({magnitude, glm::length(glm::abs(instance.box.lo)), glm::length(glm::abs(instance.box.hi))});
  for (const Plane& plane : planes) magnitude = std::max(magnitude, std::abs(plane.offset));
  slack = 0x1p-40 * 2 * magnitude;
}

// A box against one plane: outside when even its corner farthest along the normal is
// behind the plane (Akenine-Möller et al., Real-Time Rendering, "plane/box" by projected
// extent).
ViewVolume::Side ViewVolume::boxSide(int side, const dvec3& center, const dvec3& halfExtent) {
  ++planesTested;
  const Plane& plane = planes[std::size_t(side)];
  const double reach = glm::dot(halfExtent, glm::abs(plane.normal)), distance = plane.distance(center);
  if (distance < -(reach + slack)) return Side::outside;
  return distance > reach ? Side::inside : Side::crossing;
}

bool ViewVolume::sphereOutside(const dvec3& center, double radius, int* outsideOf) {
  for (int side = 0; side < 6; ++side) {
    ++planesTested;
    if (planes[std::size_t(side)].distance(center) < -(radius + slack)) {
      if (outsideOf) *outsideOf = side;
      return true;
    }
  }
  return false;
}

bool ViewVolume::boxMayBeInside(const dvec3& center, const dvec3& halfExtent, std::uint32_t& mask, int* outsideOf) {
  for (int side = 0; side < 6; ++side) {
    if (!(mask & (1u << side))) continue;
    const Side result = boxSide(side, center, halfExtent);
    if (result == Side::outside) {
      if (outsideOf) *outsideOf = side;
      return false;
    }
    if (result == Side::inside) mask &= ~(1u << side);
  }
  return true;
}

namespace {

// The planes by FrustumSide, as hsr why names them.
constexpr std::array<const char*, 6> kSideNames = {"left", "right", "bottom", "top", "near", "far"};

// hsr why: what a bound's test found, `bound` naming it ("its bounding sphere"): the
// plane it lies wholly outside, or none.
std::string boundFinding(const std::string& bound, bool mayBeInside, int outsideOf) {
  return bound + (mayBeInside ? " lies outside none of the view volume's planes (near a corner it may still miss the volume: the test is conservative)"
                              : " lies wholly outside the view volume's " + std::string(kSideNames[std::size_t(outsideOf)]) + " plane");
}

// The instances under a BVH node, for hsr why: each(instance) for every one of them.
template <typename Each>
void forEachInstanceUnder(const Bvh& bvh, std::uint32_t index, Each&& each) {
  const BvhNode& node = bvh.nodes()[index];
  if (node.leaf()) {
    for (std::uint32_t slot = node.index; slot < node.index + node.count; ++slot) each(bvh.order()[slot]);
    return;
  }
  forEachInstanceUnder(bvh, node.index, each);
  forEachInstanceUnder(bvh, node.index + 1, each);
}

// The hierarchical test: down the object BVH with plane masking. Marks the instances not
// proven outside; counts the objects tested in the leaves reached. With why: for hsr
// why's objects, the box (a node's above it, or its own) found wholly outside a plane, or
// that its own box lies outside none of the planes still open.
std::vector<std::uint8_t> traverseObjectBvh(const PreparedScene& scene, ViewVolume& volume, std::int64_t& objectsTested,
                                            Stats& stats, StageWitness* why) {
  const Bvh& bvh = scene.objectBvh(stats);
  std::vector<std::uint8_t> keep(scene.instances().size(), 0);
  struct Visit {
    std::uint32_t node, mask, depth;  // depth: the root's 0
  };
  std::vector<Visit> stack;
  if (!bvh.empty()) stack.push_back({0, ViewVolume::kAllPlanes, 0});
  std::int64_t visited = 0;
  while (!stack.empty()) {
    // (Not a structured binding: clang 14, the browser edition's, cannot capture one.)
    const Visit visit = stack.back();
    stack.pop_back();
    const std::uint32_t index = visit.node, depth = visit.depth;
    std::uint32_t mask = visit.mask;
    ++visited;
    const BvhNode& node = bvh.nodes()[index];
    const Aabb nodeBox = node.box();
    // The node's box (rounded outward from its contents) outside a plane: nothing
    // below it can be seen. Wholly inside a plane: nothing below it needs that plane.
    int outsideOf = -1;
    if (!volume.boxMayBeInside(nodeBox, mask, &outsideOf)) {
      if (why) [[unlikely]]
        forEachInstanceUnder(bvh, index, [&](std::uint32_t instance) {
          if (std::string* found = why->about(instance))
            *found = boundFinding("the box of a BVH node holding it (depth " + std::to_string(depth) + ")", false, outsideOf);
        });
      continue;
    }
    if (!node.leaf()) {
      stack.push_back({node.index + 1, mask, depth + 1});
      stack.push_back({node.index, mask, depth + 1});
      continue;
    }
    // A leaf's objects, each by its own (tighter) box against the planes still open.
    for (std::uint32_t slot = node.index; slot < node.index + node.count; ++slot) {
      const std::uint32_t instance = bvh.order()[slot];
      std::uint32_t objectMask = mask;
      ++objectsTested;
      const Aabb& box = scene.instances()[instance].box;
      keep[instance] = volume.boxMayBeInside(box, objectMask, &outsideOf);
      if (std::string* found = why ? why->about(instance) : nullptr) [[unlikely]]
        *found = boundFinding("its box, reached in a BVH leaf at depth " + std::to_string(depth) + ",", keep[instance] != 0, outsideOf);
    }
  }
  stats.add("frustum: bvh nodes visited", visited);
  return keep;
}

}  // namespace

VisibleSet cull(const PreparedScene& scene, const CameraTransform& camera, Variant variant, const VisibleSet& in,
                int threads, Stats& stats, StageWitness* why) {
  PhaseTimer timer(stats, "culling: frustum");
  ViewVolume volume(scene, camera);
  VisibleSet out;
  // Per object: each object that still has triangles in `in` is tested once. `outsideOf`:
  // the plane the test found it wholly outside, for hsr why.
  std::int64_t objectsTested = 0, objectsCulled = 0;
  int outsideOf = -1;
  const auto keepObjectsThat = [&](const char* bound, auto&& mayBeVisible) {
    return keepObjects(scene, in, [&](std::uint32_t instance) {
      const bool kept = mayBeVisible(scene.instances()[instance]);
      objectsCulled += !kept;
      if (std::string* found = why ? why->about(instance) : nullptr) [[unlikely]]
        *found = boundFinding(std::string("its ") + bound, kept, outsideOf);
      return kept;
    });
  };
  switch (variant) {
    case Variant::sphere:
      out = keepObjectsThat("bounding sphere", [&](const Instance& instance) {
        ++objectsTested;
        return !volume.sphereOutside(instance.sphereCenter, instance.sphereRadius, &outsideOf);
      });
      break;
    case Variant::aabb:
      out = keepObjectsThat("box", [&](const Instance& instance) {
        ++objectsTested;
        std::uint32_t mask = ViewVolume::kAllPlanes;
        return volume.boxMayBeInside(instance.box, mask, &outsideOf);
      });
      break;
    case Variant::bvh: {
      const std::vector<std::uint8_t> keep = traverseObjectBvh(scene, volume, objectsTested, stats, why);
      out = keepObjects(scene, in, [&](std::uint32_t instance) {
        objectsCulled += keep[instance] == 0;
        return keep[instance] != 0;
      });
      break;
    }
    case Variant::triangle:
    case Variant::anyVertex: {
      const std::vector<dvec3>& positions = scene.positions();
      const std::vector<Triangle>& triangles = scene.triangles();
      const std::array<Plane, 6>& planes = volume.planes;
      const double slack = volume.slack;
      out = keepTriangles(in, threads, [&] {
        return [&](std::uint32_t index) {
          const Triangle& t = triangles[index];
          const dvec3 corners[3] = {positions[t[0]], positions[t[1]], positions[t[2]]};
          std::string* const found = why ? why->aboutTriangle(index) : nullptr;
          if (variant == Variant::triangle) {
            // Outside only when all three corners are behind the same plane.
            const auto outside = std::find_if(planes.begin(), planes.end(), [&](const Plane& plane) {
              return std::all_of(corners, corners + 3, [&](const dvec3& p) { return plane.distance(p) < -slack; });
            });
            if (found) [[unlikely]]
              *found = outside == planes.end() ? "no plane of the view volume has all three of its corners outside it"
                                               : "all three of its corners lie outside the view volume's " +
                                                     std::string(kSideNames[std::size_t(outside - planes.begin())]) + " plane";
            return outside == planes.end();
          }
          // Any vertex inside: some corner in front of all six planes.
          const dvec3* inside = std::find_if(corners, corners + 3, [&](const dvec3& p) {
            return std::all_of(planes.begin(), planes.end(), [&](const Plane& plane) { return plane.distance(p) >= -slack; });
          });
          if (found) [[unlikely]]
            *found = inside != corners + 3 ? "its corner " + std::to_string(inside - corners + 1) + " lies inside all six planes"
                                           : "none of its corners lies inside all six planes (it may still cross the view volume: why this "
                                             "variant is wrong)";
          return inside != corners + 3;
        };
      });
      stats.add("frustum: triangles tested", static_cast<std::int64_t>(in.triangles.size()));
      stats.add("frustum: triangles culled", static_cast<std::int64_t>(in.triangles.size() - out.triangles.size()));
      return out;
    }
  }
  stats.add("frustum: objects tested", objectsTested);
  stats.add("frustum: objects culled", objectsCulled);
  stats.add("frustum: planes tested", volume.planesTested);
  stats.add("frustum: triangles culled", static_cast<std::int64_t>(in.triangles.size() - out.triangles.size()));
  return out;
}

StageEntry stage() {
  StageEntry entry = stageEntry("frustum", "drop objects or triangles wholly outside the view volume", knobTable());
  entry.mayDropVisible = [](const KnobValues& knobs) { return knobs.as<Knobs>().variant == Variant::anyVertex; };
  entry.run = [](const KnobValues& knobs, const StageInput& input) {
    return cull(input.scene, input.camera, knobs.as<Knobs>().variant, input.in, input.threads, input.stats, input.why);
  };
  return entry;
}

}  // namespace hsr::culling::frustum
