#include "renderer/raster/screen_triangles.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "renderer/geometry/clip.hpp"
#include "renderer/util/memory.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr {
namespace {

struct Counts {
  std::int64_t outside = 0, clipped = 0, empty = 0;
};

// One chunk's output; corners stays empty unless they were asked for.
struct Part {
  ScreenTriangles triangles;
  ScreenCorners corners;
  bool keepCorners = false;
};

// Sets up one screen triangle and keeps it, or counts it when it covers no pixel center.
void emitTriangle(const dvec2 pixel[3], const double t[3], const CameraTransform& camera, std::uint32_t triangle,
                  Part& out, Counts& counts) {
  ScreenTriangle screen;
  if (!setupScreenTriangle(pixel, t, camera.width(), camera.height(), triangle, screen)) {
    ++counts.empty;
    return;
  }
  out.triangles.push_back(screen);
  if (out.keepCorners)
    out.corners.push_back({dvec3(pixel[0], t[0]), dvec3(pixel[1], t[1]), dvec3(pixel[2], t[2])});
}

// The vertices the triangle stage will read, as runs [first, end) of positions() cut
// into pieces of at most kPiece, so that threads share the work evenly whichever
// objects survived culling: every vertex without a VisibleSet, else the vertices of each
// object that still has a triangle in it.
std::vector<std::pair<std::uint32_t, std::uint32_t>> vertexPieces(const PreparedScene& scene, const VisibleSet* submitted) {
  constexpr std::uint32_t kPiece = 16384;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pieces;
  const auto cut = [&](std::uint32_t first, std::uint32_t end) {
    for (std::uint32_t begin = first; begin < end; begin += std::min(kPiece, end - begin))
      pieces.emplace_back(begin, begin + std::min(kPiece, end - begin));
  };
  if (!submitted) {
    cut(0, static_cast<std::uint32_t>(scene.positions().size()));
    return pieces;
  }
  auto next = submitted->triangles.begin();
  for (const Instance& instance : scene.instances()) {
    next = std::lower_bound(next, submitted->triangles.end(), instance.firstTriangle);
    if (next != submitted->triangles.end() && *next < instance.firstTriangle + instance.triangleCount)
      cut(instance.firstVertex, instance.firstVertex + instance.vertexCount);
  }
  return pieces;
}

// Four vertices at once, a vertex per lane: screenVertex's steps on Double4. Always
// inlined into screenVerticesWithAvx2 below, where its vectors become AVX2 registers.
// It takes and returns no vector itself, so no call passes one between code built for
// the baseline and code built for AVX2 (they pass vectors differently: clang refuses
// such a call, and an uninlined one would read garbage).
HSR_INLINE void screenFourVertices(const CameraTransform& camera, const ClipVolume& volume, const dvec3* p, ScreenVertex* out) {
  const ClipCoordinates<Double4> clip = camera.clipFromWorld(Double4{p[0].x, p[1].x, p[2].x, p[3].x}, Double4{p[0].y, p[1].y, p[2].y, p[3].y},
                                                             Double4{p[0].z, p[1].z, p[2].z, p[3].z});
  const Mask4 outside = volume.outside(clip);
  // screenVertex projects only a vertex in front of the near plane; a lane behind it
  // divides by 1 instead of its w and d, which may be 0 (a vertex in the eye's plane:
  // the debug build traps a division by zero).
  const Mask4 behind = (outside & std::int64_t(kNearPlane)) != 0;
  ClipCoordinates<Double4> projected = clip;
  projected.w = behind ? broadcast<Double4>(1.0) : clip.w;
  projected.d = behind ? broadcast<Double4>(1.0) : clip.d;
  const Double4 pixelX = camera.pixelXFromClip(projected), pixelY = camera.pixelYFromClip(projected),
                depth = camera.screenAffineDepth(projected.d);
  for (int lane = 0; lane < 4; ++lane) out[lane] = {static_cast<std::uint32_t>(outside[lane]), {pixelX[lane], pixelY[lane]}, depth[lane]};
}

HSR_AVX2 void screenVerticesWithAvx2(const CameraTransform& camera, const ClipVolume& volume, std::span<const dvec3> world,
                                     ScreenVertex* out) {
  for (std::size_t first = 0; first < world.size(); first += 4) screenFourVertices(camera, volume, &world[first], &out[first]);
}

}  // namespace

