// A simulated GPU: what a program sees of a graphics card when it draws and asks
// occlusion queries (the query methods of algorithms/culling/occlusion/queries.hpp).
//
// The card runs commands in the order they are issued, each on the depth buffer the
// commands before it left:
//   draw   an object's triangles, depth-tested and written: the shared geometry stage
//          and rasterizer (pixel centers, fixed point) into a float depth buffer, the
//          z-buffer's "less" test;
//   query  boxes rasterized with the depth test on and writes off (only the faces
//          turned to the eye, so each pixel of a box's outline counts once); the answer
//          is the number of fragments that pass, at or nearer than what the buffer holds.
//
// Each command is carried out at once, on the calling thread, and timed as it runs:
// that is its duration on the card. Two clocks then replay the frame as a CPU and a GPU
// running side by side. The CPU's clock advances by the time spent between commands
// (the culling method's own work); the GPU starts a command when it is issued or when
// it has finished the one before, whichever is later. The frame ends when both are done.
//
// Answers come back late. Which answers a method may read without waiting is decided by
// counting, never by the clocks, so that a walk gives the same pictures on every run:
// an answer is in `latency` frames after its query's frame, or, counting queries, once
// `latency` more queries have been issued after it (or a later frame has begun). A method
// that reads an answer before it is in stalls for it; on the clocks, reading any answer
// waits until the GPU has finished that query, the CPU idle meanwhile. So the cost of a
// stall is measured (the card's queued work, as the rasterizer really took), not assumed.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/geometry/clip.hpp"
#include "renderer/raster/depth.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "renderer/rays/bvh.hpp"
#include "renderer/scene/prepare.hpp"

namespace hsr {

enum class LatencyUnit { frames, queries };

struct QueryLatency {
  int count = 1;
  LatencyUnit unit = LatencyUnit::frames;
};

// A query issued: its answer, which only the GPU reads out (when it is in, or by waiting).
class PendingQuery {
 public:
  PendingQuery() = default;

 private:
  friend class SimulatedGpu;
  std::int64_t frame_ = -1, sequence_ = -1;  // the frame it was issued in, and its place among all queries
  double finishes_ = 0;                      // when the GPU finishes it, on that frame's clock
  std::int64_t passed_ = 0;                  // the fragments that passed
};

// One frame's clocks, in seconds.
struct GpuFrameTimes {
  double cpuBusy = 0;  // the CPU's own work between commands
  double gpuBusy = 0;  // the commands' durations
  double waiting = 0;  // the CPU idle, waiting for answers
  double frame = 0;    // until both have finished
};

// What one frame did.
struct GpuCounts {
  std::int64_t trianglesDrawn = 0, fragmentsWritten = 0;
  std::int64_t boxesQueried = 0, queryFragments = 0, fragmentsPassed = 0;
  std::int64_t stalls = 0;  // answers read before they were in
};

class SimulatedGpu {
 public:
  explicit SimulatedGpu(QueryLatency latency = {}) : latency_(latency) {}
  // How late answers come back from here on (a culling stage sets its knobs' latency).
  void setLatency(QueryLatency latency) { latency_ = latency; }

  // Starts a frame seen by `camera`: a cleared depth buffer of its size, clocks at zero.
  void beginFrame(const CameraTransform& camera);
  // Draws some triangles of one object copy (global triangle ids, all of `instance`).
  void draw(const PreparedScene& scene, std::uint32_t instance, std::span<const std::uint32_t> triangles);
  // Issues a query over the boxes (world space) and returns it, in flight. A box reaching
  // in front of the near plane is cut open there, as a GPU's clipping cuts it: a method
  // must not query one (queries.hpp treats such a box as visible).
  PendingQuery query(std::span<const Aabb> boxes);
  // Whether the answer is in (see above): reading it now does not stall.
  bool answered(const PendingQuery& query) const;
  // The fragments that passed; stalls first if the answer is not in.
  std::int64_t answer(const PendingQuery& query);
  // Ends the frame: its clocks.
  GpuFrameTimes endFrame();

  const GpuCounts& counts() const { return counts_; }
  std::int64_t frameNumber() const { return frame_; }
  // The depth buffer as stored (float depth, 1 = far), row-major, and the frame's size.
  const std::vector<float>& depth() const { return depth_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  using Clock = std::chrono::steady_clock;
  // The CPU's clock, brought up to now.
  void cpuUntilNow();
  // Runs a command on the card: its duration, on the GPU's clock after what it was doing.
  template <typename Work>
  void onGpu(Work&& work);
  // Rasterizes one projected triangle; fragment(index, depth) gets each covered pixel.
  template <typename Fragment>
  void rasterize(const dvec2 pixel[3], const double t[3], Fragment&& fragment);

  QueryLatency latency_;
  std::int64_t frame_ = -1, queriesIssued_ = 0;
  int width_ = 0, height_ = 0;
  std::vector<float> depth_;
  std::vector<ScreenVertex> vertices_;  // scratch: one object's or box's vertices
  std::optional<CameraTransform> camera_;
  std::optional<ClipVolume> volume_;
  DepthEncoding encoding_;
  GpuCounts counts_;
  Clock::time_point mark_;  // when the CPU's clock was last brought up to date
  double cpu_ = 0, gpu_ = 0, waiting_ = 0, gpuBusy_ = 0;
};

}  // namespace hsr
