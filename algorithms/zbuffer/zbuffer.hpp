// The z-buffer (Catmull 1974; Straßer 1974): keep, for every pixel, the depth of the
// nearest surface drawn so far, and draw a new fragment only if it is nearer.
//
// Inputs: a PreparedScene (world-space triangles with ids), a view, the knobs.
// Output: per pixel, the visible triangle's id + 1 (0 = background) and its depth as
// the chosen format stored it, decoded to view distance when a later stage asks
// (Frame::distances; the full frame keeps its buffer until then).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <span>
#include <string>
#include <type_traits>

#include "algorithms/algorithm.hpp"
#include "algorithms/knobs.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/raster/depth.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/steps/steps.hpp"
#include "renderer/steps/why.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::zbuffer {

enum class Variant {
  full,      // a depth buffer of the whole image, tile-parallel: memory O(width x height)
  scanline,  // a depth buffer one row high, rows in order with an active-triangle list: O(width)
};

// How the full-frame variant runs its loops: the textbook loop a pixel at a time, or
// the fast path (fast_path.hpp), bit for bit the same ids, depths and counters.
enum class Path { simd, scalar };

struct Knobs {
  Variant variant = Variant::full;
  DepthFormat depthFormat = DepthFormat::float32;
  // Off: no depth test at all, so every fragment is written and the order of submission
  // alone decides what a pixel shows (the last triangle drawn there). Kept to show what
  // the depth buffer buys, as the culling study's modes "without a z-buffer" do.
  bool depthTest = true;
  Path path = Path::simd;
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table = [] {
    std::vector<std::pair<DepthFormat, std::string>> formats;
    for (std::size_t f = 0; f < depthFormatNames().size(); ++f) formats.emplace_back(DepthFormat(f), depthFormatNames()[f]);
    return KnobTable<Knobs>()
        .choice("variant", &Knobs::variant, {{Variant::full, "full"}, {Variant::scanline, "scanline"}},
                "full: whole-image depth buffer, tile-parallel; scanline: one row of depth, active-triangle list")
        .choice("depth-format", &Knobs::depthFormat, formats, "what the depth buffer stores (conventions.hpp)")
        .onOff("depth-test", &Knobs::depthTest,
               "off: no depth test, every fragment is drawn and the last triangle drawn at a pixel wins (wrong wherever "
               "surfaces overlap; kept to show what the depth buffer buys)")
        .choice("path", &Knobs::path, {{Path::simd, "simd"}, {Path::scalar, "scalar"}},
                "simd: eight pixels at a time with AVX2, 8 x 8 blocks skipped by depth (fast_path.hpp), where the CPU has "
                "AVX2 and the depth format is a float with the depth test on, else the textbook loop; scalar: the "
                "textbook loop. The same ids, depths and counters")
        .onlyFor({"full"});
  }();
  return table;
}

// The visibility pass: the geometry stage, then the chosen variant, into visibility.frame
// (ids and depth). threads: 0 = all cores; the same bits for every count. Stats:
// "fragments tested", "fragments written", "depth ties" (DepthTest), "depth buffer
// bytes", the geometry stage's, and "distances decoded" where they were (the scanline
// variant decodes every row; the full frame's are decoded by Frame::distances, on demand). With request.why, every fragment tested at a pixel
// asked about is recorded there (DepthTest), and the full frame runs the textbook loop.
void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility);

// The registry's entry (algorithms/algorithm.hpp).
AlgorithmEntry entry();

// Where a variant records its steps (renderer/steps/steps.hpp), and the scene its ids index.
struct Recording {
  StepRecorder& steps;
  const PreparedScene& scene;
};

// The variants' visibility passes: they overwrite every pixel of frame.ids and leave
// frame.color alone (a Frame of the scene's size may be reused). The scanline variant
// writes the distances; the full frame leaves its depth buffer with the frame, decoded
// by the first call to frame.distances().
// With a recording, the full frame draws the whole image as one tile (every triangle in
// submission order, one thread) and records after triangles; the scanline variant runs
// its rows on one thread and records after rows. Same image and counters either way.
struct FullFrameOptions {
  bool depthTest = true;
  Path path = Path::simd;
  const Recording* recording = nullptr;
  PixelWitness* witness = nullptr;  // hsr why's pixels (DepthTest), drawn by the textbook loop
  // Off: the caller reads frame.ids alone (a peer compared on ids), so the depth buffer
  // is not kept for step 3, and asking the frame for distances is a bug in the caller.
  bool keepDepth = true;
};
void renderFullFrame(const ScreenGeometry& geometry, DepthFormat format, int threads, Frame& frame, Stats& stats,
                     const FullFrameOptions& options = {});
void renderScanline(const ScreenGeometry& geometry, DepthFormat format, int threads, Frame& frame, Stats& stats,
                    bool depthTest = true, const Recording* recording = nullptr, PixelWitness* witness = nullptr);

// A step's picture: the surfaces the ids show so far beside the depth buffer, the
// triangles just drawn outlined in red.
Image buffersPicture(const Recording& recording, const CameraTransform& view, std::span<const std::uint32_t> ids,
                     std::span<const float> depth, int width, int height, std::span<const std::uint32_t> justDrawn);

// What a depth test counts (DepthTest, and the fast path alike); only the fast path skips
// fragments by block depth (covered, counted as tested, never computed).
struct DepthCounts {
  std::int64_t tested = 0, written = 0, ties = 0, skippedByBlockDepth = 0;
};

