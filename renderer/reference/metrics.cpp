#include "renderer/reference/metrics.hpp"

#include <algorithm>
#include <cmath>

#include "renderer/util/conventions.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr {

SurfaceError surfaceError(const Frame& frame, const ReferenceImage& reference) {
  const Frame& truth = reference.frame;
  HSR_CHECK(frame.width == truth.width && frame.height == truth.height);
  SurfaceError error;
  const PixelBuffer<float>& distance = frame.distances();
  double depthSum = 0;
  for (std::size_t pixel = 0; pixel < frame.pixelCount(); ++pixel) {
    if (reference.ambiguous[pixel]) {
      ++error.ambiguousPixels;
    } else {
      ++error.comparedPixels;
      error.wrongPixels += frame.ids[pixel] != truth.ids[pixel];
    }
    if (frame.ids[pixel] == truth.ids[pixel] && truth.ids[pixel] != conventions::kBackgroundId) {
      const double difference = std::abs(double(distance[pixel]) - double(truth.depth[pixel]));
      ++error.depthPixels;
      depthSum += difference;
      error.depthErrorMax = std::max(error.depthErrorMax, difference);
    }
  }
  if (error.comparedPixels > 0) error.pixelError = double(error.wrongPixels) / double(error.comparedPixels);
  if (error.depthPixels > 0) error.depthErrorMean = depthSum / double(error.depthPixels);
  return error;
}

namespace {

// The reference's image dimmed to grey, the ground both heat maps draw on.
std::vector<std::uint8_t> dimmedReference(const Frame& truth) {
  std::vector<std::uint8_t> image(4 * truth.pixelCount());
  for (std::size_t pixel = 0; pixel < truth.pixelCount(); ++pixel) {
    const std::uint8_t* rgb = &truth.color[4 * pixel];
    const auto grey = static_cast<std::uint8_t>(40 + (rgb[0] * 30 + rgb[1] * 59 + rgb[2] * 11) / 100 / 3);
    std::uint8_t* out = &image[4 * pixel];
    out[0] = out[1] = out[2] = grey;
    out[3] = 255;
  }
  return image;
}

// The heat maps' colours: what is wrong red, a tie blue, laid over the grey by `weight`
// (1: the colour itself).
constexpr std::uint8_t kWrongRed[3] = {255, 30, 30}, kTieBlue[3] = {40, 90, 255};
void paint(std::uint8_t* out, const std::uint8_t (&colour)[3], double weight = 1) {
  for (int c = 0; c < 3; ++c) out[c] = static_cast<std::uint8_t>(std::lround(out[c] * (1 - weight) + colour[c] * weight));
}

}  // namespace

std::vector<std::uint8_t> coverageHeatMap(const PixelShares& measured, const PixelShares& exact, const ReferenceImage& reference) {
  std::vector<std::uint8_t> image = dimmedReference(reference.frame);
  HSR_CHECK(exact.first.size() == reference.frame.pixelCount() + 1 && measured.first.size() == exact.first.size());
  for (std::size_t pixel = 0; pixel < reference.frame.pixelCount(); ++pixel) {
    std::uint8_t* out = &image[4 * pixel];
    if (!exact.tied.empty() && exact.tied[pixel]) {
      paint(out, kTieBlue);
      continue;
    }
    const double distance = coverageDistance(measured, exact, pixel);
    if (distance > 0) paint(out, kWrongRed, 0.25 + 0.75 * distance);
  }
  return image;
}

std::vector<std::uint8_t> errorHeatMap(const Frame& frame, const ReferenceImage& reference) {
  const Frame& truth = reference.frame;
  HSR_CHECK(frame.width == truth.width && frame.height == truth.height);
  std::vector<std::uint8_t> image = dimmedReference(truth);
  for (std::size_t pixel = 0; pixel < frame.pixelCount(); ++pixel) {
    std::uint8_t* out = &image[4 * pixel];
    if (reference.ambiguous[pixel]) paint(out, kTieBlue);
    else if (frame.ids[pixel] != truth.ids[pixel]) paint(out, kWrongRed);
  }
  return image;
}

