// The simulated GPU (simulated_gpu.hpp).
#include "algorithms/culling/occlusion/simulated_gpu.hpp"

#include <algorithm>
#include <array>

#include "renderer/raster/raster.hpp"
#include "renderer/util/conventions.hpp"

namespace hsr {
namespace {

double seconds(std::chrono::steady_clock::duration duration) { return std::chrono::duration<double>(duration).count(); }

}  // namespace

void SimulatedGpu::beginFrame(const CameraTransform& camera) {
  ++frame_;
  camera_.emplace(camera);
  volume_.emplace(*camera_, clipsFarPlane(DepthFormat::float32, camera.camera().projection));
  encoding_ = depthEncoding(DepthFormat::float32, *camera_);
  width_ = camera.width(), height_ = camera.height();
  depth_.assign(std::size_t(width_) * std::size_t(height_), Float32Depth::kFar);
  counts_ = {};
  cpu_ = gpu_ = waiting_ = gpuBusy_ = 0;
  mark_ = Clock::now();
}

void SimulatedGpu::cpuUntilNow() {
  const Clock::time_point now = Clock::now();
  cpu_ += seconds(now - mark_);
  mark_ = now;
}

template <typename Work>
void SimulatedGpu::onGpu(Work&& work) {
  cpuUntilNow();  // what the CPU did before issuing the command
  work();
  const Clock::time_point end = Clock::now();
  const double duration = seconds(end - mark_);
  mark_ = end;  // the command's own time is the GPU's, not the CPU's
  gpu_ = std::max(gpu_, cpu_) + duration;
  gpuBusy_ += duration;
}

template <typename Fragment>
void SimulatedGpu::rasterize(const dvec2 pixel[3], const double t[3], Fragment&& fragment) {
  ScreenTriangle triangle;
  if (!setupScreenTriangle(pixel, t, width_, height_, 0, triangle)) return;
  for (int y = triangle.minY; y <= triangle.maxY; ++y) {
    const std::size_t row = std::size_t(y) * std::size_t(width_);
    rasterizeSpan(triangle, y, triangle.minX, triangle.maxX + 1, [&](int x) {
      const float z = Float32Depth::store(encoding_.z(triangle.depthAt(conventions::pixelCenter(x), conventions::pixelCenter(y))));
      fragment(row + std::size_t(x), z);
    });
  }
}

void SimulatedGpu::draw(const PreparedScene& scene, std::uint32_t instance, std::span<const std::uint32_t> triangles) {
  onGpu([&] {
    // The vertex stage over the object's vertices, then each triangle through the
    // triangle stage and the rasterizer, as the z-buffer's geometry stage does.
    const Instance& object = scene.instances()[instance];
    vertices_.resize(object.vertexCount);
    for (std::uint32_t v = 0; v < object.vertexCount; ++v)
      vertices_[v] = screenVertex(*camera_, *volume_, scene.positions()[object.firstVertex + v]);
    for (const std::uint32_t t : triangles) {
      const Triangle& corners = scene.triangles()[t];
      const dvec3* const world[3] = {&scene.positions()[corners[0]], &scene.positions()[corners[1]], &scene.positions()[corners[2]]};
      triangleStage(vertices_[corners[0] - object.firstVertex], vertices_[corners[1] - object.firstVertex],
                    vertices_[corners[2] - object.firstVertex], world, *camera_, *volume_, [&](const dvec2 pixel[3], const double depth[3]) {
                      rasterize(pixel, depth, [&](std::size_t at, float z) {
                        if (!Float32Depth::nearer(z, depth_[at])) return;
                        depth_[at] = z;
                        ++counts_.fragmentsWritten;
                      });
                    });
    }
    counts_.trianglesDrawn += std::int64_t(triangles.size());
  });
}

PendingQuery SimulatedGpu::query(std::span<const Aabb> boxes) {
  PendingQuery pending;
  onGpu([&] {
    const dvec3& eye = camera_->camera().eye;
    const dvec3& forward = camera_->forward();
    for (const Aabb& box : boxes) {
      // Corner i has bit 0 set for the high x side, bit 1 for high y, bit 2 for high z.
      std::array<dvec3, 8> world;
      vertices_.resize(8);
      for (std::size_t i = 0; i < 8; ++i) {
        world[i] = {i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z};
        vertices_[i] = screenVertex(*camera_, *volume_, world[i]);
      }
      for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
          // Only the faces turned to the eye: their outlines tile the box's, so a pixel
          // counts once. The eye must be on the outer side of the face's plane (under
          // orthographic projection, the view must run against its outward normal).
          const double plane = side ? box.hi[axis] : box.lo[axis];
          const bool facesEye = camera_->perspective() ? (side ? eye[axis] > plane : eye[axis] < plane)
                                                       : (side ? forward[axis] < 0 : forward[axis] > 0);
          if (!facesEye) continue;
          // The face's corners in order around it: the two other axes' bits walked as a square.
          const int u = 1 << ((axis + 1) % 3), v = 1 << ((axis + 2) % 3), base = side << axis;
          const std::array<int, 4> around = {base, base | u, base | u | v, base | v};
          for (int half = 0; half < 2; ++half) {
            const std::size_t a = std::size_t(around[0]), b = std::size_t(around[std::size_t(1 + half)]),
                              c = std::size_t(around[std::size_t(2 + half)]);
            const dvec3* const corners[3] = {&world[a], &world[b], &world[c]};
            triangleStage(vertices_[a], vertices_[b], vertices_[c], corners, *camera_, *volume_, [&](const dvec2 pixel[3], const double depth[3]) {
              rasterize(pixel, depth, [&](std::size_t at, float z) {
                ++counts_.queryFragments;
                pending.passed_ += !Float32Depth::nearer(depth_[at], z);  // the "less or equal" test: z at or nearer
              });
            });
          }
        }
    }
    counts_.boxesQueried += std::int64_t(boxes.size());
    counts_.fragmentsPassed += pending.passed_;
  });
  pending.frame_ = frame_;
  pending.sequence_ = queriesIssued_++;
  pending.finishes_ = gpu_;
  return pending;
}

bool SimulatedGpu::answered(const PendingQuery& query) const {
  if (latency_.unit == LatencyUnit::frames) return frame_ >= query.frame_ + latency_.count;
  return frame_ > query.frame_ || queriesIssued_ >= query.sequence_ + 1 + latency_.count;
}

std::int64_t SimulatedGpu::answer(const PendingQuery& query) {
  counts_.stalls += !answered(query);
  cpuUntilNow();
  // An answer of this frame is read when the GPU has finished the query: until then the
  // CPU waits. Earlier frames' queries were finished before this frame began.
  if (query.frame_ == frame_ && query.finishes_ > cpu_) {
    waiting_ += query.finishes_ - cpu_;
    cpu_ = query.finishes_;
  }
  return query.passed_;
}

GpuFrameTimes SimulatedGpu::endFrame() {
  cpuUntilNow();
  return {cpu_ - waiting_, gpuBusy_, waiting_, std::max(cpu_, gpu_)};
}

}  // namespace hsr
