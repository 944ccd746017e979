// Depth compared plane against plane at pixel centers, as the image-space algorithms that
// decide whole windows or spans from a few samples do (Warnock, Watkins): an order in
// which smaller is nearer, and a bound on the rounding of each value, so that a decision
// taken from a window's or a span's ends holds at every pixel center between them.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "renderer/geometry/camera.hpp"
#include "renderer/raster/raster.hpp"
#include "renderer/util/conventions.hpp"

namespace hsr {

struct DepthOrder {
  // t is 1/distance under perspective (larger is nearer) and the distance itself under
  // orthographic; either way affine across the screen, and so is sign * t.
  double sign;
  explicit DepthOrder(const CameraTransform& camera) : sign(camera.perspective() ? -1.0 : 1.0) {}

  // The triangle's plane at the center of pixel (x, y), as an order key: smaller is nearer.
  double key(const ScreenTriangle& tri, int x, int y) const {
    return sign * tri.depthAt(conventions::pixelCenter(x), conventions::pixelCenter(y));
  }

  // How far key() as computed at the center of pixel (x, y) may lie from the plane's exact
  // value there: t0 + tdx (px - x0) + tdy (py - y0) takes five roundings, each at most
  // half an ulp of a value no larger than the sum of the terms' magnitudes; 4 ε of that
  // sum covers them. The magnitude is a convex function of (px, py), so its largest value
  // over a rectangle of centers is at a corner: the bound at the corners holds inside.
  // The plane's distance along the view axis at the center of pixel (x, y), as a frame
  // stores the depth of the triangle a pixel shows.
  static float distanceAt(const CameraTransform& camera, const ScreenTriangle& tri, int x, int y) {
    return static_cast<float>(camera.distanceFromScreenAffine(tri.depthAt(conventions::pixelCenter(x), conventions::pixelCenter(y))));
  }

  static double roundingBound(const ScreenTriangle& tri, int x, int y) {
    return roundingBoundAt(tri, conventions::pixelCenter(x), conventions::pixelCenter(y));
  }
  // The same at any point (px, py) in pixel units.
  static double roundingBoundAt(const ScreenTriangle& tri, double px, double py) {
    const double magnitude = std::abs(tri.t0) + std::abs(tri.tdx * (px - tri.x0)) + std::abs(tri.tdy * (py - tri.y0));
    return 4 * std::numeric_limits<double>::epsilon() * magnitude;
  }

  // Whether polygon a (its key there, and its index in submission order) is in front of
  // polygon b at a point: nearer, or as near and submitted first, as the z-buffer decides.
  static bool inFront(double keyA, std::uint32_t a, double keyB, std::uint32_t b) { return keyA < keyB || (keyA == keyB && a < b); }
};

}  // namespace hsr
