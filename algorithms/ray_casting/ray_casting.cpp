// The exact variants, naive and bvh: the same watertight ray-triangle test, run against
// every triangle or against the triangles of the BVH leaves a ray reaches.
#include "algorithms/ray_casting/ray_casting.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <optional>

#include "algorithms/ray_casting/cast.hpp"
#include "algorithms/ray_casting/fast_path.hpp"
#include "algorithms/ray_casting/march.hpp"
#include "algorithms/ray_casting/watertight.hpp"
#include "renderer/rays/bvh.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/simd.hpp"

namespace hsr::ray_casting {
namespace {

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
    const WatertightRay<double> ray(pixel.ray, pixel.inverseDirection);
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
  using Counters = TraversalCounters;

  BvhTracer(const PreparedScene& scene, Stats& stats) : bvh_(scene.triangleBvh(stats)), triangles_(scene.leafTriangles(stats)) {}

  Hit trace(const PixelRay& pixel, Counters& counters) const {
    Hit nearest{conventions::kBackgroundId, pixel.tFar};
    if (bvh_.empty()) return nearest;
    const RayBoxTest boxes(pixel.ray.origin, pixel.ray.direction, pixel.inverseDirection);
    const WatertightRay<double> ray(pixel.ray, pixel.inverseDirection);
    const std::vector<BvhNode>& nodes = bvh_.nodes();
    const auto reach = [&] { return reachOf(nearest); };

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
  // The tracers read the triangles in the BVH's leaf order: the BVH is built on first
  // use, on this render's threads.
  if (knobs.variant != Variant::march) scene.triangleBvh(stats, request.threads);
  switch (knobs.variant) {
    case Variant::naive: {
      const NaiveTracer tracer(scene, stats);
      PhaseTimer timer(stats, "ray casting");
      const auto counters = castRays(tracer, camera, request.threads, frame, recording);
      stats.add("ray-triangle tests", counters.triangleTests);
      break;
    }
    case Variant::bvh: {
      const auto cast = [&](const auto& tracer) {
        PhaseTimer timer(stats, "ray casting");
        const TraversalCounters counters = castRays(tracer, camera, request.threads, frame, recording);
        stats.add("bvh nodes visited", counters.nodesVisited);
        stats.add("ray-triangle tests", counters.triangleTests);
      };
      if (knobs.path == Path::scalar || !cpuHasAvx2()) cast(BvhTracer(scene, stats));
      else if (knobs.path == Path::packet) cast(PacketTracer(scene, stats, request.threads));
      else cast(WideBvhTracer(scene, stats, request.threads));
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
  entry.studyConfigurations = {{}, {{"path", "simd"}}, {{"path", "scalar"}}, {{"variant", "naive"}}, {{"variant", "march"}}, {{"variant", "march"}, {"refine", "6"}}};
  setRefusal(entry, refusal);
  setVisibility(entry, visibility);
  return entry;
}

}  // namespace hsr::ray_casting
