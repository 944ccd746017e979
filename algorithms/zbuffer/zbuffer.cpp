// The full-frame z-buffer, and the steps both variants share.
#include "algorithms/zbuffer/zbuffer.hpp"

#include <algorithm>
#include <memory>

#include "renderer/parallel.hpp"
#include "renderer/shading.hpp"

namespace hsr::zbuffer {
namespace {

constexpr int kTileSize = 64;  // pixels per side of a screen tile: one thread owns a tile at a time

}  // namespace

void renderFullFrame(const ScreenGeometry& geometry, DepthFormat format, int threads, Frame& frame, Stats& stats) {
  const int tilesX = (frame.width + kTileSize - 1) / kTileSize;
  const int tilesY = (frame.height + kTileSize - 1) / kTileSize;

  // Binning: each tile gets the triangles whose pixel box overlaps it, in submission
  // order, so that within a tile triangles are drawn in the same order as on one thread.
  std::vector<std::vector<std::uint32_t>> bins(std::size_t(tilesX) * std::size_t(tilesY));
  {
    PhaseTimer timer(stats, "binning");
    for (std::uint32_t i = 0; i < geometry.triangles.size(); ++i) {
      const ScreenTriangle& tri = geometry.triangles[i];
      for (int ty = tri.minY / kTileSize; ty <= tri.maxY / kTileSize; ++ty)
        for (int tx = tri.minX / kTileSize; tx <= tri.maxX / kTileSize; ++tx) bins[std::size_t(ty * tilesX + tx)].push_back(i);
    }
  }

  PhaseTimer timer(stats, "rasterization");
  withDepthFormat(format, [&]<typename Format>() {
    const DepthEncoding encoding = depthEncoding(format, geometry.camera);
    // Left uninitialized here: each tile clears its own part, on the thread that will use it.
    const auto depth = std::make_unique_for_overwrite<typename Format::Stored[]>(frame.pixelCount());
    std::vector<DepthTest<Format>> tileResults(bins.size());
    parallelFor(bins.size(), threads, [&](std::size_t tile, int) {
      const int tileX0 = int(tile % std::size_t(tilesX)) * kTileSize, tileY0 = int(tile / std::size_t(tilesX)) * kTileSize;
      const int tileX1 = std::min(tileX0 + kTileSize, frame.width), tileY1 = std::min(tileY0 + kTileSize, frame.height);
      const auto pixel = [&](int x, int y) { return std::size_t(y) * std::size_t(frame.width) + std::size_t(x); };
      DepthTest<Format> test{encoding};  // on this thread's stack: no cache line shared with other tiles
      // Step 1: clear the depth buffer to the far end of the format, and the ids to background.
      for (int y = tileY0; y < tileY1; ++y) {
        std::fill(&depth[pixel(tileX0, y)], &depth[pixel(tileX0, y)] + (tileX1 - tileX0), Format::kFar);
        std::fill(&frame.ids[pixel(tileX0, y)], &frame.ids[pixel(tileX0, y)] + (tileX1 - tileX0), conventions::kBackgroundId);
      }
      // Step 2: for every triangle and every pixel it covers, keep the fragment if it is
      // nearer than what the pixel holds.
      for (const std::uint32_t index : bins[tile]) {
        const ScreenTriangle& tri = geometry.triangles[index];
        const int x0 = std::max(tri.minX, tileX0), x1 = std::min(tri.maxX + 1, tileX1);
        for (int y = std::max(tri.minY, tileY0); y < std::min(tri.maxY + 1, tileY1); ++y) {
          const std::size_t row = pixel(0, y);
          rasterizeSpan(tri, y, x0, x1, [&](int x) {
            if (test.nearer(tri, x, y, depth[row + std::size_t(x)])) frame.ids[row + std::size_t(x)] = tri.triangle + 1;
          });
        }
      }
      // Step 3: the frame's depth is what the format stored, decoded to a view distance.
      for (int y = tileY0; y < tileY1; ++y)
        for (int x = tileX0; x < tileX1; ++x) frame.depth[pixel(x, y)] = test.distance(frame.ids[pixel(x, y)], depth[pixel(x, y)], geometry.camera);
      tileResults[tile] = test;
    });
    for (const auto& test : tileResults) {
      stats.add("fragments tested", test.tested);
      stats.add("fragments written", test.written);
    }
    stats.add("depth buffer bytes", static_cast<std::int64_t>(frame.pixelCount() * sizeof(typename Format::Stored)));
  });
}

Frame run(const PreparedScene& scene, const Knobs& knobs, int threads, Stats& stats) {
  Frame frame(scene.width(), scene.height());
  const bool clipFar = clipsFarPlane(knobs.depthFormat, scene.scene().camera.projection);
  const ScreenGeometry geometry = buildScreenTriangles(scene, clipFar, threads, stats);
  if (knobs.variant == Variant::full)
    renderFullFrame(geometry, knobs.depthFormat, threads, frame, stats);
  else
    renderScanline(geometry, knobs.depthFormat, threads, frame, stats);
  shadeFrame(scene, geometry.camera, frame, threads, stats);
  return frame;
}

}  // namespace hsr::zbuffer
