// The frame loop every ray-casting variant shares: one ray per pixel center, the part of
// it between the near and far planes, and the variant's answer written into the Frame.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/steps/steps.hpp"
#include "renderer/steps/why.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/parallel.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::ray_casting {

// A pixel's ray and the parameters where it crosses the near and far planes. Points on
// it are origin + t * direction, at view distance d(t) = startDistance + t * slope.
// inverseDirection is 1 / direction per axis (inverseOf), what box tests and the
// watertight test's shear divide by.
struct PixelRay {
  Ray ray;
  dvec3 inverseDirection;
  double startDistance, slope;
  double tNear, tFar;

  PixelRay() = default;
  PixelRay(const CameraTransform& camera, const Ray& pixelRay)
      : ray(pixelRay),
        inverseDirection(inverseOf(pixelRay.direction)),
        startDistance(glm::dot(pixelRay.origin - camera.camera().eye, camera.forward())),
        slope(glm::dot(pixelRay.direction, camera.forward())) {
    const double perDistance = 1.0 / slope;
    tNear = (camera.camera().near - startDistance) * perDistance;
    tFar = (camera.camera().far - startDistance) * perDistance;
  }

  dvec3 at(double t) const { return ray.origin + t * ray.direction; }
  double distance(double t) const { return startDistance + t * slope; }
};

struct Hit {
  std::uint32_t id = conventions::kBackgroundId;  // global triangle index + 1
  double t = std::numeric_limits<double>::infinity();
};

// How far along the ray a BVH traversal still enters boxes: a node is worth entering only
// if its box starts before the nearest hit so far. The box's entry and a triangle's t are
// each rounded, so a triangle lying in its box's face may come out a few ulps before the
// entry: the reach is widened by far more than that (2^-32 of it), so a traversal skips
// nothing the naive variant would take, ties included.
inline constexpr double kReachWidening = 1 + 0x1p-32;
inline double reachOf(const Hit& nearest) { return nearest.t * kReachWidening; }

// What a traversal of a BVH counts (the bvh variant's, and the fast paths' over the
// wide BVH, renderer/rays/wide_bvh.hpp, whose nodes have four children instead of two).
struct TraversalCounters {
  std::int64_t nodesVisited = 0, triangleTests = 0;
  TraversalCounters& operator+=(const TraversalCounters& other) {
    nodesVisited += other.nodesVisited;
    triangleTests += other.triangleTests;
    return *this;
  }
  static constexpr const char* kCostUnit = "BVH nodes visited per ray";
  double cost() const { return double(nodesVisited); }
};

// PixelRay for four pixel centers of a row, a ray per lane, by the same operations in
// the same order (glm::dot's sum taken as it takes it, ((x + y) + z)): the same bits.
struct FourPixelRays {
  FourRays rays;
  Double4 inverseDirection[3];
  Double4 startDistance, slope, tNear, tFar;
  HSR_AVX2 FourPixelRays(const CameraTransform& camera, Double4 centersX, int y);
  HSR_AVX2 PixelRay lane(int i) const;
};

// The PixelRays of pixels x0 .. x0 + count - 1 of row y, into out: four at a time in
// vector lanes where the CPU has AVX2 (the same bits as one at a time: a ray's set-up
// divides four times, and four rays share each vector division). castRays sets up a run
// of a row's rays before tracing them.
void setUpPixelRays(const CameraTransform& camera, int y, int x0, int count, PixelRay* out);
inline constexpr int kRaysSetUpTogether = 64;

// What the frame's depth holds for a ray's answer: its distance along the view axis, or
// +infinity where it met nothing.
inline float frameDepth(std::uint32_t id, double distance) {
  return id == conventions::kBackgroundId ? std::numeric_limits<float>::infinity() : static_cast<float>(distance);
}

// Where castRays records its steps (renderer/steps/steps.hpp), and the scene its ids index.
struct Recording {
  StepRecorder& steps;
  const PreparedScene& scene;
};

