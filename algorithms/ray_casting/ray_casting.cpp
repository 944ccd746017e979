// The exact variants, naive and bvh: the same watertight ray-triangle test, run against
// every triangle or against the triangles of the BVH leaves a ray reaches.
#include "algorithms/ray_casting/ray_casting.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

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

  // history: hsr why's events at this pixel, or null (renderer/steps/why.hpp).
  Hit trace(const PixelRay& pixel, Counters& counters, std::vector<PixelEvent>* history = nullptr) const {
    const WatertightRay<double> ray(pixel.ray, pixel.inverseDirection);
    Hit nearest{conventions::kBackgroundId, pixel.tFar};
    for (const PackedTriangle& triangle : triangles_) offer(ray, triangle, pixel, nearest, history);
    counters.triangleTests += static_cast<std::int64_t>(triangles_.size());
    return nearest;
  }

 private:
  const std::vector<PackedTriangle>& triangles_;
};

// hsr why's events for the bvh variant's traversal (defined below the tracer): kept out
// of its loop, cold, so that the loop without a history is the textbook's alone.
constexpr double kMiss = std::numeric_limits<double>::infinity();
[[gnu::cold]] void witnessMissedScene(std::vector<PixelEvent>& history);
[[gnu::cold]] void witnessLeaf(std::uint32_t node, std::uint32_t triangles, double entry, const PixelRay& pixel,
                               std::vector<PixelEvent>& history);
[[gnu::cold]] void witnessChildren(std::uint32_t node, double entry, std::uint32_t nearer, double nearerEntry, std::uint32_t farther,
                                   double fartherEntry, const PixelRay& pixel, std::vector<PixelEvent>& history);
[[gnu::cold]] void witnessDropped(std::uint32_t node, double entry, const Hit& nearest, const PixelRay& pixel,
                                  std::vector<PixelEvent>& history);

// Variant bvh: front-to-back traversal of the scene's triangle BVH.
class BvhTracer {
 public:
  using Counters = TraversalCounters;

  BvhTracer(const PreparedScene& scene, Stats& stats) : bvh_(scene.triangleBvh(stats)), triangles_(scene.leafTriangles(stats)) {}

  // history: hsr why's events at this pixel (every node entered or dropped, every
  // triangle tested), or null (renderer/steps/why.hpp). The traversal is compiled twice,
  // with and without a history, so that without one it is the textbook's loop alone.
  Hit trace(const PixelRay& pixel, Counters& counters, std::vector<PixelEvent>* history = nullptr) const {
    return history ? traverse<true>(pixel, counters, history) : traverse<false>(pixel, counters, nullptr);
  }

 private:
  template <bool kWitnessed>
  Hit traverse(const PixelRay& pixel, Counters& counters, std::vector<PixelEvent>* history) const {
    Hit nearest{conventions::kBackgroundId, pixel.tFar};
    if (bvh_.empty()) return nearest;
    // BEGIN SOLUTION
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
    if (current.entry == kMiss) {
      if constexpr (kWitnessed) witnessMissedScene(*history);
      return nearest;
    }
    while (true) {
      const BvhNode& node = nodes[current.node];
      ++counters.nodesVisited;
      if (node.leaf()) {
        if constexpr (kWitnessed) witnessLeaf(current.node, node.count, current.entry, pixel, *history);
        counters.triangleTests += node.count;
        for (std::uint32_t slot = node.index; slot < node.index + node.count; ++slot)
          offer(ray, triangles_[slot], pixel, nearest, kWitnessed ? history : nullptr);
      } else {
        // Ordered traversal: go on with the nearer child, keep the farther for later.
        const auto [entry0, entry1] = boxes.childEntries(&nodes[node.index], reach());
        Pending first{node.index, entry0};
        Pending second{node.index + 1, entry1};
        if (second.entry < first.entry) std::swap(first, second);
        if constexpr (kWitnessed)
          witnessChildren(current.node, current.entry, first.node, first.entry, second.node, second.entry, pixel, *history);
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
        if constexpr (kWitnessed)
          if (current.entry > reach()) witnessDropped(current.node, current.entry, nearest, pixel, *history);
      } while (current.entry > reach());
    }
    // SKELETON
    // // Exercise 3: the nearest hit along the pixel's ray, front to back through the BVH
    // // (bvh_.nodes(), the root at 0). RayBoxTest boxes(pixel.ray.origin,
    // // pixel.ray.direction, pixel.inverseDirection) gives where the ray enters a node's
    // // box before a reach (boxes.entry(node, reach), kMiss if not), and both children's
    // // (boxes.childEntries(&nodes[node.index], reach)); the reach is reachOf(nearest),
    // // the nearest hit so far. A leaf (node.leaf()) holds triangles_[node.index] to
    // // triangles_[node.index + node.count - 1]: offer each to the ray,
    // // offer(WatertightRay<double>(pixel.ray, pixel.inverseDirection), triangle, pixel,
    // // nearest, nullptr). Go on with the nearer child, keep the farther on a stack, and
    // // pop only nodes that start before the reach; count counters.nodesVisited and
    // // counters.triangleTests. Why may a popped node be dropped? (With a history, hsr
    // // why's events: witnessLeaf, witnessChildren, witnessDropped, witnessMissedScene,
    // // as the comments above them say; optional.)
    // (void)counters, (void)history;
    // (void)witnessLeaf, (void)witnessChildren, (void)witnessDropped, (void)witnessMissedScene;
    // return nearest;
    // END SOLUTION
  }

  const Bvh& bvh_;
  const std::vector<PackedTriangle>& triangles_;
};

