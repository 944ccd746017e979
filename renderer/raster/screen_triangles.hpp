// The geometry stage every rasterizing algorithm starts with: transform each vertex
// to clip space, reject triangles wholly outside the view, clip the rest at the near
// (and far) plane and the guard band, project and snap to fixed point.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/geometry/clip.hpp"
#include "renderer/raster/depth.hpp"
#include "renderer/raster/raster.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/scene/visible_set.hpp"
#include "renderer/util/memory.hpp"
#include "renderer/util/stats.hpp"

namespace hsr {

// The geometry stage's lists, made without a fill (FirstTouchAllocator): the stage's
// chunks are copied into their places on the threads.
using ScreenTriangles = std::vector<ScreenTriangle, FirstTouchAllocator<ScreenTriangle>>;
using ScreenCorners = std::vector<std::array<dvec3, 3>, FirstTouchAllocator<std::array<dvec3, 3>>>;

struct ScreenGeometry {
  CameraTransform camera;
  // In submission order: by global triangle index, and a clipped triangle's pieces
  // in fan order. Ties between equal depths go to the earlier entry.
  ScreenTriangles triangles;
  // Only when asked for (the painter's geometric tests need them; the z-buffer does
  // not): each screen triangle's corners as (pixel x, pixel y, t), unsnapped, in the
  // order the triangle was given (before the rasterizer's reordering).
  ScreenCorners corners;
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

// The vertex stage for one vertex: the clipping planes (and the image's edges) it lies
// outside of, and, when it is in front of the near plane, where it projects: its pixel
// position and screen-affine depth t. Its clip-space position is not kept: only a
// triangle that must be clipped needs it, and that one transforms its corners again
// (the same operations, so the same bits). Kept, it would double the bytes every
// triangle reads.
struct ScreenVertex {
  std::uint32_t outside;
  dvec2 pixel;
  double depth;
};
inline ScreenVertex screenVertex(const CameraTransform& camera, const ClipVolume& volume, const dvec3& world) {
  ScreenVertex vertex;
  const ClipVertex clip = camera.clipFromWorld(world);
  vertex.outside = volume.outside(clip);
  if (!(vertex.outside & kNearPlane)) {
    vertex.pixel = camera.pixelFromClip(clip);
    vertex.depth = camera.screenAffineDepth(clip.d);
  }
  return vertex;
}

// The vertex stage for a run of vertices: out[i] = screenVertex(world[i]) for each, four
// at a time in vectors where the CPU has AVX2. The lanes run screenVertex's own
// templates (the same operations in the same order), so every field screenVertex sets
// has the same bits; a vertex behind the near plane also gets a pixel and depth there,
// which no triangle reads.
void screenVertices(const CameraTransform& camera, const ClipVolume& volume, std::span<const dvec3> world, ScreenVertex* out);

// What the triangle stage did with one triangle.
enum class TriangleFate { outside, projected, clipped };

// The triangle stage for one triangle whose corners went through the vertex stage
// (`world`: the same corners in world space): dropped when all three lie outside one
// plane, else projected (clipped first at the planes it crosses, its polygon cut into a
// fan) and handed to emit(pixel[3], t[3]) as corner pixel positions and depths, one call
// per piece.
template <typename Emit>
TriangleFate triangleStage(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, const dvec3* const world[3],
                           const CameraTransform& camera, const ClipVolume& volume, Emit&& emit) {
  // All three vertices outside one plane: no point of the triangle is visible.
  if (a.outside & b.outside & c.outside) return TriangleFate::outside;
  const std::uint32_t crossed = (a.outside | b.outside | c.outside) & kClippingPlanes;
  if (!crossed) {  // the common case: the vertex stage projected the corners already
    const dvec2 pixel[3] = {a.pixel, b.pixel, c.pixel};
    const double depth[3] = {a.depth, b.depth, c.depth};
    emit(pixel, depth);
    return TriangleFate::projected;
  }
  const ClipPolygon polygon =
      clipTriangle({camera.clipFromWorld(*world[0]), camera.clipFromWorld(*world[1]), camera.clipFromWorld(*world[2])}, volume, crossed);
  dvec2 pixel[9];
  double depth[9];
  for (int i = 0; i < polygon.count; ++i) {
    pixel[i] = camera.pixelFromClip(polygon.vertices[i]);
    depth[i] = camera.screenAffineDepth(polygon.vertices[i].d);
  }
  for (int i = 1; i + 1 < polygon.count; ++i) {
    const dvec2 fanPixel[3] = {pixel[0], pixel[i], pixel[i + 1]};
    const double fanDepth[3] = {depth[0], depth[i], depth[i + 1]};
    emit(fanPixel, fanDepth);
  }
  return TriangleFate::clipped;
}

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
// The same into `geometry`, whose storage is reused (as a renderer keeps its buffers
// from frame to frame); what it held before is replaced.
void buildScreenTriangles(const PreparedScene& scene, const CameraTransform& view, const GeometryOptions& options, int threads,
                          Stats& stats, ScreenGeometry& geometry);

}  // namespace hsr
