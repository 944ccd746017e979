// The error of an algorithm against the exact reference. The definitions are the
// README's ("Metrics"); hsr compare and hsr sweep print them, and tests assert them.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "renderer/image/frame.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/raster/coverage.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/shading/shading.hpp"

namespace hsr {

// Surface algorithms: per pixel, the visible id and its depth.
struct SurfaceError {
  std::int64_t comparedPixels = 0;   // pixels the reference decides uniquely (not ambiguous)
  std::int64_t ambiguousPixels = 0;  // left out: any of the tied triangles is right
  std::int64_t wrongPixels = 0;      // compared pixels whose id differs from the reference's
  double pixelError = 0;             // wrongPixels / comparedPixels
  std::int64_t depthPixels = 0;      // pixels where both show the same triangle
  double depthErrorMean = 0;         // mean |depth - reference depth| over those, in view units
  double depthErrorMax = 0;
};
SurfaceError surfaceError(const Frame& frame, const ReferenceImage& reference);

// An RGBA8 picture of where a frame is wrong: the reference's image dimmed to grey,
// wrong pixels red, ambiguous pixels blue.
std::vector<std::uint8_t> errorHeatMap(const Frame& frame, const ReferenceImage& reference);
// The same for an antialiasing algorithm's shares against the exact ones: each pixel the
// redder the more of it shows something other than the exact shares say
// (coverageDistance), any difference at least a quarter red; pixels where the exact
// shares meet a tie blue.
std::vector<std::uint8_t> coverageHeatMap(const PixelShares& measured, const PixelShares& exact, const ReferenceImage& reference);

// Shadows: at every covered pixel of a frame and every light that faces the surface
// there, a shadow technique's decision against the exact one at the same surface point
// (renderer/shading/shading: PixelShader<double>::surfacePoint), so that the error is the shadow test's alone.
struct ShadowError {
  std::int64_t lookups = 0;    // (pixel, light) pairs tested
  std::int64_t differing = 0;  // decided differently from the exact test
  double fraction = 0;         // differing / lookups
  std::int64_t falselyShadowed = 0;  // shadowed, but lit by the exact test (acne)
  std::int64_t falselyLit = 0;       // lit, but shadowed by the exact test (peter-panning, light leaks)
};
ShadowError shadowError(const PreparedScene& scene, const Frame& frame, const ShadowTest& tested, const ShadowTest& exact,
                        int threads);

// Culling stages: per item (object or triangle), kept by the stage or not, and
// visible in the reference or not.
struct CullingError {
  std::int64_t items = 0, visible = 0, kept = 0;
  std::int64_t falseCulls = 0;  // visible but removed: must be 0 for a conservative stage
  std::int64_t wastedWork = 0;  // kept but invisible
};
CullingError cullingError(std::span<const std::uint8_t> kept, std::span<const std::uint8_t> visible);
// Which triangles the reference shows at some pixel (ambiguous pixels count for the
// id recorded and for no other).
std::vector<std::uint8_t> visibleTriangles(const ReferenceImage& reference, std::size_t triangleCount);
// Per-triangle flags (kept, visible) lifted to the scene's objects: an object is flagged
// when any of its triangles is, so cullingError can count objects, as occlusion culls them.
std::vector<std::uint8_t> objectsWithAny(const PreparedScene& scene, std::span<const std::uint8_t> triangleFlags);

// Line algorithms: each edge's visible parts drawn against the reference's
// (EdgeVisibility, renderer/lines/line_set.hpp).
struct LineError {
  double visibleLength = 0;  // pixels visible in the reference
  double wronglyDrawn = 0;   // pixels drawn but hidden in the reference
  double wronglyHidden = 0;  // pixels visible in the reference but not drawn
  double error = 0;          // (wronglyDrawn + wronglyHidden) / visibleLength
};
// drawn[i] and reference[i] describe the same edge.
LineError lineError(std::span<const EdgeVisibility> drawn, std::span<const EdgeVisibility> reference);

}  // namespace hsr