// Where a tile's depth values live: pixel (x, y) of the image is at(x, y), in a buffer
// whose first value is pixel (x0, y0) and whose rows are `stride` values apart.
template <typename Stored>
struct DepthBuffer {
  Stored* values;
  std::size_t stride;
  int x0, y0;
  Stored& at(int x, int y) const { return values[std::size_t(y - y0) * stride + std::size_t(x - x0)]; }
};

// A format whose test always passes: the buffer still records each fragment's depth
// (the frame's depth is that of the triangle shown), but nothing is ever rejected.
template <typename Format>
struct WithoutDepthTest : Format {
  static bool nearer(typename Format::Stored, typename Format::Stored) { return true; }
};
template <typename Format>
inline constexpr bool kTestsDepth = true;
template <typename Format>
inline constexpr bool kTestsDepth<WithoutDepthTest<Format>> = false;

// withDepthFormat, with the test switched off when depthTest is false.
template <typename Visitor>
void withDepthTest(DepthFormat format, bool depthTest, Visitor&& visit) {
  withDepthFormat(format, [&]<typename Format>() {
    if (depthTest)
      visit.template operator()<Format>();
    else
      visit.template operator()<WithoutDepthTest<Format>>();
  });
}

// The depth test shared by both variants: encodes the fragment's depth in the format
// and keeps it, with its id, if nearer. Ties keep the earlier triangle ("less", not "less
// or equal"), and are counted: a fragment of another triangle stored at exactly the
// depth the pixel holds is a pixel the format cannot order, decided by submission order.
template <typename Format>
struct DepthTest {
  using Stored = typename Format::Stored;
  DepthEncoding encoding;
  DepthCounts counts;
  std::int64_t activeTriangles = 0;
  // hsr why: the pixels asked about, and the camera their depths are decoded with; null
  // when nothing is asked, and then the test does no more than the textbook's.
  PixelWitness* witness = nullptr;
  const CameraTransform* witnessCamera = nullptr;

  DepthTest() = default;
  explicit DepthTest(const DepthEncoding& encoding_, PixelWitness* witness_ = nullptr, const CameraTransform* camera_ = nullptr)
      : encoding(encoding_), witness(witness_), witnessCamera(camera_) {}

  void test(const ScreenTriangle& tri, int x, int y, Stored& stored, std::uint32_t& id) {
    ++counts.tested;
    const auto z = Format::store(encoding.z(tri.depthAt(conventions::pixelCenter(x), conventions::pixelCenter(y))));
    if (witness) [[unlikely]] witnessFragment(tri, x, y, z, stored, id);
    // BEGIN SOLUTION
    if (!Format::nearer(z, stored)) {
      counts.ties += isTie(tri, z, stored, id);
      return;
    }
    stored = z;
    id = tri.triangle + 1;
    ++counts.written;
    // SKELETON
    // // Exercise 1: keep the fragment (its depth z in `stored`, its triangle's id,
    // // tri.triangle + 1, in `id`) when Format::nearer says it is nearer than what the pixel
    // // holds, and count it in counts.written; otherwise count a tie (isTie) in counts.ties.
    // // Why must a tie keep the triangle drawn first?
    // (void)z, (void)stored, (void)id;
    // END SOLUTION
  }

  // A fragment of another triangle at exactly the depth the pixel holds.
  static bool isTie(const ScreenTriangle& tri, Stored z, Stored stored, std::uint32_t id) {
    return z == stored && id != conventions::kBackgroundId && id != tri.triangle + 1;
  }

  // hsr why: the fragment, before the test decides it, in the history of its pixel if
  // that is one asked about: its triangle, its depth as stored, what the pixel held and
  // the outcome.
  void witnessFragment(const ScreenTriangle& tri, int x, int y, Stored z, Stored stored, std::uint32_t id) const {
    std::vector<PixelEvent>* history = witness->at(x, y);
    if (!history) return;
    const bool written = Format::nearer(z, stored);
    const std::string held = id == conventions::kBackgroundId ? "the far end (cleared)" : "triangle " + std::to_string(id - 1) + "'s " + text(stored);
    std::string outcome = !kTestsDepth<Format> ? "written (no depth test)"
                          : written           ? "written: nearer than what the pixel held"
                          : isTie(tri, z, stored, id) ? "tie: the same stored depth; the triangle drawn first keeps the pixel"
                                                      : "lost the depth test";
    history->push_back({tri.triangle + 1, std::move(outcome), "depth stored " + text(z) + ", the pixel held " + held,
                        distance(tri.triangle + 1, z, *witnessCamera), written, {}});
  }

  static std::string text(Stored value) {
    if constexpr (std::is_floating_point_v<Stored>) {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.9g", double(value));
      return buffer;
    } else {
      return std::to_string(value);
    }
  }

  // What the buffer stored, decoded back to a distance along the view axis
  // (+infinity where the pixel shows the background).
  float distance(std::uint32_t id, typename Format::Stored stored, const CameraTransform& camera) const {
    if (id == conventions::kBackgroundId) return std::numeric_limits<float>::infinity();
    return static_cast<float>(camera.distanceFromScreenAffine(encoding.t(Format::load(stored))));
  }
};

}  // namespace hsr::zbuffer
