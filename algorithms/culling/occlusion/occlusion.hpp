// Occlusion culling: drop the objects hidden behind nearer ones before they are drawn,
// by testing each object's box against a small depth map (depth_map.hpp).
//
//   depth-map        the software occluder depth map of the published CPU methods:
//                    choose occluders, rasterize them front to back into the map (an
//                    occluder already hidden by the nearer ones is skipped: it could not
//                    change the map), then test every object's box against it.
//   previous-frame   no occluders: the map is the previous frame's full-resolution depth,
//                    reduced with max, and an object is tested where it was in that frame.
//                    An object that comes into view behind what was there appears one
//                    frame late; the studies count those frames.
//   queries          no map: hardware occlusion queries on a simulated GPU, over a
//                    hierarchy of the objects, by one of four strategies (queries.hpp):
//                    stop-and-wait, delayed, chc (Bittner et al. 2004), chcpp (Mattausch
//                    et al. 2008).
//
// Knobs:
//   map-width, map-height  the map's resolution (the view's aspect need not match: its
//                          texels are then not square)
//   raster                 conservative (never culls a visible object) or center
//                          (depth_map.hpp)
//   pyramid                on: test each box on the hierarchical-Z level where its
//                          rectangle spans at most 2x2 texels; off: every texel it covers
//   occluders              all objects, or a fraction of them: the largest by world volume,
//                          or by solid angle from the eye (the nearest large ones)
//   fraction               that fraction, of the objects still in the set
//   shape                  mesh: an occluder's own triangles; box: its inner box, a closed
//                          box wholly inside it (12 triangles, or one polygon under the
//                          conservative rule), where the object has one (a box solid)
//   strategy ... tight-bounds   the query methods' knobs (queries.hpp)
#pragma once

#include <array>
#include <optional>

#include "algorithms/culling/culling.hpp"
#include "algorithms/culling/occlusion/depth_map.hpp"
#include "algorithms/culling/occlusion/hierarchy.hpp"
#include "algorithms/culling/occlusion/simulated_gpu.hpp"

