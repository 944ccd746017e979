// The contact sheet of hsr compare: per scene, each algorithm's image with its name,
// time and error, and below it the error heat map against the reference.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace hsr::studies {

struct SheetImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  std::vector<std::string> caption;  // one or two short lines
};

struct SheetSection {
  std::string heading;
  std::vector<SheetImage> images;    // the reference first
  std::vector<SheetImage> heatMaps;  // one per image
};

struct Sheet {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
};

// Thumbnails are kThumbnailWidth wide. Heat maps are shrunk so that no marked pixel
// disappears: a thumbnail pixel is red (or blue) if any pixel it covers is.
constexpr int kThumbnailWidth = 256;
Sheet composeContactSheet(const std::vector<SheetSection>& sections);

}  // namespace hsr::studies
