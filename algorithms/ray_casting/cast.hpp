// The frame loop every ray-casting variant shares: one ray per pixel center, the part of
// it between the near and far planes, and the variant's answer written into the Frame.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "renderer/camera.hpp"
#include "renderer/conventions.hpp"
#include "renderer/frame.hpp"
#include "renderer/parallel.hpp"
#include "renderer/prepare.hpp"
#include "renderer/stats.hpp"
#include "renderer/steps.hpp"

namespace hsr::ray_casting {

// A pixel's ray and the parameters where it crosses the near and far planes. Points on
// it are origin + t * direction, at view distance d(t) = startDistance + t * slope.
struct PixelRay {
  Ray ray;
  double startDistance, slope;
  double tNear, tFar;

  PixelRay(const CameraTransform& camera, const Ray& pixelRay)
      : ray(pixelRay),
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

// Where castRays records its steps (renderer/steps.hpp), and the scene its ids index.
struct Recording {
  StepRecorder& steps;
  const PreparedScene& scene;
};

// Runs tracer.trace(PixelRay, Counters&) -> Hit for every pixel center, one row per work
// item, and fills frame.ids and frame.depth. Counters is the tracer's own tally (summed
// with +=; cost() is one ray's work in the unit Counters::kCostUnit names); each row
// counts on its own stack, since neighbouring rows' counters share cache lines and other
// threads are writing them. With a recording, the rows run in order on one thread, and a
// step shows the image so far beside each ray's cost as a heat map.
template <typename Tracer>
typename Tracer::Counters castRays(const Tracer& tracer, const CameraTransform& camera, int threads, Frame& frame,
                                   const Recording* recording = nullptr) {
  using Counters = typename Tracer::Counters;
  const auto rows = static_cast<std::size_t>(frame.height);
  std::vector<Counters> rowCounters(rows);
  std::vector<double> costAt(recording ? frame.pixelCount() : 0);
  const auto castRow = [&](std::size_t row, int) {
    Counters counters;
    for (int x = 0; x < frame.width; ++x) {
      const PixelRay pixel(camera, camera.rayThroughPixel(conventions::pixelCenter(x), conventions::pixelCenter(int(row))));
      const double before = recording ? counters.cost() : 0;
      const Hit hit = tracer.trace(pixel, counters);
      const std::size_t index = row * std::size_t(frame.width) + std::size_t(x);
      frame.ids[index] = hit.id;
      frame.depth[index] = hit.id == conventions::kBackgroundId ? std::numeric_limits<float>::infinity()
                                                                : static_cast<float>(pixel.distance(hit.t));
      if (recording) costAt[index] = counters.cost() - before;
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