namespace hsr::culling::occlusion {

enum class Method { depthMap, previousFrame, queries };
enum class Occluders { all, volume, solidAngle };
enum class QueryStrategy { stopAndWait, delayed, chc, chcpp };

struct Knobs {
  Method method = Method::depthMap;
  Rule rule = Rule::conservative;
  int mapWidth = 256, mapHeight = 128;
  bool pyramid = false;
  Occluders occluders = Occluders::all;
  KnobNumber fraction{10, true};  // percent of the objects, when occluders is not all
  // Run only when the objects' boxes cover the view at least this many times over
  // (estimatedDepthComplexity); 0: always.
  double minDepthComplexity = 0;
  // The query methods (queries.hpp).
  QueryStrategy strategy = QueryStrategy::chc;
  int threshold = 0;  // visible when more fragments than this pass
  int latency = 1;
  LatencyUnit latencyIn = LatencyUnit::frames;
  HierarchyKind hierarchy = HierarchyKind::bvh;
  int batch = 50;          // chcpp: previously hidden nodes queried together
  int assumeVisible = 8;   // chcpp: frames a visible leaf goes unqueried
  bool multiqueries = true;  // chcpp
  bool tightBounds = true;   // chcpp
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table =
      KnobTable<Knobs>()
          .variants(&Knobs::method,
                    {{Method::depthMap, "depth-map", "occluders rasterized into a small depth map, nearest first"},
                     {Method::previousFrame, "previous-frame",
                      "the previous frame's depth, reduced to the map: objects coming into view appear a frame late"},
                     {Method::queries, "queries",
                      "occlusion queries on a simulated GPU over a hierarchy of the objects: stop-and-wait, delayed, chc or chcpp"}},
                    "where the depth map comes from, or queries instead of a map")
          .number("map-width", &Knobs::mapWidth, {1, 4096}, {"64", "128", "512"}, "the depth map's width in texels")
          .onlyFor({"depth-map", "previous-frame"})
          .number("map-height", &Knobs::mapHeight, {1, 4096}, {"64", "256"}, "the depth map's height in texels")
          .onlyFor({"depth-map", "previous-frame"})
          .choice("raster", &Knobs::rule, {{Rule::conservative, "conservative"}, {Rule::center, "center"}},
                  "conservative: a texel only where one occluder covers it entirely, at its farthest depth there; center: the "
                  "rasterizer's pixel-center rule (can cull objects seen through gaps)")
          .onlyFor({"depth-map"})
          .onOff("pyramid", &Knobs::pyramid, "on: each box tested on the hierarchical-Z level where it spans at most 2x2 texels")
          .onlyFor({"depth-map", "previous-frame"})
          .choice("occluders", &Knobs::occluders,
                  {{Occluders::all, "all"}, {Occluders::volume, "volume"}, {Occluders::solidAngle, "solid-angle"}},
                  "which objects are drawn into the map: all, or the largest by world volume or by solid angle")
          .onlyFor({"depth-map"})
          .number("fraction", &Knobs::fraction, {0.01, 100, false, true}, {"5%", "20%"},
                  "the share of the objects drawn as occluders when occluders is not all, in percent")
          .onlyFor({"depth-map"})
          .number("min-depth-complexity", &Knobs::minDepthComplexity, {0, 1000}, {"1.5", "2", "4"},
                  "run only when the objects' boxes cover the view at least this many times over (estimated from their "
                  "footprints on the map), else keep everything; 0: always")
          .onlyFor({"depth-map", "previous-frame"})
          .choice("strategy", &Knobs::strategy,
                  {{QueryStrategy::stopAndWait, "stop-and-wait"}, {QueryStrategy::delayed, "delayed"}, {QueryStrategy::chc, "chc"},
                   {QueryStrategy::chcpp, "chcpp"}},
                  "stop-and-wait: down the hierarchy, waiting for each answer; delayed: every leaf drawn by its newest answer, "
                  "never waiting (objects coming into view appear late); chc: coherent hierarchical culling, last frame's "
                  "visible leaves drawn while queries are in flight; chcpp: CHC++, with batched queries and multiqueries")
          .onlyFor({"queries"})
          .bare()
          .number("threshold", &Knobs::threshold, {0, 1e5}, {"10", "100"},
                  "a node is visible when more than this many of its box's fragments pass (0: exact)")
          .onlyFor({"queries"})
          .number("latency", &Knobs::latency, {0, 1000}, {"0", "2", "8"},
                  "how late answers come back: after this many frames, or queries (latency-in)")
          .onlyFor({"queries"})
          .choice("latency-in", &Knobs::latencyIn, {{LatencyUnit::frames, "frames"}, {LatencyUnit::queries, "queries"}},
                  "frames: an answer is in that many frames after its query; queries: once that many more queries were issued")
          .onlyFor({"queries"})
          .choice("hierarchy", &Knobs::hierarchy, {{HierarchyKind::bvh, "bvh"}, {HierarchyKind::kd, "kd"}},
                  "the hierarchy queried: the object BVH, or a k-d tree of the objects")
          .onlyFor({"queries"})
          .number("batch", &Knobs::batch, {1, 10000}, {"1", "10", "200"},
                  "chcpp: previously hidden nodes gathered before their queries are issued together")
          .onlyFor({"queries"})
          .number("assume-visible", &Knobs::assumeVisible, {1, 1000}, {"1", "4", "16"},
                  "chcpp: frames a visible leaf is drawn without a query (the first wait drawn at random, to spread them)")
          .onlyFor({"queries"})
          .onOff("multiqueries", &Knobs::multiqueries,
                 "chcpp: on: nodes likely to stay hidden share one query (re-asked one by one if it comes back visible)")
          .onlyFor({"queries"})
          .onOff("tight-bounds", &Knobs::tightBounds,
                 "chcpp: on: a node queried by its children's or objects' boxes where they cover less than its own")
          .onlyFor({"queries"});
  return table;
}

// The stage's entry in culling::stages().
StageEntry stage();

// The object copy's box in world space (corners as cornersOf orders them, moved by its
// placement) when the object is a box solid, whose mesh is exactly that box.
std::optional<std::array<dvec3, 8>> boxOfSolid(const PreparedScene& scene, const Instance& instance);

// Draws one occluder, its solid box or its triangles, into the rasterizer's map.
void drawOccluder(const PreparedScene& scene, const Instance& instance, OccluderRasterizer& rasterizer);

// The view's depth complexity as the objects' boxes estimate it: the texels of the map
// their footprints cover, summed, over the map's texels (a box through the near plane
// covers the whole view). Cheap, and an overestimate: a box covers more than its object.
double estimatedDepthComplexity(const PreparedScene& scene, const MapView& view, const VisibleSet& in);

// The occluders the knobs choose among the instances with triangles in `in`, in
// instance order.
std::vector<std::uint32_t> chooseOccluders(const PreparedScene& scene, const CameraTransform& camera, const Knobs& knobs,
                                           const VisibleSet& in);

// Rasterizes the occluders into a map, nearest first. Counts "occlusion: occluders
// rasterized", "occlusion: occluders skipped" (already hidden), "occlusion: occluders
// outside the map" (their boxes' footprints miss it: nothing to draw), "occlusion:
// occluder triangles" (a solid box drawn whole counts one), "occlusion: texels written".
DepthMap occluderDepthMap(const PreparedScene& scene, const MapView& view, const Knobs& knobs,
                          const std::vector<std::uint32_t>& occluders, Stats& stats);

// A frame's view distances (Frame::distances(), decoded here if its pass left them
// undecoded, and counted in `stats` then) reduced to a map: each texel the farthest depth
// of the pixels it overlaps.
DepthMap depthMapOfFrame(const MapView& view, const Frame& frame, Stats& stats);

// The stage: the triangles of the objects in `in` not proven hidden. Counts
// "occlusion: occludees tested", "occlusion: occludees culled", "occlusion: texels read",
// and "occlusion: no previous frame" when previous-frame has none (it then keeps all).
// With steps, records the map and each level of the pyramid above it. With why, says
// for hsr why's objects what the map test found: the texel that let the box show, or
// that every texel of its footprint hid it (and at which level of the pyramid).
VisibleSet cull(const PreparedScene& scene, const CameraTransform& camera, const Knobs& knobs, const VisibleSet& in,
                const PreviousFrame* previous, Stats& stats, StepRecorder* steps = nullptr, StageWitness* why = nullptr);

}  // namespace hsr::culling::occlusion
