#include "pipeline/transparency.hpp"

#include <limits>
#include <vector>

#include "renderer/raster/tiles.hpp"

namespace hsr::pipeline {
namespace {

// What one tile counted.
struct TileCounts {
  std::int64_t writes = 0, blended = 0;
  ShadingCounts shading;
};

// The opacity of a fragment's surface, looked up once per run of fragments of one triangle.
class OpacityOf {
 public:
  explicit OpacityOf(const PreparedScene& scene) : scene_(scene) {}
  double operator()(std::uint32_t triangle) {
    if (triangle != triangle_) triangle_ = triangle, opacity_ = scene_.instanceOf(triangle).opacity;
    return opacity_;
  }

 private:
  const PreparedScene& scene_;
  std::uint32_t triangle_ = std::numeric_limits<std::uint32_t>::max();
  double opacity_ = 1;
};

// The blended colors, written to the frame as bytes.
void writeColors(const std::vector<dvec3>& blended, Frame& frame) {
  for (std::size_t pixel = 0; pixel < frame.pixelCount(); ++pixel) {
    for (int c = 0; c < 3; ++c) frame.color[4 * pixel + std::size_t(c)] = channelByte(blended[pixel][c]);
    frame.color[4 * pixel + 3] = 255;
  }
}

// Shading's per-triangle set-up, once, for every surface the pieces paint.
void setUpShading(const PaintedPieces& pieces, PixelShader<float>& shader, int threads, Stats& stats) {
  std::vector<std::uint32_t> triangles;
  triangles.reserve(pieces.order.pieces.size());
  for (const Piece& piece : pieces.order.pieces) triangles.push_back(pieces.geometry.triangles[piece.screenTriangle].triangle);
  shader.setUp(triangles, threads, stats);
}

TileCounts total(const std::vector<TileCounts>& tiles) {
  TileCounts sum;
  for (const TileCounts& tile : tiles) {
    sum.writes += tile.writes;
    sum.blended += tile.blended;
    sum.shading += tile.shading;
  }
  return sum;
}

}  // namespace

void blendInOrder(const PreparedScene& scene, const PaintedPieces& painted, PixelShader<float>& shader, int threads, Frame& frame,
                  Stats& stats) {
  PhaseTimer timer(stats, "transparency");
  setUpShading(painted, shader, threads, stats);
  const dvec3 background(scene.scene().background);
  const TileGrid tiles(frame.width, frame.height);
  std::vector<dvec3> blended(frame.pixelCount());
  std::vector<TileCounts> counts(tiles.count());
  std::vector<OpacityOf> opacities(tiles.count(), OpacityOf(scene));
  paintInOrder(
      scene, painted, tiles, threads,
      [&](std::size_t, const TileGrid::Rect& rect) {
        for (int y = rect.y0; y < rect.y1; ++y)
          for (int x = rect.x0; x < rect.x1; ++x) blended[std::size_t(y) * std::size_t(frame.width) + std::size_t(x)] = background;
      },
      [&](std::size_t tile, const PieceFragment& f) {
        // Porter and Duff's "over": this surface in front of everything drawn so far.
        const double opacity = opacities[tile](f.triangle);
        blended[f.pixel] = opacity * dvec3(shader.shade(f.triangle, f.x, f.y, counts[tile].shading)) + (1 - opacity) * blended[f.pixel];
        if (opacity < 1) ++counts[tile].blended;
      });
  const TileCounts sum = total(counts);
  stats.add("blended writes", sum.blended);
  sum.shading.addTo(stats);
  writeColors(blended, frame);
}

void blendOverOpaque(const PreparedScene& scene, const PaintedPieces& glass, PixelShader<float>& shader, int threads, Frame& frame,
                     Stats& stats) {
  PhaseTimer timer(stats, "transparency");
  setUpShading(glass, shader, threads, stats);
  const PixelBuffer<float> opaqueDepth = frame.distances(&stats);  // then frame.depth holds distances, and the nearest glass goes there
  const TileGrid tiles(frame.width, frame.height);
  std::vector<dvec3> blended(frame.pixelCount());
  std::vector<TileCounts> counts(tiles.count());
  std::vector<OpacityOf> opacities(tiles.count(), OpacityOf(scene));
  const std::int64_t cutTests = paintInOrder(
      scene, glass, tiles, threads,
      [&](std::size_t, const TileGrid::Rect& rect) {
        for (int y = rect.y0; y < rect.y1; ++y)
          for (int x = rect.x0; x < rect.x1; ++x) {
            const std::size_t pixel = std::size_t(y) * std::size_t(frame.width) + std::size_t(x);
            for (int c = 0; c < 3; ++c) blended[pixel][c] = frame.color[4 * pixel + std::size_t(c)] / 255.0;
          }
      },
      [&](std::size_t tile, const PieceFragment& f) {
        // Over opaque surfaces already drawn, only what lies in front of them shows, and
        // the pixel's id is the nearest surface, whatever order the colors blend in.
        if (!(f.depth < opaqueDepth[f.pixel])) return;
        ++counts[tile].writes;
        if (f.depth < frame.depth[f.pixel]) {
          frame.ids[f.pixel] = f.triangle + 1;
          frame.depth[f.pixel] = f.depth;
        }
        const double opacity = opacities[tile](f.triangle);
        blended[f.pixel] = opacity * dvec3(shader.shade(f.triangle, f.x, f.y, counts[tile].shading)) + (1 - opacity) * blended[f.pixel];
        if (opacity < 1) ++counts[tile].blended;
      });
  const TileCounts sum = total(counts);
  stats.add("pieces painted", static_cast<std::int64_t>(glass.order.pieces.size()));
  stats.add("fragments written", sum.writes);
  stats.add("cut tests", cutTests);
  stats.add("blended writes", sum.blended);
  sum.shading.addTo(stats);
  writeColors(blended, frame);
}

}  // namespace hsr::pipeline
