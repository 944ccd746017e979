// The full-frame z-buffer's machinery around the textbook loop (textbook.hpp): the image
// cut into tiles drawn in parallel, the depth buffer they share, the fast path where it
// runs, --steps' pictures, and the counters.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <type_traits>

#include "algorithms/zbuffer/fast_path.hpp"
#include "algorithms/zbuffer/textbook.hpp"
#include "algorithms/zbuffer/zbuffer.hpp"
#include "renderer/util/memory.hpp"
#include "renderer/util/parallel.hpp"
#include "renderer/util/simd.hpp"

namespace hsr::zbuffer {
namespace {

// --steps on the full frame: the image is drawn as one tile on one thread, and after
// each triangle (about 40 of them, StepRecorder::due) the colour beside the depth so
// far, the triangle just drawn outlined; every pixel a triangle covers is one more
// fragment tested there, for the overdraw the last picture shows.
template <typename Format>
class StepsWatcher final : public TileWatcher {
 public:
  StepsWatcher(const Recording& recording, const Tile<Format>& tile, std::vector<double>& testedAt)
      : recording_(recording), tile_(tile), testedAt_(testedAt) {}

  void drawn(std::size_t index, const ScreenTriangle& tri, SourceLocation where) override {
    const Frame& frame = tile_.frame;
    for (int y = tri.minY; y <= tri.maxY; ++y) rasterizeSpan(tri, y, tri.minX, tri.maxX + 1, [&](int x) { ++testedAt_[tile_.pixel(x, y)]; });
    if (!recording_.steps.due(index, tile_.triangles.size())) return;
    std::vector<float> distances(frame.pixelCount());
    for (int y = 0; y < frame.height; ++y)
      for (int x = 0; x < frame.width; ++x)
        distances[tile_.pixel(x, y)] = tile_.test.distance(frame.ids[tile_.pixel(x, y)], tile_.depth.at(x, y), tile_.geometry.camera);
    const DepthCounts& counts = tile_.test.counts;
    recording_.steps.record("step 2, depth test: triangle " + std::to_string(index + 1) + " of " + std::to_string(tile_.triangles.size()) +
                                " drawn (red); " + std::to_string(counts.written) + " of " + std::to_string(counts.tested) +
                                " fragments so far were nearer and kept",
                            buffersPicture(recording_, tile_.geometry.camera, frame.ids, distances, frame.width, frame.height,
                                           std::span(&tri.triangle, 1)),
                            where);
  }

