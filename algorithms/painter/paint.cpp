// The painter's last step, the same for every order: draw the pieces back to front,
// each over what is already there. With no depth test, a pixel shows whatever was
// drawn there last, so the order alone decides what is visible.
#include "algorithms/painter/paint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "algorithms/effects/effects.hpp"
#include "renderer/conventions.hpp"
#include "renderer/error.hpp"
#include "renderer/parallel.hpp"
#include "renderer/shading.hpp"
#include "renderer/tiles.hpp"

namespace hsr::painter {
namespace {

// A triangle's plane as one corner and the unnormalized normal (b - a) x (c - a): the
// same orientation as ExactPredicates::orient3d, so dot(normal, p - corner) has its sign
// (up to rounding, which both pieces of a split see identically).
struct Plane {
  dvec3 corner, normal;
};

Plane planeOf(const PreparedScene& scene, std::uint32_t triangle) {
  const Triangle& t = scene.triangles()[triangle];
  const dvec3& a = scene.positions()[t[0]];
  return {a, glm::cross(scene.positions()[t[1]] - a, scene.positions()[t[2]] - a)};
}

struct TileCounts {
  std::int64_t writes = 0, cutTests = 0, blended = 0;
  ShadingCounts shading;
};

}  // namespace

void PaintOrder::add(std::uint32_t screenTriangle, const std::vector<Cut>& pieceCuts) {
  pieces.push_back({screenTriangle, static_cast<std::uint32_t>(cuts.size()), static_cast<std::uint32_t>(pieceCuts.size())});
  cuts.insert(cuts.end(), pieceCuts.begin(), pieceCuts.end());
}

SplitPolygon splitPolygon(const std::vector<dvec3>& vertices, const std::vector<int>& sides, const std::vector<double>& heights) {
  SplitPolygon pieces;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (sides[i] >= 0) pieces.positive.push_back(vertices[i]);
    if (sides[i] <= 0) pieces.negative.push_back(vertices[i]);
    if (sides[i] * sides[j] < 0) {
      // The height is affine along the edge: it crosses zero at heights[i] / (heights[i]
      // - heights[j]). Rounding may put that a hair outside the edge (clamped) or make it
      // NaN when both heights round to zero (the midpoint).
      const double ratio = heights[i] / (heights[i] - heights[j]);
      const double along = std::isfinite(ratio) ? std::clamp(ratio, 0.0, 1.0) : 0.5;
      const dvec3 crossing = vertices[i] + along * (vertices[j] - vertices[i]);
      pieces.positive.push_back(crossing);
      pieces.negative.push_back(crossing);
    }
  }
  return pieces;
}

int eyeSide(const PreparedScene& scene, const CameraTransform& camera, std::uint32_t triangle, ExactPredicates& predicates) {
  const Triangle& t = scene.triangles()[triangle];
  const dvec3 &a = scene.positions()[t[0]], &b = scene.positions()[t[1]], &c = scene.positions()[t[2]];
  if (camera.perspective()) return predicates.orient3d(a, b, c, camera.camera().eye);
  return predicates.facing(a, b, c, -camera.forward());
}