void screenVertices(const CameraTransform& camera, const ClipVolume& volume, std::span<const dvec3> world, ScreenVertex* out) {
  const std::size_t vectorized = cpuHasAvx2() ? world.size() / 4 * 4 : 0;
  screenVerticesWithAvx2(camera, volume, world.first(vectorized), out);
  for (std::size_t v = vectorized; v < world.size(); ++v) out[v] = screenVertex(camera, volume, world[v]);
}

ScreenGeometry buildScreenTriangles(const PreparedScene& scene, const GeometryOptions& options, int threads, Stats& stats) {
  return buildScreenTriangles(scene, scene.camera(), options, threads, stats);
}

ScreenGeometry buildScreenTriangles(const PreparedScene& scene, const CameraTransform& view, const GeometryOptions& options,
                                    int threads, Stats& stats) {
  ScreenGeometry geometry{view, {}, {}};
  buildScreenTriangles(scene, view, options, threads, stats, geometry);
  return geometry;
}

void buildScreenTriangles(const PreparedScene& scene, const CameraTransform& view, const GeometryOptions& options, int threads,
                          Stats& stats, ScreenGeometry& geometry) {
  PhaseTimer timer(stats, "geometry");
  const bool clipFar = options.clipFar, keepCorners = options.keepCorners;
  const VisibleSet* const submitted = options.submitted;
  geometry.camera = view;
  // The storage stays, for the triangles below; emptied first, so that nothing of an
  // earlier frame's list is copied when it grows.
  geometry.triangles.clear();
  geometry.corners.clear();
  const CameraTransform& camera = geometry.camera;
  const ClipVolume volume(camera, clipFar);

  // Vertex stage: every vertex the triangles will read, once, into clip space.
  const std::vector<dvec3>& positions = scene.positions();
  // Left uninitialized: every element a triangle reads is written by the loop below, in
  // parallel. A vertex in front of the near plane is also projected here, once, however
  // many triangles share it (on a closed mesh, about six).
  const auto vertices = uninitializedArray<ScreenVertex>(positions.size());
  // Their outcodes again, packed: what rejecting a triangle reads (below).
  const auto outsideOf = uninitializedArray<std::uint32_t>(positions.size());
  const int workers = resolveThreadCount(threads);
  {
    PhaseTimer vertexTimer(stats, "geometry: vertices");
    const auto pieces = vertexPieces(scene, submitted);
    parallelFor(pieces.size(), workers, [&](std::size_t piece, int) {
      const auto [first, end] = pieces[piece];
      screenVertices(camera, volume, std::span(positions).subspan(first, end - first), &vertices[first]);
      for (std::uint32_t v = first; v < end; ++v) outsideOf[v] = vertices[v].outside;
    });
    std::int64_t transformed = 0;
    for (const auto& [first, end] : pieces) transformed += end - first;
    stats.add("vertices transformed", transformed);
  }

  // Triangle stage, in fixed chunks claimed by whichever thread is free (the visible
  // triangles of a scene are seldom spread evenly over its index range), concatenated
  // in chunk order afterwards: the output order, and so every tie, is the same for any
  // thread count. One worker takes the chunks in order, so where the output has room
  // kept from an earlier frame (a caller reusing its storage) they append straight to
  // it, with nothing to concatenate (on dragons the concatenation's copy of 11 MB took 7%
  // of one thread's frame, by perf). Grown from nothing, the list would be copied at
  // every doubling: more than the concatenation copies (dragons' geometry stage 1.09
  // times as long).
  const std::vector<Triangle>& triangles = scene.triangles();
  const std::size_t submittedCount = submitted ? submitted->triangles.size() : triangles.size();
  constexpr std::size_t kChunkSize = 4096;
  const std::size_t chunks = (submittedCount + kChunkSize - 1) / kChunkSize;
  const bool inOrder = parallelWorkers(chunks, workers) == 1 && geometry.triangles.capacity() != 0;
  std::vector<Part> parts(inOrder ? 1 : chunks);
  if (inOrder) parts[0].triangles = std::move(geometry.triangles), parts[0].corners = std::move(geometry.corners);
  std::vector<Counts> counts(chunks);
  PhaseTimer triangleTimer(stats, "geometry: triangles");
  parallelFor(chunks, workers, [&](std::size_t part, int) {
    const std::size_t begin = part * kChunkSize, end = std::min(begin + kChunkSize, submittedCount);
    Part& out = parts[inOrder ? 0 : part];
    out.keepCorners = keepCorners;
    if (!inOrder) out.triangles.reserve(end - begin);  // one triangle in, at most one out unless clipped: no regrowth in the common case
    // Counted on this thread's stack and stored once: neighbouring chunks' counts share
    // cache lines, and the other thread is working on the next chunk (counted in place,
    // the two threads took 3.5 times one thread's time in this loop on dragons).
    Counts chunkCounts;
    for (std::size_t k = begin; k < end; ++k) {
      const std::size_t i = submitted ? submitted->triangles[k] : k;
      const Triangle& t = triangles[i];
      // Most triangles of a large scene lie wholly outside the view (three quarters of
      // the dragons'): triangleStage's first test, made here on the packed outcodes, 4
      // bytes a vertex where a ScreenVertex is 32, so that rejecting a triangle reads a
      // cache line instead of three (on dragons, by perf: the triangle loop 2.35 -> 1.87 ms).
      if (outsideOf[t[0]] & outsideOf[t[1]] & outsideOf[t[2]]) {
        ++chunkCounts.outside;
        continue;
      }
      const dvec3* const world[3] = {&positions[t[0]], &positions[t[1]], &positions[t[2]]};
      const TriangleFate fate = triangleStage(vertices[t[0]], vertices[t[1]], vertices[t[2]], world, camera, volume,
                                              [&](const dvec2 pixel[3], const double depth[3]) {
                                                emitTriangle(pixel, depth, camera, static_cast<std::uint32_t>(i), out, chunkCounts);
                                              });
      chunkCounts.outside += fate == TriangleFate::outside;
      chunkCounts.clipped += fate == TriangleFate::clipped;
    }
    counts[part] = chunkCounts;
  });

  // Concatenate the parts in order, each copied into its place on the threads. The lists
  // are resized without a fill (ScreenTriangles): with std::vector, resizing zeroed
  // every triangle first (11 MB on dragons) on one thread, which cost more than the
  // copy's second thread saved, and the parts were appended on one thread instead.
  if (inOrder) {
    geometry.triangles = std::move(parts[0].triangles), geometry.corners = std::move(parts[0].corners);
  } else {
    std::vector<std::size_t> placeOf(parts.size() + 1, 0);
    for (std::size_t part = 0; part < parts.size(); ++part) placeOf[part + 1] = placeOf[part] + parts[part].triangles.size();
    geometry.triangles.resize(placeOf.back());
    if (keepCorners) geometry.corners.resize(placeOf.back());
    parallelFor(parts.size(), workers, [&](std::size_t part, int) {
      const auto place = static_cast<std::ptrdiff_t>(placeOf[part]);
      std::copy(parts[part].triangles.begin(), parts[part].triangles.end(), geometry.triangles.begin() + place);
      if (keepCorners) std::copy(parts[part].corners.begin(), parts[part].corners.end(), geometry.corners.begin() + place);
    });
  }
  Counts sum;
  for (const Counts& chunk : counts) {
    sum.outside += chunk.outside;
    sum.clipped += chunk.clipped;
    sum.empty += chunk.empty;
  }
  stats.add("triangles in", static_cast<std::int64_t>(submittedCount));
  stats.add("triangles outside view", sum.outside);
  stats.add("triangles clipped", sum.clipped);
  stats.add("triangles between pixel centers", sum.empty);
  stats.add("screen triangles", static_cast<std::int64_t>(geometry.triangles.size()));
}

}  // namespace hsr
