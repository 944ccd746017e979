// The font the step pictures are labelled in (legends, a heat map's ends, a line's QI, an
// animation frame's caption): DejaVu Sans at 12 and 13 pixels, drawn once by OpenImageIO
// into a table (scripts/label_font/make_label_font.sh) that is compiled in. Labels are
// the same bits on every target the suite builds for, and need no font library: the
// browser edition and the arm64 build draw the same steps as this machine's.
#pragma once

#include <string>

#include "renderer/image/frame.hpp"
#include "renderer/image/image.hpp"

namespace hsr {

// One glyph: its advance, and the coverage (0 to 255) of the box its ink covers, placed
// `left` pixels right of the pen and `top` pixels below the baseline (negative: above).
struct LabelGlyph {
  unsigned codePoint;
  int advance, left, top, width, height;
  const char* coverage;  // width x height bytes, row by row
};

// The sizes the table holds; any other size is drawn at the nearest.
inline constexpr int kSmallLabelSize = 12, kLabelSize = 13;

// How wide `text` (UTF-8) is at `size`: the sum of its glyphs' advances. A character the
// table lacks is drawn as U+FFFD.
int labelWidth(const std::string& text, int size = kLabelSize);
// Draws `text` with its pen starting at x and its baseline at y, each glyph's coverage
// blended over the picture (RGBA) in `color`; what falls off the picture is cut.
void drawLabel(Image& picture, int x, int baseline, const std::string& text, Rgb color, int size = kLabelSize);

}  // namespace hsr
