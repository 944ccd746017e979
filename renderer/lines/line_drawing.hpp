// A line drawing as a picture: SVG in the view's pixel coordinates, or rasterized with
// the line rule of renderer/raster/raster, with the hidden parts shown as the style asks.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "renderer/image/frame.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/steps/steps.hpp"

namespace hsr {


// How a drawing shows hidden parts.
enum class LineStyle {
  visible,  // visible parts only, solid black
  hidden,   // and hidden parts dashed grey
  qi,       // by quantitative invisibility: QI 0 solid black, each higher QI dashed in its colour, with a legend
};
// The colours by QI: 0 black, 1 blue, 2 orange, 3 and more magenta (chosen apart for
// readers with the common colour-vision deficiencies too, by lightness as well as hue).
inline constexpr std::array<Rgb, 4> kQiColors = {Rgb{0, 0, 0}, Rgb{40, 100, 230}, Rgb{235, 140, 0}, Rgb{190, 0, 150}};
inline constexpr Rgb kHiddenLineColor = {136, 136, 136};
// A line algorithm's step (renderer/steps/steps.hpp): the drawing so far (`lines` with the
// pieces decided so far) in the style, under it the edges just decided in broad light
// green (kJustDecided), and on each of their pieces long enough to hold it, its QI
// (style qi).
inline constexpr Rgb kJustDecided = {170, 235, 170};
Image lineStepPicture(const LineSet& lines, std::span<const std::uint32_t> justDecided, LineStyle style);
// What each QI colour means, for a legend.
std::vector<std::pair<Rgb, std::string>> qiLegend();
inline constexpr double kLineWidthPixels = 1.5;
inline constexpr double kDashPixels = 6, kGapPixels = 4;

// What a reader calls an edge in a drawing's <title>s: for a mesh edge its kind and
// object, for a junction the two objects that meet there (edgeNamesOf).
using EdgeNamer = std::function<std::string(const FeatureEdge&)>;
EdgeNamer edgeNamesOf(const PreparedScene& scene);

// SVG in the view's pixel coordinates (y down): pieces that continue one another as one
// <polyline>; the QI style adds its legend. Each stroke carries a <title> (a tooltip in a
// browser, a label to a screen reader) with its QI and, given `names`, the edge's name;
// only strokes of the same title are joined.
std::string lineSetSvg(const LineSet& lines, LineStyle style, const EdgeNamer& names = {});
// The drawing rasterized (renderer/raster/raster's line rule) over a white background; the QI
// style with its legend in the top left corner.
Frame lineSetFrame(const LineSet& lines, LineStyle style);
// The visible pieces as text, a line each, "x0 y0 x1 y1" in the view's pixel coordinates
// (y down) to six decimals, after a comment line: what hsr render --segments writes and
// hsr grade reads from a line exercise's submission (grading/line_judge.hpp).
std::string visibleSegmentsText(const LineSet& lines);

}  // namespace hsr
