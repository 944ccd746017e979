// The geometry stage every rasterizing algorithm starts with: transform each vertex
// to clip space, reject triangles wholly outside the view, clip the rest at the near
// (and far) plane and the guard band, project and snap to fixed point.
#pragma once

#include <array>
#include <vector>

#include "renderer/camera.hpp"
#include "renderer/depth.hpp"
#include "renderer/prepare.hpp"
#include "renderer/raster.hpp"
#include "renderer/stats.hpp"
#include "renderer/visible_set.hpp"

namespace hsr {

struct ScreenGeometry {
  CameraTransform camera;
  // In submission order: by global triangle index, and a clipped triangle's pieces
  // in fan order. Ties between equal depths go to the earlier entry.
  std::vector<ScreenTriangle> triangles;
  // Only when asked for (the painter's geometric tests need them; the z-buffer does
  // not): each screen triangle's corners as (pixel x, pixel y, t), unsnapped, in the
  // order the triangle was given (before the rasterizer's reordering).
  std::vector<std::array<dvec3, 3>> corners;
};

// What the geometry stage is asked for.
struct GeometryOptions {
  // Clip at the far plane as well as the near one: every depth format but the reversed
  // float with an infinite far plane needs it.
  bool clipFar = true;
  // Keep each screen triangle's unsnapped corners (ScreenGeometry::corners): the
  // painter's geometric tests need them, the z-buffer does not.
  bool keepCorners = false;
  // Only these triangles (what culling stages kept); nullptr: all of them.
  const VisibleSet* submitted = nullptr;
};

// Counts in stats: "triangles in", "triangles outside view" (rejected whole),
// "triangles clipped", "triangles between pixel centers" (zero area or no center
// inside), "screen triangles" (what the rasterizer receives), "vertices transformed".
// With a VisibleSet only its triangles go in, and only the vertices of objects that
// still have a triangle in it are transformed: what a culling stage saves.
ScreenGeometry buildScreenTriangles(const PreparedScene& scene, const GeometryOptions& options, int threads, Stats& stats);
// The same from another viewpoint than the scene's camera (a light's, for a shadow map),
// into an image of the view's size.
ScreenGeometry buildScreenTriangles(const PreparedScene& scene, const CameraTransform& view, const GeometryOptions& options,
                                    int threads, Stats& stats);

}  // namespace hsr
