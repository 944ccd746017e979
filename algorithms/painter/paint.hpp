// What the three orders share: the back-to-front list they produce, and the drawing of
// that list (paint.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "algorithms/painter/painter.hpp"
#include "renderer/predicates.hpp"
#include "renderer/screen_triangles.hpp"
#include "renderer/shading.hpp"

namespace hsr::painter {

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

// Splits a convex polygon by a plane, given each vertex's exact side of it (+1, 0, -1)
// and its signed height above it in double precision (only to place the crossings on
// the edges whose ends lie on opposite sides). Vertices on the plane go to both pieces.
struct SplitPolygon {
  std::vector<dvec3> positive, negative;
};
SplitPolygon splitPolygon(const std::vector<dvec3>& vertices, const std::vector<int>& sides, const std::vector<double>& heights);

// The orders (sort.cpp, newell.cpp; the BSP tree's is in bsp.hpp).
PaintOrder sortOrder(const ScreenGeometry& geometry, SortKey key, Stats& stats);
PaintOrder newellOrder(const PreparedScene& scene, const ScreenGeometry& geometry, const Knobs& knobs, Stats& stats);

// Which side of the triangle's plane the eye is on, in the sign convention of Cut:
// +1, -1, or 0 when the plane passes through the eye (seen edge-on). Under orthographic
// projection the eye is the point at infinity behind the camera.
int eyeSide(const PreparedScene& scene, const CameraTransform& camera, std::uint32_t triangle, ExactPredicates& predicates);

// What the z-buffer's sorted transparency pass paints over: the opaque surfaces it drew
// and shaded, and the shader that shaded them.
struct OpaqueBase {
  const Frame& frame;
  const PixelShader& shader;
};

// Draws the pieces in order into a frame of the scene's size: ids, depth, and color
// (shaded by the effects' passes; blended back to front when the scene declares
// transparency), then fog and outline when declared. Over a `base`, each piece shows
// only where it lies in front of the base's depth, blended over its colors, and a
// pixel's id and depth are the nearest surface's (a depth test for ids alone). Stats:
// "pieces painted", "fragments written", "cut tests", and with transparency "blended
// writes"; phase "painting", or "transparency" over a base.
Frame paint(const PreparedScene& scene, const ScreenGeometry& geometry, const PaintOrder& order, int threads, Stats& stats,
            const OpaqueBase* base = nullptr);

}  // namespace hsr::painter
