#include "renderer/steps/label_font.hpp"

#include <algorithm>
#include <cstdint>
#include <span>

namespace hsr {

namespace {

#include "renderer/steps/label_font_glyphs.inc"

std::span<const LabelGlyph> glyphsOf(int size) {
  if (size <= kSmallLabelSize) return kGlyphs12;
  return kGlyphs13;
}

// The glyph of a code point, U+FFFD's (the table's last) when it has none. ASCII comes
// first in the table, in order: a search from the front is short for what labels hold.
const LabelGlyph& glyphOf(std::span<const LabelGlyph> glyphs, unsigned codePoint) {
  const auto found = std::find_if(glyphs.begin(), glyphs.end(), [&](const LabelGlyph& glyph) { return glyph.codePoint == codePoint; });
  return found != glyphs.end() ? *found : glyphs.back();
}

// The code points of UTF-8 text; a malformed byte stands for itself (and is drawn as U+FFFD).
template <typename Each>
void forEachCodePoint(const std::string& text, Each&& each) {
  for (std::size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    const int extra = byte >= 0xF0 ? 3 : byte >= 0xE0 ? 2 : byte >= 0xC0 ? 1 : 0;
    unsigned codePoint = extra == 0 ? byte : byte & (0x3Fu >> extra);
    std::size_t next = i + 1;
    for (int k = 0; k < extra && next < text.size() && (static_cast<unsigned char>(text[next]) & 0xC0) == 0x80; ++k, ++next)
      codePoint = (codePoint << 6) | (static_cast<unsigned char>(text[next]) & 0x3Fu);
    each(codePoint);
    i = next;
  }
}

}  // namespace

int labelWidth(const std::string& text, int size) {
  const std::span<const LabelGlyph> glyphs = glyphsOf(size);
  int width = 0;
  forEachCodePoint(text, [&](unsigned codePoint) { width += glyphOf(glyphs, codePoint).advance; });
  return width;
}

void drawLabel(Image& picture, int x, int baseline, const std::string& text, Rgb color, int size) {
  const std::span<const LabelGlyph> glyphs = glyphsOf(size);
  int pen = x;
  forEachCodePoint(text, [&](unsigned codePoint) {
    const LabelGlyph& glyph = glyphOf(glyphs, codePoint);
    for (int gy = 0; gy < glyph.height; ++gy)
      for (int gx = 0; gx < glyph.width; ++gx) {
        const int px = pen + glyph.left + gx, py = baseline + glyph.top + gy;
        if (px < 0 || py < 0 || px >= picture.width || py >= picture.height) continue;
        const int coverage = static_cast<unsigned char>(glyph.coverage[gy * glyph.width + gx]);
        std::uint8_t* pixel = &picture.pixels[(std::size_t(py) * std::size_t(picture.width) + std::size_t(px)) * 4];
        // Over: the colour in the glyph's share of the pixel, the picture in the rest.
        for (std::size_t c = 0; c < 3; ++c) pixel[c] = std::uint8_t((color[c] * coverage + pixel[c] * (255 - coverage) + 127) / 255);
      }
    pen += glyph.advance;
  });
}

}  // namespace hsr
