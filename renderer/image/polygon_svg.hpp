// Visible polygons as a picture: what an object-space algorithm (Weiler-Atherton)
// answers besides its pixels, drawn as SVG in the view's pixel coordinates.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/image/frame.hpp"
#include "renderer/util/math.hpp"

namespace hsr {

// A convex piece of one triangle that is visible, its corners in pixel coordinates (y
// down), in order around it.
struct VisiblePolygon {
  std::uint32_t triangle;  // global triangle index
  std::vector<dvec2> corners;
};

// SVG of the polygons over the image's background colour, each filled with the mean colour of the
// image's pixels that show its triangle (so the drawing has the shaded image's colours
// with exact outlines), and outlined in a thin translucent black so that the pieces the
// clipping made can be told apart.
std::string visiblePolygonsSvg(const std::vector<VisiblePolygon>& polygons, const Frame& shaded);

}  // namespace hsr
