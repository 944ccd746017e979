// Painting in order: the last step of every list-priority method (the painter's sort,
// Newell's and the BSP tree's orders, and the sorted transparency pass). An order is a
// back-to-front list of pieces of screen triangles; painting it draws each piece over
// what is already there, with no depth test, so the order alone decides what shows.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/raster/raster.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "renderer/raster/tiles.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr {

// A cut keeps the part of a triangle on one side of another triangle's plane: where
// ExactPredicates::orient3d(the plane triangle's corners, point) is >= 0 (positive) or
// < 0 (negative). Newell splits and BSP splits both produce cuts.
struct Cut {
  std::uint32_t plane;  // global triangle index whose plane cuts
  bool positive;
};

// One item to draw: the pixels of a screen triangle that lie on the kept side of each of
// its cuts. Two pieces split from one triangle by one plane carry the same cut with
// opposite sides, evaluated by the same arithmetic at each pixel, so between them they
// cover exactly the triangle's pixels, each once: no crack and no double write along a
// split, whatever the rounding.
struct Piece {
  std::uint32_t screenTriangle;
  std::uint32_t firstCut = 0, cutCount = 0;  // into PaintOrder::cuts
};

struct PaintOrder {
  std::vector<Piece> pieces;  // back to front
  std::vector<Cut> cuts;
  std::string partial;        // why the order is known to be wrong somewhere ("" when it is not)

  void add(std::uint32_t screenTriangle, const std::vector<Cut>& pieceCuts);
};

// An order with the screen triangles its pieces cut from.
struct PaintedPieces {
  ScreenGeometry geometry;
  PaintOrder order;
};

// One pixel of one piece.
struct PieceFragment {
  std::uint32_t triangle;  // global triangle index
  std::uint32_t piece;     // the piece's place in the order (PaintOrder::pieces)
  int x, y;
  std::size_t pixel;       // row-major index into the view's image
  float depth;             // view distance at the pixel center
};

// Tile by tile in parallel, each tile on one thread and its pieces in order, so that
// every pixel sees its pieces in order whatever the thread count: startTile(tile, rect)
// once per tile, then fragment(tile, f) for every pixel of every piece in the tile, and
// after each piece pieceDone(tile, index into the order). Returns the cut tests made.
struct NothingAfterAPiece {
  void operator()(std::size_t, std::uint32_t) const {}
};
template <typename StartTile, typename Fragment, typename PieceDone = NothingAfterAPiece>
std::int64_t paintInOrder(const PreparedScene& scene, const PaintedPieces& painted, const TileGrid& tiles, int threads,
                          StartTile&& startTile, Fragment&& fragment, PieceDone&& pieceDone = {});

// ---- implementation ----

namespace pieces_detail {
// A triangle's plane as one corner and the unnormalized normal (b - a) x (c - a): the
// same orientation as ExactPredicates::orient3d, so dot(normal, p - corner) has its sign
// (up to rounding, which both pieces of a split see identically).
struct Plane {
  dvec3 corner, normal;
};
Plane planeOf(const PreparedScene& scene, std::uint32_t triangle);
}  // namespace pieces_detail

template <typename StartTile, typename Fragment, typename PieceDone>
std::int64_t paintInOrder(const PreparedScene& scene, const PaintedPieces& painted, const TileGrid& tiles, int threads,
                          StartTile&& startTile, Fragment&& fragment, PieceDone&& pieceDone) {
  using pieces_detail::Plane;
  const PaintOrder& order = painted.order;
  const ScreenGeometry& geometry = painted.geometry;
  const CameraTransform& camera = geometry.camera;
  std::vector<Plane> cutPlanes;
  cutPlanes.reserve(order.cuts.size());
  for (const Cut& cut : order.cuts) cutPlanes.push_back(pieces_detail::planeOf(scene, cut.plane));
  const auto bins = tiles.bin(order.pieces.size(), [&](std::uint32_t i) -> const ScreenTriangle& {
    return geometry.triangles[order.pieces[i].screenTriangle];
  });
  std::vector<std::int64_t> cutTests(bins.size(), 0);
  parallelFor(bins.size(), threads, [&](std::size_t tile, int) {
    const TileGrid::Rect rect = tiles.rect(tile);
    startTile(tile, rect);
    std::int64_t tileCutTests = 0;  // stored once: neighbouring tiles' counts share cache lines
    for (const std::uint32_t index : bins[tile]) {
      const Piece& piece = order.pieces[index];
      const ScreenTriangle& tri = geometry.triangles[piece.screenTriangle];
      const Plane own = pieces_detail::planeOf(scene, tri.triangle);
      // A piece's pixels are its triangle's pixels whose point (where the pixel's ray
      // meets the triangle's plane) lies on the kept side of every cut.
      const auto insideCuts = [&](int x, int y) {
        const Ray ray = camera.rayThroughPixel(conventions::pixelCenter(x), conventions::pixelCenter(y));
        const double along = glm::dot(own.normal, own.corner - ray.origin) / glm::dot(own.normal, ray.direction);
        const dvec3 point = ray.origin + along * ray.direction;
        for (std::uint32_t k = 0; k < piece.cutCount; ++k) {
          ++tileCutTests;
          const Plane& plane = cutPlanes[piece.firstCut + k];
          const bool nonNegative = glm::dot(plane.normal, point - plane.corner) >= 0;  // NaN: negative side
          if (nonNegative != order.cuts[piece.firstCut + k].positive) return false;
        }
        return true;
      };
      const int spanBegin = std::max(tri.minX, rect.x0), spanEnd = std::min(tri.maxX + 1, rect.x1);
      for (int y = std::max(tri.minY, rect.y0); y < std::min(tri.maxY + 1, rect.y1); ++y)
        rasterizeSpan(tri, y, spanBegin, spanEnd, [&](int x) {
          if (piece.cutCount != 0 && !insideCuts(x, y)) return;
          const float depth = static_cast<float>(
              camera.distanceFromScreenAffine(tri.depthAt(conventions::pixelCenter(x), conventions::pixelCenter(y))));
          fragment(tile, PieceFragment{tri.triangle, index, x, y, std::size_t(y) * std::size_t(tiles.width) + std::size_t(x), depth});
        });
      pieceDone(tile, index);
    }
    cutTests[tile] = tileCutTests;
  });
  std::int64_t total = 0;
  for (const std::int64_t tests : cutTests) total += tests;
  return total;
}

}  // namespace hsr
