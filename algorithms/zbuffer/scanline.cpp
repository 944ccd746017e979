// The one-scanline z-buffer: the same depth test with a depth buffer one row high.
// Rows are processed top to bottom; an active-triangle list holds the triangles that
// span the current row, so each row touches only those (Watkins-style row coherence).
#include <algorithm>
#include <limits>

#include "algorithms/zbuffer/textbook.hpp"
#include "algorithms/zbuffer/zbuffer.hpp"
#include "renderer/raster/active_triangles.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr::zbuffer {
namespace {

// A step: the rows finished so far (the rest shown empty), the active triangles outlined
// in red, the row in blue.
void recordRow(const Recording& recording, const CameraTransform& view, const Frame& frame, std::size_t y,
               const ScreenTriangles& triangles, const std::vector<std::uint32_t>& active, std::size_t entering,
               SourceLocation where = SourceLocation::current()) {
  const std::size_t done = (y + 1) * std::size_t(frame.width);
  std::vector<std::uint32_t> ids(frame.ids.begin(), frame.ids.begin() + std::ptrdiff_t(done));
  std::vector<float> depth(frame.depth.begin(), frame.depth.begin() + std::ptrdiff_t(done));
  ids.resize(frame.pixelCount(), conventions::kBackgroundId);
  depth.resize(frame.pixelCount(), std::numeric_limits<float>::infinity());
  std::vector<std::uint32_t> activeTriangles;
  for (const std::uint32_t i : active) activeTriangles.push_back(triangles[i].triangle);
  Image picture = buffersPicture(recording, view, ids, depth, frame.width, frame.height, activeTriangles);
  drawSegment(picture, {0, double(y) + 0.5}, {double(frame.width), double(y) + 0.5}, kSecondHighlight, 1.0);
  recording.steps.record("step 4: row " + std::to_string(y) + " resolved with " + std::to_string(active.size()) +
                             " active triangles (red; " + std::to_string(entering) + " entered on this row)",
                         std::move(picture), where);
}

}  // namespace

void renderScanline(const ScreenGeometry& geometry, DepthFormat format, int threads, Frame& frame, Stats& stats,
                    bool depthTest, const Recording* recording, PixelWitness* witness) {
  PhaseTimer timer(stats, "rasterization");
  const auto& triangles = geometry.triangles;
  frame.leaveUndecoded({});  // step 5 writes the distances, row by row

  // Step 1: a bucket per row of the triangles whose first row it is, in submission order.
  const auto startingAt = trianglesByFirstRow(triangles, frame.height);

  // Rows are split into bands, one per worker; each band keeps its own row buffer and
  // active list, and writes only its own rows.
  // A recording watches the rows in order, on one thread.
  const int workers = recording ? 1 : std::min(resolveThreadCount(threads), frame.height);
  const DepthEncoding encoding = depthEncoding(format, geometry.camera);
  withDepthTest(format, depthTest, [&]<typename Format>() {
    std::vector<DepthTest<Format>> bandResults(static_cast<std::size_t>(workers));
    parallelFor(static_cast<std::size_t>(workers), workers, [&](std::size_t band, int) {
      const auto [first, last] = partRange(static_cast<std::size_t>(frame.height), static_cast<std::size_t>(workers), band);
      std::vector<typename Format::Stored> depthRow(static_cast<std::size_t>(frame.width));
      DepthTest<Format> test{encoding, witness, &geometry.camera};  // on this thread's stack: no cache line shared with other bands
      // Step 2: the active list starts with the triangles that began above the band and reach into it.
      ActiveTriangles activeList(triangles, startingAt, first);
      for (std::size_t y = first; y < last; ++y) {
        // Step 3: retire the triangles that ended above this row, admit those starting on it,
        // keeping submission order so ties resolve exactly as in the full-frame buffer.
        const std::size_t entering = activeList.advanceTo(y);
        const std::vector<std::uint32_t>& active = activeList.active();
        // Step 4: clear the row, then depth-test every active triangle's span on it.
        const std::size_t row = y * std::size_t(frame.width);
        std::fill(depthRow.begin(), depthRow.end(), Format::kFar);
        std::fill(&frame.ids[row], &frame.ids[row] + frame.width, conventions::kBackgroundId);
        test.activeTriangles += static_cast<std::int64_t>(active.size());
        for (const std::uint32_t i : active) {
          const ScreenTriangle& tri = triangles[i];
          rasterizeSpan(tri, int(y), tri.minX, tri.maxX + 1,
                        [&](int x) { test.test(tri, x, int(y), depthRow[std::size_t(x)], frame.ids[row + std::size_t(x)]); });
        }
        // Step 5: the row is final: decode its depth into the frame (the full frame's step 3,
        // decodeRows) before the buffer is reused (the full frame keeps its buffer and
        // decodes when asked; a row is gone by then).
        decodeRows(test, geometry.camera, DepthBuffer<const typename Format::Stored>{depthRow.data(), depthRow.size(), 0, int(y)}, frame.ids,
                   frame.depth, {int(y), int(y) + 1});
        if (recording && recording->steps.due(y, last)) recordRow(*recording, geometry.camera, frame, y, triangles, active, entering);
      }
      bandResults[band] = test;
    });
    for (const auto& test : bandResults) {
      stats.add("fragments tested", test.counts.tested);
      stats.add("fragments written", test.counts.written);
      stats.add(kDepthTiesCounter, test.counts.ties);
      stats.add("active triangles summed over rows", test.activeTriangles);
    }
    stats.add("depth buffer bytes",
              static_cast<std::int64_t>(std::size_t(workers) * std::size_t(frame.width) * sizeof(typename Format::Stored)));
    stats.add(kDistancesDecodedCounter, static_cast<std::int64_t>(frame.pixelCount()));
  });
}

}  // namespace hsr::zbuffer
