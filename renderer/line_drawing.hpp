// A line drawing as a picture: SVG in the view's pixel coordinates, or rasterized with
// the line rule of renderer/raster, with the hidden parts shown as the style asks.
#pragma once

#include <string>

#include "renderer/frame.hpp"
#include "renderer/line_set.hpp"

namespace hsr {


// How a drawing shows hidden parts.
enum class LineStyle {
  visible,  // visible parts only, solid black
  hidden,   // and hidden parts dashed grey
  qi,       // by quantitative invisibility: QI 0 black, 1 grey dashed, 2 and more light grey
};
inline constexpr double kLineWidthPixels = 1.5;
inline constexpr double kDashPixels = 6, kGapPixels = 4;

// SVG in the view's pixel coordinates (y down), one <line> per drawn piece.
std::string lineSetSvg(const LineSet& lines, LineStyle style);
// The drawing rasterized (renderer/raster's line rule) over a white background.
Frame lineSetFrame(const LineSet& lines, LineStyle style);

}  // namespace hsr
