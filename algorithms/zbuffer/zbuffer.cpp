// The full-frame z-buffer, and the steps both variants share.
#include "algorithms/zbuffer/zbuffer.hpp"

#include <algorithm>
#include <memory>
#include <optional>

#include "renderer/parallel.hpp"
#include "renderer/screen_triangles.hpp"
#include "renderer/simd.hpp"
#include "renderer/tiles.hpp"

namespace hsr::zbuffer {
Image buffersPicture(const Recording& recording, const CameraTransform& view, std::span<const std::uint32_t> ids,
                     std::span<const float> depth, int width, int height, std::span<const std::uint32_t> justDrawn) {
  Image surfaces = surfacePicture(recording.scene, view, ids, width, height);
  drawWireframe(surfaces, recording.scene, view, justDrawn, kHighlight);
  return besideEachOther({surfaces, depthPicture(depth, width, height)});
}

namespace {

// How far ahead of the triangle being drawn the next is asked for: enough to cover a
// cache miss while a few small triangles are drawn (on dragons, zbuffer_bench raster:
// 4 ahead 6.10 ms, 8 ahead 5.68, 16 ahead 5.86).
constexpr std::size_t kPrefetchAhead = 8;

}  // namespace

void renderFullFrame(const ScreenGeometry& geometry, DepthFormat format, int threads, Frame& frame, Stats& stats,
                     const FullFrameOptions& options) {
  const Recording* recording = options.recording;
  // Binning: each tile gets the triangles whose pixel box overlaps it, in submission
  // order, so that within a tile triangles are drawn in the same order as on one thread.
  const TileGrid tiles(frame.width, frame.height, recording ? std::max(frame.width, frame.height) : TileGrid::kTileSize);
  std::vector<std::vector<std::uint32_t>> bins;
  {
    PhaseTimer timer(stats, "binning");
    bins = tiles.bin(geometry.triangles.size(), [&](std::uint32_t i) -> const ScreenTriangle& { return geometry.triangles[i]; });
  }

  PhaseTimer timer(stats, "rasterization");
  withDepthTest(format, options.depthTest, [&]<typename Format>() {
    const DepthEncoding encoding = depthEncoding(format, geometry.camera);
    // The fast path runs float formats with the depth test on, on a CPU with AVX2.
    constexpr bool kFloatDepthTest = std::is_same_v<Format, Float32Depth> || std::is_same_v<Format, ReversedFloat32Depth>;
    const bool simd = kFloatDepthTest && options.path == Path::simd && cpuHasAvx2();
    // The textbook's depth buffer covers the whole frame. The fast path draws each tile
    // in a buffer of its own, one per worker, which stays in the cache while the tile is
    // drawn (a tiling GPU keeps its tile in on-chip memory for the same reason): the same
    // values, stored closer. Left uninitialized here: each tile clears its own part, on
    // the thread that will use it.
    const auto depthValues = [&](const TileGrid& grid, int workers) {
      return simd ? std::size_t(parallelWorkers(grid.count(), workers)) * grid.largestTileArea() : frame.pixelCount();
    };
    const auto depth = std::make_unique_for_overwrite<typename Format::Stored[]>(depthValues(tiles, threads));
    std::vector<double> testedAt(recording ? frame.pixelCount() : 0);  // fragments tested per pixel, for the steps
    std::vector<DepthTest<Format>> tileResults(bins.size());
    parallelFor(bins.size(), threads, [&](std::size_t tile, int worker) {
      const auto [tileX0, tileY0, tileX1, tileY1] = tiles.rect(tile);
      const auto pixel = [&](int x, int y) { return std::size_t(y) * std::size_t(frame.width) + std::size_t(x); };
      using TileDepth = DepthBuffer<typename Format::Stored>;
      const TileDepth tileDepth = simd ? TileDepth{&depth[std::size_t(worker) * tiles.largestTileArea()], std::size_t(tileX1 - tileX0), tileX0, tileY0}
                                       : TileDepth{depth.get(), std::size_t(frame.width), 0, 0};
      DepthTest<Format> test{encoding};  // on this thread's stack: no cache line shared with other tiles
      // Step 1: clear the depth buffer to the far end of the format, and the ids to background.
      for (int y = tileY0; y < tileY1; ++y) {
        std::fill(&tileDepth.at(tileX0, y), &tileDepth.at(tileX0, y) + (tileX1 - tileX0), Format::kFar);
        std::fill(&frame.ids[pixel(tileX0, y)], &frame.ids[pixel(tileX0, y)] + (tileX1 - tileX0), conventions::kBackgroundId);
      }
      // The fast path's tile (fast_path.hpp), when it runs: the same steps 2 and 3.
      std::optional<SimdTile> fast;
      if constexpr (kFloatDepthTest)
        if (simd) fast.emplace(tiles.rect(tile), frame.width, tileDepth, frame.ids.data(), encoding,
                               std::is_same_v<Format, ReversedFloat32Depth>, test.counts);
      // Step 2: for every triangle and every pixel it covers, keep the fragment if it is
      // nearer than what the pixel holds.
      for (std::size_t drawn = 0; drawn < bins[tile].size(); ++drawn) {
        // A tile's triangles lie scattered through the scene's list (a mesh's triangles
        // fall into many tiles): ask for one a few ahead while this one is drawn, or each
        // waits on a cache miss (on dragons, most of the pass).
        if (drawn + kPrefetchAhead < bins[tile].size()) prefetch(geometry.triangles[bins[tile][drawn + kPrefetchAhead]]);
        const ScreenTriangle& tri = geometry.triangles[bins[tile][drawn]];
        const int x0 = std::max(tri.minX, tileX0), x1 = std::min(tri.maxX + 1, tileX1);
        if (fast && fast->worthDrawing(tri)) {
          fast->draw(tri);
        } else {
          for (int y = std::max(tri.minY, tileY0); y < std::min(tri.maxY + 1, tileY1); ++y) {
            const std::size_t row = pixel(0, y);
            rasterizeSpan(tri, y, x0, x1, [&](int x) { test.test(tri, x, y, tileDepth.at(x, y), frame.ids[row + std::size_t(x)]); });
          }
        }
        if (recording) {
          // Overdraw: every pixel the triangle covered was one more fragment tested there.
          for (int y = tri.minY; y <= tri.maxY; ++y) rasterizeSpan(tri, y, tri.minX, tri.maxX + 1, [&](int x) { ++testedAt[pixel(x, y)]; });
          if (recording->steps.due(drawn, bins[tile].size())) {
            std::vector<float> distances(frame.pixelCount());  // recording draws the image as one tile
            for (int y = 0; y < frame.height; ++y)
              for (int x = 0; x < frame.width; ++x) distances[pixel(x, y)] = test.distance(frame.ids[pixel(x, y)], tileDepth.at(x, y), geometry.camera);
            recording->steps.record("step 2, depth test: triangle " + std::to_string(drawn + 1) + " of " + std::to_string(bins[tile].size()) +
                                        " drawn (red); " + std::to_string(test.counts.written) + " of " + std::to_string(test.counts.tested) +
                                        " fragments so far were nearer and kept",
                                    buffersPicture(*recording, geometry.camera, frame.ids, distances, frame.width, frame.height,
                                                   std::span(&tri.triangle, 1)));
          }
        }
      }
      // Step 3: the frame's depth is what the format stored, decoded to a view distance.
      if (fast) {
        fast->decode(frame.depth, geometry.camera.perspective());
      } else {
        for (int y = tileY0; y < tileY1; ++y)
          for (int x = tileX0; x < tileX1; ++x) frame.depth[pixel(x, y)] = test.distance(frame.ids[pixel(x, y)], tileDepth.at(x, y), geometry.camera);
      }
      tileResults[tile] = test;
    });
    if (recording)
      recording->steps.record("overdraw: fragments tested per pixel (" + std::to_string(tileResults[0].counts.tested) + " in all, " +
                                  std::to_string(tileResults[0].counts.written) + " written)",
                              heatMapPicture(testedAt, frame.width, frame.height, "fragments tested per pixel"));
    for (const auto& test : tileResults) {
      stats.add("fragments tested", test.counts.tested);
      stats.add("fragments written", test.counts.written);
      stats.add("depth ties", test.counts.ties);
      if (simd) stats.add("fragments skipped by block depth", test.counts.skippedByBlockDepth);  // present exactly when the fast path ran
    }
    // What drawing needs. A recording draws the image as one tile, on one thread; it
    // counts what drawing in tiles on one thread needs, so that recording the steps
    // changes no counter.
    const std::size_t counted = recording ? depthValues(TileGrid(frame.width, frame.height), 1) : depthValues(tiles, threads);
    stats.add("depth buffer bytes", static_cast<std::int64_t>(counted * sizeof(typename Format::Stored)));
  });
}

void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility) {
  const bool clipFar = clipsFarPlane(knobs.depthFormat, request.view.camera().projection);
  const ScreenGeometry geometry =
      buildScreenTriangles(request.scene, request.view, {.clipFar = clipFar, .submitted = request.triangles}, request.threads, request.stats);
  std::optional<Recording> recording;
  if (request.steps) recording.emplace(Recording{*request.steps, request.scene});
  const Recording* steps = recording ? &*recording : nullptr;
  if (knobs.variant == Variant::full)
    renderFullFrame(geometry, knobs.depthFormat, request.threads, visibility.frame, request.stats, {knobs.depthTest, knobs.path, steps});
  else
    renderScanline(geometry, knobs.depthFormat, request.threads, visibility.frame, request.stats, knobs.depthTest, steps);
}

AlgorithmEntry entry() {
  AlgorithmEntry entry;
  entry.name = "zbuffer";
  entry.summary = "per-pixel depth test (Catmull 1974): full-frame or one-scanline buffer";
  setKnobs(entry, knobTable());
  entry.keyCounters = {"screen triangles", "fragments tested", "fragments written", "fragments skipped by block depth"};
  entry.studyConfigurations = {{}, {{"path", "scalar"}}, {{"variant", "scanline"}}, {{"depth-format", "unorm24"}}, {{"depth-format", "unorm16"}}};
  entry.takesTriangleSubsets = true;
  setVisibility(entry, visibility);
  return entry;
}

}  // namespace hsr::zbuffer
