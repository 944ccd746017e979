// Where a line drawing is wrong against the exact drawing (renderer/reference/line_reference),
// measured and drawn: the length drawn off every exact line, and a picture in the
// suite's error colours (exactly visible lines light grey, parts drawn but hidden red,
// parts visible but missed blue).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "renderer/image/frame.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/steps/steps.hpp"

namespace hsr {

// The length in pixels of the parts drawn visible that the reference hides and that do
// not lie on a visible line of the exact drawing (within 1e-6 pixel). Where an edge lies
// exactly behind a nearer edge (an orthographic view along a face, say), the reference's
// closed triangles hide it while an algorithm may draw it: that counts in the line error
// but changes no pixel, and not here. Sampled every half pixel. truth[i] describes lines.edges[i].
double strayDrawnLength(const LineSet& lines, std::span<const EdgeVisibility> truth);

// Where a drawing is wrong, as an RGBA8 picture: the exactly visible lines light grey,
// parts drawn but hidden in the reference red, parts visible there but not drawn blue.
// truth[i] describes lines.edges[i].
std::vector<std::uint8_t> lineErrorMap(const LineSet& lines, std::span<const EdgeVisibility> truth);

inline constexpr Rgb kExactLineGrey = {187, 187, 187}, kWronglyDrawnRed = {220, 30, 30}, kWronglyHiddenBlue = {30, 60, 220};
inline constexpr double kErrorLineWidth = 3;  // errors drawn wider, so a short one is still seen

// An RGBA8 picture of a drawing's errors, white to start with.
class LineErrorPicture {
 public:
  LineErrorPicture(int width, int height) : picture_(blankPicture(width, height)) {}
  void line(const dvec2& a, const dvec2& b, double width, Rgb color) { drawSegment(picture_, a, b, color, width); }
  // Parts of an edge; those shorter than a millionth of a pixel are the rounding of event
  // positions, not errors.
  void parts(const FeatureEdge& edge, const std::vector<Interval>& parts, double width, Rgb color) {
    for (const Interval& part : parts)
      if ((part.end - part.begin) * edge.lengthPixels() > 1e-6) line(edge.pixelAt(part.begin), edge.pixelAt(part.end), width, color);
  }
  std::vector<std::uint8_t> take() { return std::move(picture_.pixels); }

 private:
  Image picture_;
};

}  // namespace hsr