// Runs tracer.trace(PixelRay, Counters&, history) -> Hit for every pixel center, one row per work
// item, and fills frame.ids and frame.depth; a tracer that traces several rays at once
// has instead traceRun(camera, y, x0, count, ids, depths, Counters&, costs or null),
// which sets up, traces and writes pixels x0 .. x0 + count - 1 of row y itself. Counters is the tracer's own tally (summed
// with +=; cost() is one ray's work in the unit Counters::kCostUnit names); each row
// counts on its own stack, since neighbouring rows' counters share cache lines and other
// threads are writing them. With a recording, the rows run in order on one thread, and a
// step shows the image so far beside each ray's cost as a heat map. With hsr why's
// pixels (why, renderer/steps/why.hpp), a ray through one of them is traced one at a time
// with its pixel's history, where the tracer records what it met (null at other pixels).
template <typename Tracer>
typename Tracer::Counters castRays(const Tracer& tracer, const CameraTransform& camera, int threads, Frame& frame,
                                   const Recording* recording = nullptr, PixelWitness* why = nullptr) {
  using Counters = typename Tracer::Counters;
  const auto rows = static_cast<std::size_t>(frame.height);
  std::vector<Counters> rowCounters(rows);
  std::vector<double> costAt(recording ? frame.pixelCount() : 0);
  const auto castRow = [&](std::size_t row, int) {
    Counters counters;
    std::array<PixelRay, kRaysSetUpTogether> pixels;
    for (int x0 = 0; x0 < frame.width; x0 += kRaysSetUpTogether) {
      const int count = std::min(kRaysSetUpTogether, frame.width - x0);
      const std::size_t first = row * std::size_t(frame.width) + std::size_t(x0);
      if constexpr (requires { tracer.traceRun(camera, 0, 0, 0, frame.ids.data(), frame.depth.data(), counters, costAt.data()); }) {
        HSR_CHECK(!why && "this tracer keeps no history: hsr why traces with the textbook's");
        tracer.traceRun(camera, int(row), x0, count, &frame.ids[first], &frame.depth[first], counters, recording ? &costAt[first] : nullptr);
      } else {
        setUpPixelRays(camera, int(row), x0, count, pixels.data());
        for (int i = 0; i < count; ++i) {
          const PixelRay& pixel = pixels[std::size_t(i)];
          const double before = recording ? counters.cost() : 0;
          Hit hit;
          if constexpr (requires { tracer.trace(pixel, counters, nullptr); }) {
            hit = tracer.trace(pixel, counters, why ? why->at(x0 + i, int(row)) : nullptr);
          } else {
            HSR_CHECK(!why && "this tracer keeps no history: hsr why traces with the textbook's");
            hit = tracer.trace(pixel, counters);
          }
          frame.ids[first + std::size_t(i)] = hit.id;
          frame.depth[first + std::size_t(i)] = frameDepth(hit.id, pixel.distance(hit.t));
          if (recording) costAt[first + std::size_t(i)] = counters.cost() - before;
        }
      }
    }
    rowCounters[row] = counters;
  };
  if (!recording) {
    parallelFor(rows, threads, castRow);
  } else {
    for (std::size_t row = 0; row < rows; ++row) {
      castRow(row, 0);
      if (!recording->steps.due(row, rows)) continue;
      // The rows not cast yet show as background, and as no cost.
      std::vector<std::uint32_t> ids(frame.ids.begin(), frame.ids.begin() + std::ptrdiff_t((row + 1) * std::size_t(frame.width)));
      ids.resize(frame.pixelCount(), conventions::kBackgroundId);
      Image image = surfacePicture(recording->scene, camera, ids, frame.width, frame.height);
      drawSegment(image, {0, double(row) + 0.5}, {double(frame.width), double(row) + 0.5}, kSecondHighlight, 1.0);
      recording->steps.record("row " + std::to_string(row + 1) + " of " + std::to_string(rows) +
                                  " cast (blue): one ray per pixel, the nearest hit wins",
                              besideEachOther({image, heatMapPicture(costAt, frame.width, frame.height, Counters::kCostUnit)}));
    }
  }
  Counters total;
  for (const Counters& counters : rowCounters) total += counters;
  return total;
}

}  // namespace hsr::ray_casting
