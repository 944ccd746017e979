// The peer benchmark for ray casting: the same primary rays (one per pixel center,
// from CameraTransform::rayThroughPixel), the same scene and the same thread count in
// hsr's bvh variant and in Intel Embree's rtcIntersect1 (single rays), timed in one
// run, interleaved, and compared pixel by pixel on the triangle each ray hits.
//
//   build/bench/embree_peer [--threads N] [--runs R] [dragons counters ...]
//
// Both sides do the same work per ray: generate it, find the nearest hit between the
// near and far planes, and store the hit triangle. Embree gets float vertices and rays
// (its native precision) and builds with its default quality; hsr traces in double.
// Rows are spread over threads by the same parallelFor. Embree is used here only, never
// by the algorithms.
#include <embree3/rtcore.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "algorithms/ray_casting/ray_casting.hpp"
#include "peer_timing.hpp"
#include "renderer/camera.hpp"
#include "renderer/memory.hpp"
#include "renderer/parallel.hpp"

namespace {

constexpr int kWidth = 1280, kHeight = 720;

using hsr::bench::millisecondsOf;
using hsr::bench::Timing;

class EmbreeScene {
 public:
  explicit EmbreeScene(const hsr::PreparedScene& scene) {
    device_ = rtcNewDevice(nullptr);
    scene_ = rtcNewScene(device_);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), scene.positions().size()));
    for (std::size_t i = 0; i < scene.positions().size(); ++i)
      for (int axis = 0; axis < 3; ++axis) vertices[3 * i + axis] = static_cast<float>(scene.positions()[i][axis]);
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), scene.triangleCount()));
    for (std::size_t i = 0; i < scene.triangleCount(); ++i)
      for (int corner = 0; corner < 3; ++corner) indices[3 * i + corner] = scene.triangles()[i][corner];
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    buildMilliseconds_ = millisecondsOf([&] { rtcCommitScene(scene_); });
  }
  ~EmbreeScene() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  double buildMilliseconds() const { return buildMilliseconds_; }

  // ids as hsr writes them: triangle index + 1, 0 for no hit.
  void trace(const hsr::CameraTransform& camera, int threads, std::vector<std::uint32_t>& ids) const {
    hsr::parallelFor(std::size_t(kHeight), threads, [&](std::size_t row, int) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      for (int x = 0; x < kWidth; ++x) {
        const hsr::Ray ray = camera.rayThroughPixel(x + 0.5, double(row) + 0.5);
        const double startDistance = glm::dot(ray.origin - camera.camera().eye, camera.forward());
        const double slope = glm::dot(ray.direction, camera.forward());
        RTCRayHit hit{};
        hit.ray.org_x = float(ray.origin.x), hit.ray.org_y = float(ray.origin.y), hit.ray.org_z = float(ray.origin.z);
        hit.ray.dir_x = float(ray.direction.x), hit.ray.dir_y = float(ray.direction.y), hit.ray.dir_z = float(ray.direction.z);
        hit.ray.tnear = float((camera.camera().near - startDistance) / slope);
        hit.ray.tfar = float((camera.camera().far - startDistance) / slope);
        hit.ray.mask = ~0u;
        hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &context, &hit);
        ids[row * kWidth + std::size_t(x)] = hit.hit.geomID == RTC_INVALID_GEOMETRY_ID ? 0 : hit.hit.primID + 1;
      }
    });
  }

 private:
  RTCDevice device_;
  RTCScene scene_;
  double buildMilliseconds_ = 0;
};

}  // namespace

int main(int argc, char** argv) try {
  hsr::keepFreedMemoryForReuse();
  int threads = 1, runs = 9;
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--threads" && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else if (argument == "--runs" && i + 1 < argc) {
      runs = std::max(3, std::atoi(argv[++i]));
    } else if (!argument.empty() && argument[0] != '-') {
      names.push_back(argument);
    } else {
      std::fprintf(stderr, "usage: embree_peer [--threads N] [--runs R] [scene ...]\n");
      return 2;
    }
  }
  if (names.empty()) names = {"dragons", "counters"};
  std::printf("hsr ray_casting bvh vs Embree %d.%d.%d rtcIntersect1, %dx%d primary rays, %d thread(s), %d runs after a warm-up\n",
              RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH, kWidth, kHeight, threads, runs);
  for (const std::string& name : names) {
    const hsr::Scene scene = hsr::loadScene(std::string(HSR_SOURCE_DIR) + "/scenes/" + name + ".toml");
    hsr::PreparedScene prepared(scene);
    prepared.setSize(kWidth, kHeight);
    const hsr::CameraTransform camera(scene.camera, kWidth, kHeight);
    const EmbreeScene embree(prepared);
    hsr::Stats buildStats;
    const double hsrBuild = millisecondsOf([&] { prepared.triangleBvh(buildStats); });

    const hsr::ray_casting::Knobs knobs;  // the bvh variant
    // Both write into buffers allocated once.
    hsr::Visibility visibility{hsr::Frame(kWidth, kHeight), std::nullopt};
    const hsr::Frame& ours = visibility.frame;
    std::vector<std::uint32_t> theirs(std::size_t(kWidth) * kHeight);
    hsr::Stats warmUp;
    hsr::ray_casting::visibility({prepared, camera, nullptr, threads, warmUp}, knobs, visibility);
    embree.trace(camera, threads, theirs);
    Timing oursMs, theirsMs;
    for (int run = 0; run < runs; ++run) {  // interleaved, so both see the same machine load
      oursMs.milliseconds.push_back(millisecondsOf([&] {
        hsr::Stats stats;
        hsr::ray_casting::visibility({prepared, camera, nullptr, threads, stats}, knobs, visibility);
      }));
      theirsMs.milliseconds.push_back(millisecondsOf([&] { embree.trace(camera, threads, theirs); }));
    }
    std::int64_t agree = 0, covered = 0;
    for (std::size_t i = 0; i < theirs.size(); ++i) {
      if (ours.ids[i] == 0 && theirs[i] == 0) continue;
      ++covered;
      agree += ours.ids[i] == theirs[i];
    }
    const double rays = double(kWidth) * kHeight;
    std::printf("%s (%zu triangles; build: hsr SAH %.1f ms, %zu nodes; Embree %.1f ms)\n", name.c_str(),
                prepared.triangleCount(), hsrBuild, prepared.triangleBvh(buildStats).nodes().size(), embree.buildMilliseconds());
    std::printf("  hsr    median %7.2f ms  %6.2f Mrays/s\n", oursMs.median(), rays / oursMs.median() / 1e3);
    std::printf("  Embree median %7.2f ms  %6.2f Mrays/s\n", theirsMs.median(), rays / theirsMs.median() / 1e3);
    std::printf("  throughput ratio hsr/Embree %.2f\n", theirsMs.median() / oursMs.median());
    std::printf("  pixels hit by either: %lld, same triangle %.4f%%\n", static_cast<long long>(covered),
                100.0 * double(agree) / double(std::max<std::int64_t>(1, covered)));
  }
  return 0;
} catch (const hsr::InputError& error) {
  std::fprintf(stderr, "embree_peer: %s\n", error.what());
  return 2;
}
