// The exact surface reference: for every pixel center, the visible triangle decided in
// object space, the ground truth every surface algorithm is measured against.
//
// It shares no code with the rasterizer. A ray leaves the eye through the pixel center
// (parallel to the view axis from the near-plane rectangle under orthographic, as
// CameraTransform::rayThroughPixel defines it), and the nearest triangle it meets
// between the near and far planes wins:
//   1. Candidates come from a BVH (renderer/rays/bvh) with conservative box tests.
//   2. Each is tested with the watertight ray-triangle test of Woop, Benthin and Wald
//      (2013) in double precision, with a forward error bound on each of its values.
//   3. Wherever a bound leaves a decision open (a pixel center on an edge, a hit on the
//      near plane, two hits closer than their depth bounds), the same test is evaluated
//      again exactly (renderer/geometry/exact.hpp): the ray's origin and direction and
//      the vertices are doubles, and every value the test compares is a quotient of sums
//      of their products, so the decision is exact for that ray.
//   4. A pixel whose nearest hit is shared exactly by two or more triangles (coplanar
//      faces overlapping, a center exactly on a shared edge or vertex) is *ambiguous*:
//      any of them is a correct answer. The id recorded is the lowest, and metrics skip
//      the pixel.
//   5. With packets, a tile of pixels that shows one triangle whole, or nothing, is
//      proved to (renderer/reference/tile_proof.hpp) and not searched ray by ray: the same
//      answers.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/raster/coverage.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/shading/shading.hpp"
#include "renderer/util/stats.hpp"

namespace hsr {

struct ReferenceHit {
  std::uint32_t id = 0;     // global triangle index + 1; 0 = nothing between near and far
  // Along the view axis, as Frame::depth measures it: +infinity where nothing was met.
  double distance = std::numeric_limits<double>::infinity();
  bool ambiguous = false;   // two or more triangles are exactly the nearest
  bool usedExact = false;   // some decision for this ray needed exact arithmetic
};

// How the reference traverses the BVH for a row of primary rays: eight rays at a time
// through the wide BVH where the CPU has AVX2 (reference_packets.cpp), with tiles proved
// whole where they can be (traceTile), or the textbook traversal of one ray at a time.
// The same ids, depths, ambiguity and fall-backs.
enum class ReferenceTraversal { packets, textbook };

class SurfaceReference {
 public:
  // Builds (or reuses) the scene's triangle BVH, and the wide one for packets.
  // `threads`: what the BVHs are built on, if this is their first use.
  SurfaceReference(const PreparedScene& scene, Stats& stats, ReferenceTraversal traversal = ReferenceTraversal::textbook, int threads = 1);

  // Per-ray work counters, summed by the caller.
  struct Counters {
    std::int64_t nodesVisited = 0, triangleTests = 0, exactTriangleTests = 0, exactComparisons = 0;
    std::int64_t tilesProved = 0, raysProved = 0;  // traceTile's proofs, and the rays they answered
  };
  // `tied`, when given, receives the triangles exactly nearest (global index + 1, ascending):
  // the one winner, every triangle of a certified tie, or none where nothing is met.
  ReferenceHit trace(const CameraTransform& camera, const Ray& ray, Counters& counters,
                     std::vector<std::uint32_t>* tied = nullptr) const;
  // trace() for the rays through pixels x0 .. x0 + count - 1 of row y
  // (CameraTransform::rayThroughPixel), by the traversal chosen.
  void traceRun(const CameraTransform& camera, int y, int x0, int count, ReferenceHit* hits, Counters& counters) const;
  // traceRun() for a row of tiles of pixels: rows y0 .. y0 + height - 1 (height at most
  // kTileSize) of the whole image width, into hits[row * stride + x]; the same answers.
  // With packets, each tile takes a candidate: what the row above (`above`, answered
  // already; or null) shows along it, or with no row above, what one ray through the
  // tile's middle shows, if it shows one answer plainly. The tile is proved to show it
  // (renderer/reference/tile_proof.hpp) if it does, and its rays are then not searched;
  // up to kRunTiles neighbouring tiles with the same candidate are proved at once.
  static constexpr int kTileSize = 8, kRunTiles = 8;
  void traceTileRow(const CameraTransform& camera, int y0, int height, const ReferenceHit* above, ReferenceHit* hits, std::size_t stride,
                    Counters& counters) const;

  // Every triangle the ray meets between the near and far planes, nearest first in the
  // exact order of their distances, up to the first opaque one (for the exact blend of
  // transparent surfaces); `tied` when two of those are met at exactly the same distance
  // (a pixel center on a shared edge, coplanar faces), where no order is the right one.
  struct Layers {
    std::vector<ReferenceHit> hits;
    bool tied = false;
  };
  Layers traceAll(const CameraTransform& camera, const Ray& ray, Counters& counters) const;

  // Whether an opaque triangle other than global triangle `except` meets the segment
  // origin + t direction for t in (tMin, 1]: the exact shadow ray (each inside decision
  // and each comparison with tMin and 1 exact for these doubles).
  bool blocked(const Ray& segment, double tMin, std::uint32_t except, Counters& counters) const;