Frame paint(const PreparedScene& scene, const ScreenGeometry& geometry, const PaintOrder& order, int threads, Stats& stats,
            const OpaqueBase* base) {
  std::optional<PhaseTimer> timer(std::in_place, stats, base ? "transparency" : "painting");
  Frame frame(scene.width(), scene.height());
  const CameraTransform& camera = geometry.camera;
  const bool blend = scene.scene().effects.transparency;
  const dvec3 background(scene.scene().background);
  HSR_CHECK(!base || blend);

  std::vector<Plane> cutPlanes;
  cutPlanes.reserve(order.cuts.size());
  for (const Cut& cut : order.cuts) cutPlanes.push_back(planeOf(scene, cut.plane));

  const TileGrid tiles(frame.width, frame.height);
  const auto bins = tiles.bin(order.pieces.size(), [&](std::uint32_t i) -> const ScreenTriangle& {
    return geometry.triangles[order.pieces[i].screenTriangle];
  });
  // Blending needs each surface's color when it is drawn, not once per pixel at the end
  // (and so the shadow maps before any surface is drawn).
  std::optional<effects::Lighting> lighting;
  if (blend && !base) lighting.emplace(scene, camera, threads, stats);
  const PixelShader* shader = base ? &base->shader : lighting ? &lighting->shader() : nullptr;
  std::vector<dvec3> blended(blend ? frame.pixelCount() : 0);

  std::vector<TileCounts> counts(bins.size());
  parallelFor(bins.size(), threads, [&](std::size_t tile, int) {
    const auto [x0, y0, x1, y1] = tiles.rect(tile);
    TileCounts count;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const std::size_t pixel = std::size_t(y) * std::size_t(frame.width) + std::size_t(x);
        if (base) {
          frame.ids[pixel] = base->frame.ids[pixel];
          frame.depth[pixel] = base->frame.depth[pixel];
          for (int c = 0; c < 3; ++c) blended[pixel][c] = base->frame.color[4 * pixel + std::size_t(c)] / 255.0;
        } else {
          frame.ids[pixel] = conventions::kBackgroundId;
          frame.depth[pixel] = std::numeric_limits<float>::infinity();
          if (blend) blended[pixel] = background;
        }
      }
    for (const std::uint32_t index : bins[tile]) {
      const Piece& piece = order.pieces[index];
      const ScreenTriangle& tri = geometry.triangles[piece.screenTriangle];
      const Plane own = planeOf(scene, tri.triangle);
      const double opacity = blend ? scene.instanceOf(tri.triangle).opacity : 1.0;
      // A piece's pixels are its triangle's pixels whose point (where the pixel's ray
      // meets the triangle's plane) lies on the kept side of every cut.
      const auto insideCuts = [&](int x, int y) {
        const Ray ray = camera.rayThroughPixel(conventions::pixelCenter(x), conventions::pixelCenter(y));
        const double along = glm::dot(own.normal, own.corner - ray.origin) / glm::dot(own.normal, ray.direction);
        const dvec3 point = ray.origin + along * ray.direction;
        for (std::uint32_t k = 0; k < piece.cutCount; ++k) {
          ++count.cutTests;
          const Plane& plane = cutPlanes[piece.firstCut + k];
          const bool nonNegative = glm::dot(plane.normal, point - plane.corner) >= 0;  // NaN: negative side
          if (nonNegative != order.cuts[piece.firstCut + k].positive) return false;
        }
        return true;
      };
      const int spanBegin = std::max(tri.minX, x0), spanEnd = std::min(tri.maxX + 1, x1);
      for (int y = std::max(tri.minY, y0); y < std::min(tri.maxY + 1, y1); ++y)
        rasterizeSpan(tri, y, spanBegin, spanEnd, [&](int x) {
          if (piece.cutCount != 0 && !insideCuts(x, y)) return;
          const std::size_t pixel = std::size_t(y) * std::size_t(frame.width) + std::size_t(x);
          const float depth = static_cast<float>(camera.distanceFromScreenAffine(tri.depthAt(conventions::pixelCenter(x), conventions::pixelCenter(y))));
          // Over opaque surfaces already drawn, only what lies in front of them shows, and
          // the pixel's id is the nearest surface, whatever order the colors blend in.
          if (base && !(depth < base->frame.depth[pixel])) return;
          ++count.writes;
          if (!base || depth < frame.depth[pixel]) {
            frame.ids[pixel] = tri.triangle + 1;
            frame.depth[pixel] = depth;
          }
          if (!blend) return;
          // Porter and Duff's "over": this surface in front of everything drawn so far.
          blended[pixel] = opacity * shader->shade(tri.triangle, x, y, count.shading) + (1 - opacity) * blended[pixel];
          if (opacity < 1) ++count.blended;
        });
    }
    counts[tile] = count;
  });
  TileCounts total;
  for (const TileCounts& count : counts) {
    total.writes += count.writes;
    total.cutTests += count.cutTests;
    total.blended += count.blended;
    total.shading += count.shading;
  }
  stats.add("pieces painted", static_cast<std::int64_t>(order.pieces.size()));
  stats.add("fragments written", total.writes);
  stats.add("cut tests", total.cutTests);

  if (!blend) {
    timer.reset();
    effects::finishFrame(scene, camera, frame, threads, stats);
    return frame;
  }
  stats.add("blended writes", total.blended);
  total.shading.addTo(stats);
  for (std::size_t pixel = 0; pixel < frame.pixelCount(); ++pixel) {
    for (int c = 0; c < 3; ++c) frame.color[4 * pixel + std::size_t(c)] = channelByte(blended[pixel][c]);
    frame.color[4 * pixel + 3] = 255;
  }
  timer.reset();
  effects::applyImageEffects(scene, camera, frame, threads, stats);
  return frame;
}

}  // namespace hsr::painter
