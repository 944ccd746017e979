// The exact variants, naive and bvh: the same watertight ray-triangle test, run against
// every triangle or against the triangles of the BVH leaves a ray reaches.
#include "algorithms/ray_casting/ray_casting.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <optional>

#include "algorithms/ray_casting/cast.hpp"
#include "algorithms/ray_casting/march.hpp"
#include "renderer/bvh.hpp"
#include "renderer/error.hpp"

namespace hsr::ray_casting {
namespace {

// The watertight ray-triangle test (Woop, Benthin and Wald 2013). Set up once per ray:
// a permutation and shear that map the ray onto the +z axis from the origin, so that
// the test of a triangle reduces to the signs of three 2D edge functions at (0, 0).
// An edge shared by two triangles gives them exactly opposite edge functions (the same
// products, subtracted the other way round), so a ray through the edge cannot slip
// between them: no cracks in a closed mesh, whatever the rounding.
class WatertightRay {
 public:
  // inverseDirection: 1 / ray.direction, per axis (the slab test needs it too).
  WatertightRay(const Ray& ray, const dvec3& inverseDirection) : origin_(ray.origin) {
    // Step 1: kz, the axis the direction is largest along; kx, ky the other two, swapped
    // when the ray runs down kz so the triangle's winding is kept.
    const dvec3 size = glm::abs(ray.direction);
    kz_ = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
    kx_ = (kz_ + 1) % 3;
    ky_ = (kx_ + 1) % 3;
    if (ray.direction[kz_] < 0) std::swap(kx_, ky_);
    // Step 2: the shear that takes the direction to (0, 0, 1).
    shearZ_ = inverseDirection[kz_];
    shearX_ = ray.direction[kx_] * shearZ_;
    shearY_ = ray.direction[ky_] * shearZ_;
  }

  // The hit parameter when the ray meets the triangle in [tMin, tMax].
  bool hit(const dvec3& a, const dvec3& b, const dvec3& c, double tMin, double tMax, double& t) const {
    // Step 3: the vertices relative to the origin, sheared in the xy plane.
    const dvec3 A = a - origin_, B = b - origin_, C = c - origin_;
    const double ax = A[kx_] - shearX_ * A[kz_], ay = A[ky_] - shearY_ * A[kz_];
    const double bx = B[kx_] - shearX_ * B[kz_], by = B[ky_] - shearY_ * B[kz_];
    const double cx = C[kx_] - shearX_ * C[kz_], cy = C[ky_] - shearY_ * C[kz_];
    // Step 4: the scaled barycentrics. The ray passes inside (or on an edge) when they
    // share a sign; 0 counts as either, so an edge belongs to both its triangles.
    const double u = cx * by - cy * bx;
    const double v = ax * cy - ay * cx;
    const double w = bx * ay - by * ax;
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
    const double det = u + v + w;
    if (det == 0) return false;  // the ray lies in the triangle's plane: it sees the triangle edge-on
    // Step 5: the hit distance, interpolated from the vertices' sheared z.
    t = (u * (shearZ_ * A[kz_]) + v * (shearZ_ * B[kz_]) + w * (shearZ_ * C[kz_])) / det;
    return t >= tMin && t <= tMax;
  }

 private:
  dvec3 origin_;
  int kx_, ky_, kz_;
  double shearX_, shearY_, shearZ_;
};

using PackedTriangle = PreparedScene::LeafTriangle;

// Offers a triangle to the nearest hit so far. The nearest wins; at exactly equal t the
// lower id does, so the answer does not depend on the order triangles are offered in
// (which is why naive and bvh give identical images).
// `nearest` starts as {background, tFar}: the first hit up to the far plane is taken.
void offer(const WatertightRay& ray, const PackedTriangle& triangle, const PixelRay& pixel, Hit& nearest) {
  double t;
  if (!ray.hit(triangle.a, triangle.b, triangle.c, pixel.tNear, nearest.t, t)) return;
  if (nearest.id == conventions::kBackgroundId || t < nearest.t || triangle.id < nearest.id) nearest = {triangle.id, t};
}

// Variant naive: every triangle, in id order.
class NaiveTracer {
 public:
  struct Counters {
    std::int64_t triangleTests = 0;
    Counters& operator+=(const Counters& other) {
      triangleTests += other.triangleTests;
      return *this;
    }
    static constexpr const char* kCostUnit = "ray-triangle tests per ray";
    double cost() const { return double(triangleTests); }
  };

  // The BVH's leaf order is as good an order as any: the answer does not depend on it.
  NaiveTracer(const PreparedScene& scene, Stats& stats) : triangles_(scene.leafTriangles(stats)) {}

  Hit trace(const PixelRay& pixel, Counters& counters) const {
    const WatertightRay ray(pixel.ray, inverseOf(pixel.ray.direction));
    Hit nearest{conventions::kBackgroundId, pixel.tFar};
    for (const PackedTriangle& triangle : triangles_) offer(ray, triangle, pixel, nearest);
    counters.triangleTests += static_cast<std::int64_t>(triangles_.size());
    return nearest;
  }

 private:
  const std::vector<PackedTriangle>& triangles_;
};

// Variant bvh: front-to-back traversal of the scene's triangle BVH.
class BvhTracer {
 public:
  struct Counters {
    std::int64_t nodesVisited = 0, triangleTests = 0;
    Counters& operator+=(const Counters& other) {
      nodesVisited += other.nodesVisited;
      triangleTests += other.triangleTests;
      return *this;
    }
    static constexpr const char* kCostUnit = "BVH nodes visited per ray";
    double cost() const { return double(nodesVisited); }
  };

