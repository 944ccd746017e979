// The one-scanline z-buffer's promise, measured rather than taken from its own counter:
// at the largest image hsr allows (16384 x 16384), the heap it needs beyond the frame it
// returns is O(width), where a full-frame depth buffer alone would be 1 GiB. And the
// full frame's two paths: the textbook loop's buffer covers the frame, the fast path's
// one tile per worker. The heap is measured by the same meter that gives hsr compare
// its peak memory column (studies/allocation_meter.cpp).
#include <gtest/gtest.h>

#include "renderer/util/simd.hpp"
#include "studies/allocation_meter.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

struct Measured {
  std::int64_t frameBytes = 0;    // what the returned frame holds
  std::int64_t workingBytes = 0;  // the heap's peak during the render beyond that
  std::int64_t depthBufferBytes = 0;  // the z-buffer's own counter
};

Measured measure(const PreparedScene& scene, zbuffer::Variant variant, zbuffer::Path path = zbuffer::Path::scalar) {
  const std::int64_t before = studies::heapBytesInUse();
  studies::resetHeapPeak();
  Stats stats;
  zbuffer::Knobs knobs;
  knobs.variant = variant;
  knobs.path = path;
  const Frame frame = test::render(scene, knobs, 2, stats);
  Measured measured;
  measured.frameBytes = std::int64_t(frame.color.capacity() + frame.depth.capacity() * sizeof(float) +
                                     frame.ids.capacity() * sizeof(std::uint32_t));
  measured.workingBytes = studies::heapPeakBytes() - before - measured.frameBytes;
  measured.depthBufferBytes = stats.counter("depth buffer bytes");
  return measured;
}

TEST(ZBufferMemory, ScanlineNeedsRowsOfDepthEvenAtTheLargestImage) {
  const Scene cube = loadScene(test::sourcePath("scenes/cube.toml"));
  PreparedScene scene(cube);

  // The meter sees a full-frame buffer when there is one (2048 x 2048: 16 MiB of float32).
  scene.setSize(2048, 2048);
  const Measured full = measure(scene, zbuffer::Variant::full);
  EXPECT_GE(full.workingBytes, 2048 * 2048 * 4);
  EXPECT_EQ(full.depthBufferBytes, 2048 * 2048 * 4);
  if (cpuHasAvx2()) {  // the fast path: a 64 x 64 tile of float32 for each of the two workers
    const Measured fast = measure(scene, zbuffer::Variant::full, zbuffer::Path::simd);
    EXPECT_EQ(fast.depthBufferBytes, 2 * 64 * 64 * 4);
    EXPECT_LT(fast.workingBytes, full.workingBytes - 2048 * 2048 * 4 + 2 * 64 * 64 * 4 + (1 << 20));
  }

  scene.setSize(kMaxImageSide, kMaxImageSide);
  const Measured scanline = measure(scene, zbuffer::Variant::scanline);
  EXPECT_EQ(scanline.depthBufferBytes, 2 * kMaxImageSide * 4) << "one float32 row per band, two bands";
  // A row of depth per band, a bucket per row for the active-triangle list, the geometry:
  // about 1 MiB, against the 1 GiB a full-frame buffer would take.
  EXPECT_LT(scanline.workingBytes, 8 << 20);
  std::printf("16384 x 16384 scanline: frame %.0f MiB, working heap %.2f MiB (full-frame depth would be %.0f MiB)\n",
              double(scanline.frameBytes) / (1 << 20), double(scanline.workingBytes) / (1 << 20),
              double(kMaxImageSide) * kMaxImageSide * 4 / (1 << 20));
}

}  // namespace
}  // namespace hsr
