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
#pragma once

#include <array>
#include <optional>

#include "algorithms/culling/culling.hpp"
#include "algorithms/culling/occlusion/depth_map.hpp"

namespace hsr::culling::occlusion {

enum class Method { depthMap, previousFrame };
enum class Occluders { all, volume, solidAngle };

struct Settings {
  Method method = Method::depthMap;
  Rule rule = Rule::conservative;
  int mapWidth = 256, mapHeight = 128;
  bool pyramid = false;
  Occluders occluders = Occluders::all;
  double fraction = 0.1;  // of the objects, when occluders is not all
  // Run only when the objects' boxes cover the view at least this many times over
  // (estimatedDepthComplexity); 0: always.
  double minDepthComplexity = 0;
};
Settings settingsOf(const StageChoice& choice);

// The stage's entry in culling::stages().
StageEntry stage();

// The object copy's box in world space (corners as cornersOf orders them, moved by its
// placement) when the object is a box solid, whose mesh is exactly that box.
std::optional<std::array<dvec3, 8>> boxOfSolid(const PreparedScene& scene, const Instance& instance);

// The view's depth complexity as the objects' boxes estimate it: the texels of the map
// their footprints cover, summed, over the map's texels (a box through the near plane
// covers the whole view). Cheap, and an overestimate: a box covers more than its object.
double estimatedDepthComplexity(const PreparedScene& scene, const MapView& view, const VisibleSet& in);

// The occluders the settings choose among the instances with triangles in `in`, in
// instance order.
std::vector<std::uint32_t> chooseOccluders(const PreparedScene& scene, const CameraTransform& camera, const Settings& settings,
                                           const VisibleSet& in);

// Rasterizes the occluders into a map, nearest first. Counts "occlusion: occluders
// rasterized", "occlusion: occluders skipped" (already hidden), "occlusion: occluder
// triangles", "occlusion: texels written".
DepthMap occluderDepthMap(const PreparedScene& scene, const MapView& view, const Settings& settings,
                          const std::vector<std::uint32_t>& occluders, Stats& stats);

// A depth image (Frame::depth, distances) reduced to a map: each texel the farthest depth
// of the pixels it overlaps.
DepthMap depthMapOfFrame(const MapView& view, const Frame& frame);

// The stage: the triangles of the objects in `in` not proven hidden. Counts
// "occlusion: occludees tested", "occlusion: occludees culled", "occlusion: texels read",
// and "occlusion: no previous frame" when previous-frame has none (it then keeps all).
VisibleSet cull(const PreparedScene& scene, const CameraTransform& camera, const Settings& settings, const VisibleSet& in,
                const PreviousFrame* previous, Stats& stats);

}  // namespace hsr::culling::occlusion