  BvhTracer(const PreparedScene& scene, Stats& stats) : bvh_(scene.triangleBvh(stats)), triangles_(scene.leafTriangles(stats)) {}

  Hit trace(const PixelRay& pixel, Counters& counters) const {
    Hit nearest{conventions::kBackgroundId, pixel.tFar};
    if (bvh_.empty()) return nearest;
    const RayBoxTest boxes(pixel.ray.origin, pixel.ray.direction);
    const WatertightRay ray(pixel.ray, boxes.inverseDirection);
    const std::vector<BvhNode>& nodes = bvh_.nodes();
    // A node is worth entering only if its box starts before the nearest hit so far.
    // The box's entry and a triangle's t are each rounded, so a triangle lying in its
    // box's face may come out a few ulps before the entry: the reach is widened by far
    // more than that (2^-32 of it), so bvh skips nothing naive would take, ties included.
    constexpr double kWiden = 1 + 0x1p-32;
    const auto reach = [&] { return nearest.t * kWiden; };

    struct Pending {
      std::uint32_t node;
      double entry;
    };
    std::array<Pending, Bvh::kMaxDepth + 1> stack;
    int size = 0;
    Pending current{0, boxes.entry(nodes[0], reach())};
    if (current.entry == kMiss) return nearest;
    while (true) {
      const BvhNode& node = nodes[current.node];
      ++counters.nodesVisited;
      if (node.leaf()) {
        counters.triangleTests += node.count;
        for (std::uint32_t slot = node.index; slot < node.index + node.count; ++slot)
          offer(ray, triangles_[slot], pixel, nearest);
      } else {
        // Ordered traversal: go on with the nearer child, keep the farther for later.
        const auto [entry0, entry1] = boxes.childEntries(&nodes[node.index], reach());
        Pending first{node.index, entry0};
        Pending second{node.index + 1, entry1};
        if (second.entry < first.entry) std::swap(first, second);
        if (first.entry != kMiss) {
          if (second.entry != kMiss) stack[size++] = second;
          current = first;
          continue;
        }
      }
      // Early exit: pop until a node that still starts before the nearest hit.
      do {
        if (size == 0) return nearest;
        current = stack[--size];
      } while (current.entry > reach());
    }
  }

 private:
  static constexpr double kMiss = std::numeric_limits<double>::infinity();
  const Bvh& bvh_;
  const std::vector<PackedTriangle>& triangles_;
};

}  // namespace

std::string refusal(const PreparedScene& scene, const Knobs& knobs) {
  // The work a run would do at most, in its own unit: ray-triangle tests or samples.
  const double pixels = double(scene.width()) * double(scene.height());
  const bool naive = knobs.variant == Variant::naive;
  if (!naive && knobs.variant != Variant::march) return "";
  const double perRay = naive ? double(scene.triangleCount()) : marchSamplesPerRay(scene, knobs.step);
  if (pixels * perRay <= knobs.budget) return "";
  char text[320];
  std::snprintf(text, sizeof text,
                "%s ray casting would run %d x %d pixels x %.4g %s = %.3g %s, over its budget of %.3g (raise it with "
                "--knob budget=N, or use a smaller --size%s)",
                naive ? "naive" : "march", scene.width(), scene.height(), perRay,
                naive ? "triangles" : "samples per ray", pixels * perRay, naive ? "ray-triangle tests" : "samples",
                knobs.budget, naive ? "" : " or a longer --knob step");
  return text;
}

void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility) {
  const PreparedScene& scene = request.scene;
  if (const std::string reason = refusal(scene, knobs); !reason.empty()) throw InputError(reason);
  HSR_CHECK(!request.triangles && "ray casting traces every triangle");
  Frame& frame = visibility.frame;
  const CameraTransform& camera = request.view;
  Stats& stats = request.stats;
  stats.add("primary rays", static_cast<std::int64_t>(frame.pixelCount()));
  std::optional<Recording> steps;
  if (request.steps) steps.emplace(Recording{*request.steps, scene});
  const Recording* recording = steps ? &*steps : nullptr;
  switch (knobs.variant) {
    case Variant::naive: {
      const NaiveTracer tracer(scene, stats);
      PhaseTimer timer(stats, "ray casting");
      const auto counters = castRays(tracer, camera, request.threads, frame, recording);
      stats.add("ray-triangle tests", counters.triangleTests);
      break;
    }
    case Variant::bvh: {
      const BvhTracer tracer(scene, stats);
      PhaseTimer timer(stats, "ray casting");
      const auto counters = castRays(tracer, camera, request.threads, frame, recording);
      stats.add("bvh nodes visited", counters.nodesVisited);
      stats.add("ray-triangle tests", counters.triangleTests);
      break;
    }
    case Variant::march:
      march(scene, knobs, camera, request.threads, frame, stats, recording);
      break;
  }
}

AlgorithmEntry entry() {
  AlgorithmEntry entry;
  entry.name = "ray_casting";
  entry.summary = "a ray per pixel center, nearest surface wins (Appel 1968): through a BVH, naive, or marched in steps";
  setKnobs(entry, knobTable());
  entry.keyCounters = {"primary rays", "bvh nodes visited", "ray-triangle tests", "march samples", "inside tests",
                       "nearest-triangle voxels searched"};
  entry.studyConfigurations = {{}, {{"variant", "naive"}}, {{"variant", "march"}}, {{"variant", "march"}, {"refine", "6"}}};
  setRefusal(entry, refusal);
  setVisibility(entry, visibility);
  return entry;
}

}  // namespace hsr::ray_casting
