#include "studies/contact_sheet.hpp"

#include <algorithm>
#include <stdexcept>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

namespace hsr::studies {
namespace {

constexpr int kMargin = 10, kHeadingHeight = 30, kCaptionLine = 17, kFontSize = 14;
constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";  // Debian: fonts-dejavu-core

int thumbnailHeight(const SheetImage& image) {
  return std::max(1, image.height * kThumbnailWidth / std::max(1, image.width));
}

OIIO::ImageBuf wrap(const SheetImage& image) {
  OIIO::ImageBuf buffer(OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::UINT8));
  buffer.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, image.rgba.data());
  return buffer;
}

OIIO::ImageBuf shrinkImage(const SheetImage& image) {
  return OIIO::ImageBufAlgo::resize(wrap(image), "", 0, OIIO::ROI(0, kThumbnailWidth, 0, thumbnailHeight(image), 0, 1, 0, 4));
}

// The most saturated pixel of each block wins, so a single wrong pixel stays visible.
OIIO::ImageBuf shrinkHeatMap(const SheetImage& image) {
  const int width = kThumbnailWidth, height = thumbnailHeight(image);
  std::vector<std::uint8_t> small(std::size_t(width) * std::size_t(height) * 4, 0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* from = &image.rgba[4 * (std::size_t(y) * std::size_t(image.width) + std::size_t(x))];
      std::uint8_t* to = &small[4 * (std::size_t(y * height / image.height) * std::size_t(width) + std::size_t(x * width / image.width))];
      const auto saturation = [](const std::uint8_t* p) { return std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}); };
      if (to[3] == 0 || saturation(from) > saturation(to)) std::copy(from, from + 4, to);
    }
  OIIO::ImageBuf buffer(OIIO::ImageSpec(width, height, 4, OIIO::TypeDesc::UINT8));
  buffer.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, small.data());
  return buffer;
}

void text(OIIO::ImageBuf& canvas, int x, int baseline, const std::string& line, float grey) {
  const float color[4] = {grey, grey, grey, 1};
  if (!OIIO::ImageBufAlgo::render_text(canvas, x, baseline, line, kFontSize, kFont, color))
    throw std::runtime_error(std::string("contact sheet: cannot draw text with ") + kFont + ": " + canvas.geterror());
}

int captionHeight(const std::vector<SheetImage>& images) {
  std::size_t lines = 0;
  for (const SheetImage& image : images) lines = std::max(lines, image.caption.size());
  return int(lines) * kCaptionLine + 6;
}

int rowHeight(const std::vector<SheetImage>& images) {
  int height = 0;
  for (const SheetImage& image : images) height = std::max(height, thumbnailHeight(image));
  return height + captionHeight(images);
}

}  // namespace

Sheet composeContactSheet(const std::vector<SheetSection>& sections) {
  std::size_t columns = 1;
  int height = kMargin;
  for (const SheetSection& section : sections) {
    columns = std::max(columns, section.images.size());
    height += kHeadingHeight + rowHeight(section.images) + rowHeight(section.heatMaps) + kMargin;
  }
  const int width = kMargin + int(columns) * (kThumbnailWidth + kMargin);

  OIIO::ImageBuf canvas(OIIO::ImageSpec(width, height, 4, OIIO::TypeDesc::UINT8));
  const float background[4] = {0.09f, 0.09f, 0.1f, 1};
  OIIO::ImageBufAlgo::fill(canvas, background);
  int y = kMargin;
  for (const SheetSection& section : sections) {
    text(canvas, kMargin, y + 20, section.heading, 1.0f);
    y += kHeadingHeight;
    for (const auto* row : {&section.images, &section.heatMaps}) {
      const int imagesHeight = rowHeight(*row) - captionHeight(*row);
      for (std::size_t column = 0; column < row->size(); ++column) {
        const SheetImage& image = (*row)[column];
        const int x = kMargin + int(column) * (kThumbnailWidth + kMargin);
        const OIIO::ImageBuf thumbnail = row == &section.images ? shrinkImage(image) : shrinkHeatMap(image);
        OIIO::ImageBufAlgo::paste(canvas, x, y, 0, 0, thumbnail);
        for (std::size_t line = 0; line < image.caption.size(); ++line)
          text(canvas, x, y + imagesHeight + kCaptionLine * int(line + 1), image.caption[line], line == 0 ? 0.95f : 0.7f);
      }
      y += rowHeight(*row);
    }
    y += kMargin;
  }
  Sheet sheet{width, height, std::vector<std::uint8_t>(std::size_t(width) * std::size_t(height) * 4)};
  canvas.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, sheet.rgba.data());
  return sheet;
}

}  // namespace hsr::studies
