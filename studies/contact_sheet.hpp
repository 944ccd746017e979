// The contact sheet of hsr compare: per scene, each algorithm's image with its name,
// time and error, and below it the error heat map against the reference.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "renderer/image/frame.hpp"

namespace hsr::studies {

struct SheetImage {
  SheetImage(int width, int height, std::span<const std::uint8_t> rgba, std::vector<std::string> caption_)
      : image{width, height, 4, {rgba.begin(), rgba.end()}}, caption(std::move(caption_)) {}
  Image image;
  std::vector<std::string> caption;  // one or two short lines
};

struct SheetSection {
  std::string heading;
  std::vector<SheetImage> images;    // the reference first
  std::vector<SheetImage> heatMaps;  // one per image
};

// Thumbnails are kThumbnailWidth wide. Heat maps are shrunk so that no marked pixel
// disappears: a thumbnail pixel is red (or blue) if any pixel it covers is. Caption lines
// wider than a thumbnail are broken at spaces.
constexpr int kThumbnailWidth = 256;
Image composeContactSheet(std::vector<SheetSection> sections);  // taken by value: its captions are re-broken in place

}  // namespace hsr::studies