 private:
  using PackedTriangle = PreparedScene::LeafTriangle;
  const PreparedScene& scene_;
  const Bvh& bvh_;
  const std::vector<PackedTriangle>& triangles_;  // in bvh_.order(), so a leaf reads one contiguous run
  const WideBvh* wideBvh_;                         // for packets; null for the textbook traversal
  Aabb sceneBox_;                                  // the BVH's root box: every triangle
  // Up to eight rays of a row as one packet, when they can travel together
  // (RayPacket::travelTogether); false when they cannot.
  bool tracePacket(const CameraTransform& camera, int y, int x, int count, ReferenceHit* hits, Counters& counters) const;
  // traceTileRow's tile at x0 .. x0 + width - 1: proved to show its candidate (a triangle's
  // id, or 0 for nothing) where it can; else its first row is searched, and the other
  // rows proved to show what that row shows, if it shows one answer plainly, or searched.
  void traceTile(const CameraTransform& camera, int x0, int y0, int width, int height, std::optional<std::uint32_t> candidateId,
                 ReferenceHit* hits, std::size_t stride, Counters& counters) const;
  // The pixels of the rectangle x0 .. x0 + width - 1, y0 .. y0 + height - 1 answered by a
  // proof that they show triangle `id` (0: nothing), or false when it fails and nothing
  // was written.
  bool answerByProof(const CameraTransform& camera, int x0, int y0, int width, int height, std::uint32_t id, ReferenceHit* hits,
                     std::size_t stride, Counters& counters) const;
  // Up to eight rays of a row where a tile's proof showed that no triangle but
  // `candidate` can be met before it: their hits on it, or false when they cannot travel
  // together or one of them does not surely meet it between the near and far planes.
  bool candidateRun(const CameraTransform& camera, int y, int x, int count, const PackedTriangle& candidate, ReferenceHit* hits,
                    Counters& counters) const;
};

// Exact shadow rays: a point is shadowed from a light when a segment from it to the light
// (a point light) or out of the scene's bounds toward it (a directional light) meets
// another opaque triangle (a transparent one lets the light through, as in the shadow maps). Hits within 1e-9 of the segment's length from the point are ignored:
// the point lies on its own triangle and that triangle's neighbours only to rounding.
// Stats (summed by the caller through counters()): the reference's counters.
class ExactShadows : public ShadowTest {
 public:
  ExactShadows(const PreparedScene& scene, Stats& stats);
  bool shadowed(std::size_t light, const dvec3& point, std::uint32_t triangle) const override;

 private:
  const PreparedScene& scene_;
  SurfaceReference reference_;
  double reach_;  // longer than any path across the scene's bounds
};

struct ReferenceImage {
  Frame frame;                           // ids, depth, and color shaded as every algorithm shades
  std::vector<std::uint8_t> ambiguous;   // 1 where the pixel is ambiguous (see above)
  std::int64_t ambiguousPixels = 0;
  std::int64_t exactFallbacks = 0;       // pixels whose ray needed exact arithmetic
  // With transparency only: 1 where two surfaces along the ray lie at exactly the same
  // distance, so that no blending order is the right one (metrics skip the pixel).
  std::vector<std::uint8_t> blendTied;
  std::int64_t blendTiedPixels = 0;
};

// The visibility pass alone: ids, depth and ambiguity; the color is left black.
// Stats: "reference rays", "reference exact fall-backs", "reference ambiguous pixels",
// "reference tiles proved" and "reference rays proved" (SurfaceReference::traceTile),
// "bvh nodes visited", "ray-triangle tests", "exact ray-triangle tests", "exact depth
// comparisons"; phases "reference" and (on first use) "bvh build". threads: 0 = all cores.
ReferenceImage traceReference(const PreparedScene& scene, int threads, Stats& stats,
                              ReferenceTraversal traversal = ReferenceTraversal::packets);
// The same into `image`, reusing its buffers when it has the scene's size (a benchmark's
// frames, as the z-buffer's reuse theirs); its color is left as it was.
void traceReference(const PreparedScene& scene, int threads, Stats& stats, ReferenceTraversal traversal, ReferenceImage& image);
// Each pixel's exact shares (renderer/raster/coverage.hpp), what coverage error is
// measured against: what the reference sees at samples x samples points of the pixel (the
// pixel centers of an image `samples` times finer), each point a share; the same shares as
// tracing every point, with far fewer rays. A pixel is traced in full unless it is proved
// to show one surface whole: a survey at 4 x 4 points per pixel finds one triangle at its
// points and its neighbours' nearest ones (so that triangle covers it), and no other
// triangle that may touch the pixel has a corner in front of that triangle's plane (or,
// for a pixel showing nothing, none between the near and far planes may touch it). Opaque
// surfaces: the shares are of coverage. Stats: "coverage reference rays", "coverage
// reference pixels traced in full"; phase "coverage reference".
PixelShares traceExactShares(const PreparedScene& scene, int samples, int threads, Stats& stats);

// traceReference, then the shading every algorithm's frame gets (renderer/shading/shading), with
// exact shadow rays where an algorithm's frame has shadow maps, then fog and outline.
ReferenceImage renderReference(const PreparedScene& scene, int threads, Stats& stats);

}  // namespace hsr