CullingError cullingError(std::span<const std::uint8_t> kept, std::span<const std::uint8_t> visible) {
  HSR_CHECK(kept.size() == visible.size());
  CullingError error;
  error.items = static_cast<std::int64_t>(kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    error.visible += visible[i] != 0;
    error.kept += kept[i] != 0;
    error.falseCulls += visible[i] && !kept[i];
    error.wastedWork += kept[i] && !visible[i];
  }
  return error;
}

std::vector<std::uint8_t> objectsWithAny(const PreparedScene& scene, std::span<const std::uint8_t> triangleFlags) {
  HSR_CHECK(triangleFlags.size() == scene.triangleCount());
  std::vector<std::uint8_t> objects(scene.instances().size(), 0);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const Instance& object = scene.instances()[i];
    const auto begin = triangleFlags.begin() + object.firstTriangle;
    objects[i] = std::any_of(begin, begin + object.triangleCount, [](std::uint8_t flag) { return flag != 0; });
  }
  return objects;
}

std::vector<std::uint8_t> visibleTriangles(const ReferenceImage& reference, std::size_t triangleCount) {
  std::vector<std::uint8_t> visible(triangleCount, 0);
  for (std::uint32_t id : reference.frame.ids)
    if (id != conventions::kBackgroundId) visible[id - 1] = 1;
  return visible;
}

namespace {

// Total length of the intersection of two sorted lists of disjoint intervals.
double overlap(const std::vector<Interval>& a, const std::vector<Interval>& b) {
  double total = 0;
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    total += std::max(0.0, std::min(a[i].end, b[j].end) - std::max(a[i].begin, b[j].begin));
    if (a[i].end < b[j].end) ++i; else ++j;
  }
  return total;
}

double length(const std::vector<Interval>& intervals) {
  double total = 0;
  for (const Interval& interval : intervals) total += interval.end - interval.begin;
  return total;
}

}  // namespace

LineError lineError(std::span<const EdgeVisibility> drawn, std::span<const EdgeVisibility> reference) {
  HSR_CHECK(drawn.size() == reference.size());
  LineError error;
  for (std::size_t edge = 0; edge < drawn.size(); ++edge) {
    const double pixels = reference[edge].lengthPixels;
    const double both = overlap(drawn[edge].visible, reference[edge].visible);
    const double truthLength = length(reference[edge].visible);
    error.visibleLength += pixels * truthLength;
    error.wronglyDrawn += pixels * (length(drawn[edge].visible) - both);
    error.wronglyHidden += pixels * (truthLength - both);
  }
  if (error.visibleLength > 0) error.error = (error.wronglyDrawn + error.wronglyHidden) / error.visibleLength;
  return error;
}

ShadowError shadowError(const PreparedScene& scene, const Frame& frame, const ShadowTest& tested, const ShadowTest& exact,
                        int threads) {
  const CameraTransform camera(scene.scene().camera, frame.width, frame.height);
  const auto& lights = scene.scene().lights;
  PixelShader<double> shader(scene, camera, &exact);
  Stats unused;
  shader.setUpShownIn(frame, threads, unused);
  std::vector<ShadowError> rows(static_cast<std::size_t>(frame.height));
  parallelFor(rows.size(), threads, [&](std::size_t row, int) {
    ShadowError& error = rows[row];
    for (int x = 0; x < frame.width; ++x) {
      const std::uint32_t id = frame.ids[row * std::size_t(frame.width) + std::size_t(x)];
      if (id == conventions::kBackgroundId) continue;
      const SurfacePoint point = shader.surfacePoint(id - 1, x, static_cast<int>(row));
      for (std::size_t light = 0; light < lights.size(); ++light) {
        if (glm::dot(point.normal, towardLight(lights[light], point.position)) <= 0) continue;
        ++error.lookups;
        const bool shadowed = tested.shadowed(light, point.position, id - 1);
        const bool truly = exact.shadowed(light, point.position, id - 1);
        error.falselyShadowed += shadowed && !truly;
        error.falselyLit += !shadowed && truly;
      }
    }
  });
  ShadowError total;
  for (const ShadowError& row : rows) {
    total.lookups += row.lookups;
    total.falselyShadowed += row.falselyShadowed;
    total.falselyLit += row.falselyLit;
  }
  total.differing = total.falselyShadowed + total.falselyLit;
  total.fraction = total.lookups ? double(total.differing) / double(total.lookups) : 0.0;
  return total;
}

}  // namespace hsr
