// The peer benchmark for ray casting: the same primary rays (one per pixel center,
// from CameraTransform::rayThroughPixel), the same scene and the same thread count in
// hsr's bvh variant and in Intel Embree, timed in one run, interleaved, and compared
// pixel by pixel on the triangle each ray hits:
//   hsr path=scalar   the textbook traversal of the binary BVH, one ray at a time
//   hsr path=simd     one ray at a time through the eight-wide BVH (AVX2)
//   hsr path=packet   eight neighbouring rays of a row together
//   Embree 1, 8, 16   rtcIntersect1 (single rays), rtcIntersect8 and rtcIntersect16
//                     (packets of 8 and 16 neighbouring rays of a row, marked coherent)
//
//   build/bench/embree_peer [--threads N] [--runs R] [dragons counters city ...]
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
#include <functional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "algorithms/ray_casting/ray_casting.hpp"
#include "peer_timing.hpp"
#include "renderer/geometry/camera.hpp"
#include "renderer/util/memory.hpp"
#include "renderer/util/parallel.hpp"

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

  // ids as hsr writes them: triangle index + 1, 0 for no hit; `width` rays at a time
  // (1: rtcIntersect1; 8, 16: a packet of that many neighbours of a row).
  void trace(const hsr::CameraTransform& camera, int threads, int width, std::vector<std::uint32_t>& ids) const {
    switch (width) {
      case 1: return traceRows<1>(camera, threads, ids);
      case 8: return traceRows<8>(camera, threads, ids);
      default: return traceRows<16>(camera, threads, ids);
    }
  }

 private:
  template <int kWidthOfCall>
  void traceRows(const hsr::CameraTransform& camera, int threads, std::vector<std::uint32_t>& ids) const {
    using RayHits = std::conditional_t<kWidthOfCall == 1, RTCRayHit, std::conditional_t<kWidthOfCall == 8, RTCRayHit8, RTCRayHit16>>;
    hsr::parallelFor(std::size_t(kHeight), threads, [&](std::size_t row, int) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      if (kWidthOfCall > 1) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      for (int x0 = 0; x0 < kWidth; x0 += kWidthOfCall) {
        alignas(64) RayHits hits{};
        alignas(64) int valid[kWidthOfCall];
        for (int lane = 0; lane < kWidthOfCall; ++lane) {
          const int x = x0 + lane;
          valid[lane] = x < kWidth ? -1 : 0;
          const hsr::Ray ray = camera.rayThroughPixel(std::min(x, kWidth - 1) + 0.5, double(row) + 0.5);
          const double startDistance = glm::dot(ray.origin - camera.camera().eye, camera.forward());
          const double slope = glm::dot(ray.direction, camera.forward());
          const float tNear = float((camera.camera().near - startDistance) / slope), tFar = float((camera.camera().far - startDistance) / slope);
          if constexpr (kWidthOfCall == 1) {
            hits.ray.org_x = float(ray.origin.x), hits.ray.org_y = float(ray.origin.y), hits.ray.org_z = float(ray.origin.z);
            hits.ray.dir_x = float(ray.direction.x), hits.ray.dir_y = float(ray.direction.y), hits.ray.dir_z = float(ray.direction.z);
            hits.ray.tnear = tNear, hits.ray.tfar = tFar, hits.ray.mask = ~0u;
            hits.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          } else {
            hits.ray.org_x[lane] = float(ray.origin.x), hits.ray.org_y[lane] = float(ray.origin.y), hits.ray.org_z[lane] = float(ray.origin.z);
            hits.ray.dir_x[lane] = float(ray.direction.x), hits.ray.dir_y[lane] = float(ray.direction.y), hits.ray.dir_z[lane] = float(ray.direction.z);
            hits.ray.tnear[lane] = tNear, hits.ray.tfar[lane] = tFar, hits.ray.mask[lane] = ~0u;
            hits.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
          }
        }
        if constexpr (kWidthOfCall == 1) rtcIntersect1(scene_, &context, &hits);
        else if constexpr (kWidthOfCall == 8) rtcIntersect8(valid, scene_, &context, &hits);
        else rtcIntersect16(valid, scene_, &context, &hits);
        for (int lane = 0; lane < kWidthOfCall && x0 + lane < kWidth; ++lane) {
          unsigned geometry, primitive;
          if constexpr (kWidthOfCall == 1) geometry = hits.hit.geomID, primitive = hits.hit.primID;
          else geometry = hits.hit.geomID[lane], primitive = hits.hit.primID[lane];
          ids[row * kWidth + std::size_t(x0 + lane)] = geometry == RTC_INVALID_GEOMETRY_ID ? 0 : primitive + 1;
        }
      }
    });
  }

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
  if (names.empty()) names = {"dragons", "counters", "city"};
  std::printf("hsr ray_casting bvh vs Embree %d.%d.%d, %dx%d primary rays, %d thread(s), %d runs after a warm-up\n",
              RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH, kWidth, kHeight, threads, runs);
  for (const std::string& name : names) {
    const hsr::Scene scene = hsr::loadScene(std::string(HSR_SOURCE_DIR) + "/scenes/" + name + ".toml");
    hsr::PreparedScene prepared(scene);
    prepared.setSize(kWidth, kHeight);
    const hsr::CameraTransform camera(scene.camera, kWidth, kHeight);
    const EmbreeScene embree(prepared);
    hsr::Stats buildStats;
    const double hsrBuild = millisecondsOf([&] { prepared.wideTriangleBvh(buildStats); });

    // Each side writes into buffers allocated once; one warm-up of each first.
    struct Side {
      std::string name;
      std::function<void()> run;
      std::span<const std::uint32_t> ids;
      Timing milliseconds;
    };
    std::vector<Side> sides;
    std::vector<hsr::Visibility> ours;
    ours.reserve(3);
    for (const auto& [path, pathName] : {std::pair(hsr::ray_casting::Path::scalar, "scalar"), std::pair(hsr::ray_casting::Path::simd, "simd"),
                                         std::pair(hsr::ray_casting::Path::packet, "packet")}) {
      hsr::ray_casting::Knobs knobs;  // the bvh variant
      knobs.path = path;
      hsr::Visibility& visibility = ours.emplace_back(hsr::Visibility{hsr::Frame(kWidth, kHeight), std::nullopt});
      sides.push_back({std::string("hsr path=") + pathName, [&, knobs] {
                         hsr::Stats stats;
                         hsr::ray_casting::visibility({prepared, camera, nullptr, threads, stats}, knobs, visibility);
                       },
                       visibility.frame.ids, {}});
    }
    std::vector<std::vector<std::uint32_t>> theirs(3, std::vector<std::uint32_t>(std::size_t(kWidth) * kHeight));
    for (const int width : {1, 8, 16}) {
      std::vector<std::uint32_t>& ids = theirs[width == 1 ? 0 : width == 8 ? 1 : 2];
      sides.push_back({"Embree rtcIntersect" + std::to_string(width), [&, width] { embree.trace(camera, threads, width, ids); }, ids, {}});
    }
    for (Side& side : sides) side.run();
    for (int run = 0; run < runs; ++run)  // interleaved, so every side sees the same machine load
      for (Side& side : sides) side.milliseconds.milliseconds.push_back(millisecondsOf(side.run));

    const double rays = double(kWidth) * kHeight;
    std::printf("%s (%zu triangles; build: hsr SAH and eight-wide %.1f ms, %zu wide nodes; Embree %.1f ms)\n", name.c_str(),
                prepared.triangleCount(), hsrBuild, prepared.wideTriangleBvh(buildStats).nodes().size(), embree.buildMilliseconds());
    for (Side& side : sides) {
      std::int64_t agree = 0, covered = 0;
      const std::span<const std::uint32_t> textbook = sides.front().ids;
      for (std::size_t i = 0; i < textbook.size(); ++i) {
        if (side.ids[i] == 0 && textbook[i] == 0) continue;
        ++covered;
        agree += side.ids[i] == textbook[i];
      }
      std::printf("  %-22s median %7.2f ms [%.2f-%.2f]  %6.2f Mrays/s  same triangle as path=scalar: %.4f%% of %lld\n", side.name.c_str(),
                  side.milliseconds.median(), side.milliseconds.min(), side.milliseconds.max(), rays / side.milliseconds.median() / 1e3,
                  100.0 * double(agree) / double(std::max<std::int64_t>(1, covered)), static_cast<long long>(covered));
    }
    const auto ratio = [&](std::size_t ours_, std::size_t theirs_) { return sides[theirs_].milliseconds.median() / sides[ours_].milliseconds.median(); };
    std::printf("  throughput hsr/Embree: scalar/1 %.2f, simd/1 %.2f, packet/8 %.2f, packet/16 %.2f\n", ratio(0, 3), ratio(1, 3), ratio(2, 4),
                ratio(2, 5));
  }
  return 0;
} catch (const hsr::InputError& error) {
  std::fprintf(stderr, "embree_peer: %s\n", error.what());
  return 2;
}