 private:
  const Recording& recording_;
  const Tile<Format>& tile_;
  std::vector<double>& testedAt_;
};

// Step 3 (decodeRows, textbook.hpp), left for the stage that asks for distances
// (Frame::distances). What it decodes: the textbook loop's depth buffer, kept whole
// (`kept`), or, when that is null, the values the fast path left in the frame's depth,
// which the fast path's own step 3 decodes (decodeRowsFast).
// Without keepDepth the caller has said it reads the ids alone, and nothing is kept.
template <typename Format, bool kFastPathBuilt>
void leaveStep3(Frame& frame, const CameraTransform& camera, const DepthEncoding& encoding,
                std::shared_ptr<const typename Format::Stored[]> kept, int threads, bool keepDepth) {
  if (!keepDepth) {
    frame.leaveUndecoded([](std::span<float>, std::span<const std::uint32_t>) {
      checkFailed("the z-buffer was asked for ids alone (FullFrameOptions::keepDepth), and kept no depth to decode", __FILE__, __LINE__);
    });
    return;
  }
  const int width = frame.width, height = frame.height;
  frame.leaveUndecoded([=, kept = std::move(kept)](std::span<float> distance, std::span<const std::uint32_t> ids) {
    using Stored = typename Format::Stored;
    const Stored* values = kept ? kept.get() : reinterpret_cast<const Stored*>(distance.data());
    const DepthBuffer<const Stored> stored{values, std::size_t(width), 0, 0};
    const DepthTest<Format> test{encoding};
    // One band of rows per worker: a row is too little work to be claimed alone.
    const std::size_t bands = std::size_t(parallelWorkers(std::size_t(height), threads));
    parallelFor(bands, threads, [&](std::size_t band, int) {
      const auto [first, end] = partRange(std::size_t(height), bands, band);
      const std::pair<int, int> rows{int(first), int(end)};
      if constexpr (kFastPathBuilt) {
        if (!kept) return decodeRowsFast(encoding, camera.perspective(), stored, ids, distance, rows);
      }
      decodeRows(test, camera, stored, ids, distance, rows);
    });
  });
}

}  // namespace

void renderFullFrame(const ScreenGeometry& geometry, DepthFormat format, int threads, Frame& frame, Stats& stats,
                     const FullFrameOptions& options) {
  const Recording* recording = options.recording;
  // Binning: each tile gets the triangles whose pixel box overlaps it, in submission
  // order, so that within a tile triangles are drawn in the same order as on one thread.
  // A recording draws the whole image as one tile.
  const TileGrid tiles(frame.width, frame.height, recording ? std::max(frame.width, frame.height) : TileGrid::kTileSize);
  std::vector<std::vector<std::uint32_t>> bins;
  {
    PhaseTimer timer(stats, "binning");
    bins = tiles.bin(geometry.triangles.size(), [&](std::uint32_t i) -> const ScreenTriangle& { return geometry.triangles[i]; });
  }

  PhaseTimer timer(stats, "rasterization");
  withDepthTest(format, options.depthTest, [&]<typename Format>() {
    const DepthEncoding encoding = depthEncoding(format, geometry.camera);
    // The fast path runs float formats with the depth test on, on an x86 CPU with AVX2.
    constexpr bool kFastPathBuilt = kX86 && (std::is_same_v<Format, Float32Depth> || std::is_same_v<Format, ReversedFloat32Depth>);
    // hsr why's pixels are drawn by the textbook loop, where each fragment is tested alone.
    const bool simd = kFastPathBuilt && options.path == Path::simd && cpuHasAvx2() && !options.witness;
    // The textbook's depth buffer covers the whole frame. The fast path draws each tile
    // in a buffer of its own, one per worker, which stays in the cache while the tile is
    // drawn (a tiling GPU keeps its tile in on-chip memory for the same reason): the same
    // values, stored closer. Left uninitialized here: each tile clears its own part, on
    // the thread that will use it.
    const auto depthValues = [&](const TileGrid& grid, int workers) {
      return simd ? std::size_t(parallelWorkers(grid.count(), workers)) * grid.largestTileArea() : frame.pixelCount();
    };
    auto depth = uninitializedArray<typename Format::Stored>(depthValues(tiles, threads));
    std::vector<double> testedAt(recording ? frame.pixelCount() : 0);  // fragments tested per pixel, for the steps
    std::vector<DepthTest<Format>> tileResults(bins.size());
    parallelFor(bins.size(), threads, [&](std::size_t index, int worker) {
      const TileGrid::Rect area = tiles.rect(index);
      using TileDepth = DepthBuffer<typename Format::Stored>;
      DepthTest<Format> test{encoding, options.witness, &geometry.camera};  // on this thread's stack: no cache line shared with other tiles
      const Tile<Format> tile{area, geometry, bins[index],
                              simd ? TileDepth{&depth[std::size_t(worker) * tiles.largestTileArea()], std::size_t(area.x1 - area.x0), area.x0, area.y0}
                                   : TileDepth{depth.get(), std::size_t(frame.width), 0, 0},
                              frame, test};
      std::optional<StepsWatcher<Format>> watcher;
      if (recording) watcher.emplace(*recording, tile, testedAt);
      TileWatcher* watching = watcher ? &*watcher : nullptr;
      if constexpr (kFastPathBuilt) {
        if (simd) drawTileFast(tile, watching);
        else drawTile(tile, watching);
      } else {
        drawTile(tile, watching);
      }
      // The fast path's buffer is reused for this worker's next tile: the tile's depth, as
      // stored, is kept in the frame's (a float format's values are floats) for step 3.
      if (simd && options.keepDepth)
        for (int y = area.y0; y < area.y1; ++y)
          std::copy_n(&tile.depth.at(area.x0, y), area.x1 - area.x0, reinterpret_cast<typename Format::Stored*>(&frame.depth[tile.pixel(area.x0, y)]));
      tileResults[index] = test;
    });
    leaveStep3<Format, kFastPathBuilt>(frame, geometry.camera, encoding, simd ? nullptr : std::shared_ptr<const typename Format::Stored[]>(std::move(depth)), threads,
               options.keepDepth);
    if (recording)
      recording->steps.record("overdraw: fragments tested per pixel (" + std::to_string(tileResults[0].counts.tested) + " in all, " +
                                  std::to_string(tileResults[0].counts.written) + " written)",
                              heatMapPicture(testedAt, frame.width, frame.height, "fragments tested per pixel"));
    for (const auto& test : tileResults) {
      stats.add("fragments tested", test.counts.tested);
      stats.add("fragments written", test.counts.written);
      stats.add(kDepthTiesCounter, test.counts.ties);
      if (simd) stats.add("fragments skipped by block depth", test.counts.skippedByBlockDepth);  // present exactly when the fast path ran
    }
    // What drawing needs. A recording draws the image as one tile, on one thread; it
    // counts what drawing in tiles on one thread needs, so that recording the steps
    // changes no counter.
    const std::size_t counted = recording ? depthValues(TileGrid(frame.width, frame.height), 1) : depthValues(tiles, threads);
    stats.add("depth buffer bytes", static_cast<std::int64_t>(counted * sizeof(typename Format::Stored)));
  });
}

}  // namespace hsr::zbuffer