// hsr why's words for a parameter along the ray: its distance along the view axis.
std::string where(double t, const PixelRay& pixel) {
  char text[64];
  std::snprintf(text, sizeof text, "distance %.9g", std::max(pixel.distance(t), pixel.distance(pixel.tNear)));
  return text;
}

void witnessNode(std::uint32_t node, std::string outcome, std::string detail, std::vector<PixelEvent>& history) {
  history.push_back({conventions::kBackgroundId, std::move(outcome), std::move(detail), std::numeric_limits<double>::quiet_NaN(), false,
                     "BVH node " + std::to_string(node)});
}

void witnessMissedScene(std::vector<PixelEvent>& history) {
  witnessNode(0, "missed: the ray does not enter the scene's box", "", history);
}

void witnessLeaf(std::uint32_t node, std::uint32_t triangles, double entry, const PixelRay& pixel, std::vector<PixelEvent>& history) {
  witnessNode(node, "a leaf: its " + std::to_string(triangles) + (triangles == 1 ? " triangle" : " triangles") + " tested",
              "its box begins at " + where(entry, pixel), history);
}

void witnessChildren(std::uint32_t node, double entry, std::uint32_t nearer, double nearerEntry, std::uint32_t farther,
                     double fartherEntry, const PixelRay& pixel, std::vector<PixelEvent>& history) {
  const auto child = [&](std::uint32_t which, double whichEntry) {
    return "node " + std::to_string(which) +
           (whichEntry == kMiss ? " missed (or begins beyond the nearest hit)" : " entered at " + where(whichEntry, pixel));
  };
  // What the traversal decides at an inner node it entered: the outcome names it first, so
  // that a question about the node (the browser edition's quiz) asks which of the three.
  const std::string outcome = nearerEntry == kMiss    ? "both children missed"
                              : fartherEntry == kMiss ? "one child to go on with"
                                                      : "the nearer child first, the farther stacked";
  witnessNode(node, outcome, "its box begins at " + where(entry, pixel) + "; " + child(nearer, nearerEntry) + ", " + child(farther, fartherEntry),
              history);
}

void witnessDropped(std::uint32_t node, double entry, const Hit& nearest, const PixelRay& pixel, std::vector<PixelEvent>& history) {
  witnessNode(node, "dropped (early exit): its box begins beyond the nearest hit",
              "its box begins at " + where(entry, pixel) + "; the nearest hit is " +
                  (nearest.id == conventions::kBackgroundId ? "none yet" : "at " + where(nearest.t, pixel)),
              history);
}

}  // namespace

void witnessOffer(const WatertightRay<double>& ray, const PackedTriangle& triangle, const PixelRay& pixel, const Hit& nearest,
                  bool met, double t, bool nearer, std::vector<PixelEvent>& history) {
  // The numbers the test decided by: the edge functions at the ray (step 4), and where
  // along the ray it meets the triangle's plane (step 5).
  const ScaledBarycentrics<double> s = ray.barycentrics(triangle.a, triangle.b, triangle.c);
  char edges[160];
  std::snprintf(edges, sizeof edges, "edge functions %.6g, %.6g, %.6g", s.u, s.v, s.w);
  const bool outside = (s.u < 0 || s.v < 0 || s.w < 0) && (s.u > 0 || s.v > 0 || s.w > 0);
  const double det = s.u + s.v + s.w;
  double planeT = std::numeric_limits<double>::quiet_NaN();
  if (!outside && det != 0) ray.hitParameter(s, det, planeT);
  const double distance = std::isnan(planeT) ? planeT : pixel.distance(planeT);
  std::string outcome;
  if (outside) outcome = "missed: the ray passes outside an edge";
  else if (det == 0) outcome = "missed: the ray lies in its plane (edge-on)";
  else if (!met && planeT < pixel.tNear) outcome = "missed: met before the near plane";
  else if (!met && nearest.id == conventions::kBackgroundId) outcome = "missed: met beyond the far plane";
  else if (!met) outcome = "met, but beyond the nearest hit so far";
  else if (nearer && nearest.id != conventions::kBackgroundId && t == nearest.t) outcome = "nearest: a tie at the same distance, the lower triangle wins";
  else if (nearer) outcome = "nearest so far";
  else outcome = "met at the same distance as the nearest so far: a tie, the lower triangle keeps it";
  const std::string signs = outside ? " (of both signs)" : det == 0 ? " (summing to 0)" : " (of one sign: inside)";
  history.push_back({triangle.id, std::move(outcome), std::string(edges) + signs, met ? pixel.distance(t) : distance, nearer, {}});
}

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
      const auto counters = castRays(tracer, camera, request.threads, frame, recording, request.why);
      stats.add("ray-triangle tests", counters.triangleTests);
      break;
    }
    case Variant::bvh: {
      const auto cast = [&](const auto& tracer) {
        PhaseTimer timer(stats, "ray casting");
        const TraversalCounters counters = castRays(tracer, camera, request.threads, frame, recording, request.why);
        stats.add("bvh nodes visited", counters.nodesVisited);
        stats.add("ray-triangle tests", counters.triangleTests);
      };
      // hsr why follows the textbook traversal, whatever the path (they give the same bits).
      if (knobs.path == Path::scalar || !cpuHasAvx2() || request.why) cast(BvhTracer(scene, stats));
      else if (knobs.path == Path::packet) cast(PacketTracer(scene, stats, request.threads));
      else cast(WideBvhTracer(scene, stats, request.threads));
      break;
    }
    case Variant::march:
      march(scene, knobs, camera, request.threads, frame, stats, recording, request.why);
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
  entry.answersWhy = true;
  return entry;
}

}  // namespace hsr::ray_casting
