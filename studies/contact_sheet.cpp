#include "studies/contact_sheet.hpp"

#include <algorithm>

#include "renderer/image/image_library.hpp"
#include "renderer/util/error.hpp"

namespace hsr::studies {
namespace {

constexpr int kMargin = 10, kHeadingHeight = 30, kCaptionLine = 17, kFontSize = 14;

int thumbnailHeight(const Image& image) {
  return std::max(1, image.height * kThumbnailWidth / std::max(1, image.width));
}

Image shrinkImage(const Image& image) {
  Image thumbnail;
  const std::string error = imageLibrary().resize(image, kThumbnailWidth, thumbnailHeight(image), thumbnail);
  if (!error.empty()) throw InputError("contact sheet: cannot shrink an image: " + error);
  return thumbnail;
}

// The most saturated pixel of each block wins, so a single wrong pixel stays visible.
Image shrinkHeatMap(const Image& image) {
  const int width = kThumbnailWidth, height = thumbnailHeight(image);
  Image small{width, height, 4, std::vector<std::uint8_t>(std::size_t(width) * std::size_t(height) * 4, 0)};
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* from = &image.pixels[4 * (std::size_t(y) * std::size_t(image.width) + std::size_t(x))];
      std::uint8_t* to =
          &small.pixels[4 * (std::size_t(y * height / image.height) * std::size_t(width) + std::size_t(x * width / image.width))];
      const auto saturation = [](const std::uint8_t* p) { return std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}); };
      if (to[3] == 0 || saturation(from) > saturation(to)) std::copy(from, from + 4, to);
    }
  // A heat map narrower than the thumbnail is enlarged instead: the thumbnail pixels no
  // image pixel fell on take their nearest one's.
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint8_t* to = &small.pixels[4 * (std::size_t(y) * std::size_t(width) + std::size_t(x))];
      if (to[3] != 0) continue;
      const std::size_t nearest = std::size_t(y * image.height / height) * std::size_t(image.width) + std::size_t(x * image.width / width);
      std::copy(&image.pixels[4 * nearest], &image.pixels[4 * nearest] + 4, to);
    }
  return small;
}

// Copies an RGBA image into the canvas with its top left corner at (x, y), clipped.
void paste(Image& canvas, int x, int y, const Image& image) {
  const int columns = std::min(image.width, canvas.width - x);
  if (columns <= 0) return;
  for (int row = 0; row < image.height && y + row < canvas.height; ++row) {
    const auto from = image.pixels.begin() + 4 * std::ptrdiff_t(row) * image.width;
    std::copy(from, from + 4 * columns, canvas.pixels.begin() + 4 * (std::ptrdiff_t(y + row) * canvas.width + x));
  }
}

void text(Image& canvas, int x, int baseline, const std::string& line, float grey) {
  const float color[4] = {grey, grey, grey, 1};
  if (const std::string error = imageLibrary().drawText(canvas, x, baseline, line, kFontSize, kLabelFont, color); !error.empty())
    throw InputError(std::string("contact sheet: cannot draw text with ") + kLabelFont + ": " + error);
}

int textWidth(const std::string& line) {
  int width = 0;
  if (const std::string error = imageLibrary().textWidth(line, kFontSize, kLabelFont, width); !error.empty())
    throw InputError(std::string("contact sheet: cannot measure text with ") + kLabelFont + ": " + error);
  return width;
}

// A caption's lines broken at spaces where one is wider than a thumbnail, so that no
// text runs into the next tile (a single word wider than that keeps a line of its own).
std::vector<std::string> fitted(const std::vector<std::string>& caption) {
  std::vector<std::string> lines;
  for (const std::string& line : caption) {
    std::string current;
    std::size_t start = 0;
    while (start <= line.size()) {
      const std::size_t space = std::min(line.find(' ', start), line.size());
      const std::string word = line.substr(start, space - start);
      const std::string longer = current.empty() ? word : current + " " + word;
      if (!current.empty() && textWidth(longer) > kThumbnailWidth) {
        lines.push_back(current);
        current = word;
      } else {
        current = longer;
      }
      start = space + 1;
    }
    lines.push_back(current);
  }
  return lines;
}

int captionHeight(const std::vector<SheetImage>& images) {
  std::size_t lines = 0;
  for (const SheetImage& image : images) lines = std::max(lines, image.caption.size());
  return int(lines) * kCaptionLine + 6;
}

int rowHeight(const std::vector<SheetImage>& images) {
  int height = 0;
  for (const SheetImage& sheetImage : images) height = std::max(height, thumbnailHeight(sheetImage.image));
  return height + captionHeight(images);
}

}  // namespace

Image composeContactSheet(std::vector<SheetSection> sections) {
  for (SheetSection& section : sections)
    for (auto* row : {&section.images, &section.heatMaps})
      for (SheetImage& shown : *row) shown.caption = fitted(shown.caption);
  std::size_t columns = 1;
  int height = kMargin;
  for (const SheetSection& section : sections) {
    columns = std::max(columns, section.images.size());
    height += kHeadingHeight + rowHeight(section.images) + rowHeight(section.heatMaps) + kMargin;
  }
  const int width = kMargin + int(columns) * (kThumbnailWidth + kMargin);

  Image canvas{width, height, 4, std::vector<std::uint8_t>(std::size_t(width) * std::size_t(height) * 4)};
  const std::uint8_t background[4] = {23, 23, 26, 255};  // (0.09, 0.09, 0.1) in 8 bits
  for (std::size_t pixel = 0; pixel < canvas.pixels.size(); pixel += 4) std::copy(background, background + 4, &canvas.pixels[pixel]);
  int y = kMargin;
  for (const SheetSection& section : sections) {
    text(canvas, kMargin, y + 20, section.heading, 1.0f);
    y += kHeadingHeight;
    for (const auto* row : {&section.images, &section.heatMaps}) {
      const int imagesHeight = rowHeight(*row) - captionHeight(*row);
      for (std::size_t column = 0; column < row->size(); ++column) {
        const SheetImage& shown = (*row)[column];
        const int x = kMargin + int(column) * (kThumbnailWidth + kMargin);
        paste(canvas, x, y, row == &section.images ? shrinkImage(shown.image) : shrinkHeatMap(shown.image));
        for (std::size_t line = 0; line < shown.caption.size(); ++line)
          text(canvas, x, y + imagesHeight + kCaptionLine * int(line + 1), shown.caption[line], line == 0 ? 0.95f : 0.7f);
      }
      y += rowHeight(*row);
    }
    y += kMargin;
  }
  return canvas;
}

}  // namespace hsr::studies
