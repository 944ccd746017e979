// What hsr asks of OpenImageIO, which stays the suite's image library for what it is for:
// depth as OpenEXR, images in any format, OpenImageIO's comparison numbers, resizing and
// text for contact sheets. It is a module loaded on first use (dlopen), not a link-time
// dependency of the hsr program: Debian's OpenImageIO brings some 250 shared libraries
// (OpenCV, FFmpeg, GDAL...), and loading them cost every command about 0.2 s before it
// did anything. PNG, what every render writes, goes through libpng (renderer/image/png.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/image/image.hpp"

namespace hsr {


// OpenImageIO's ImageBufAlgo::compare, on two images of the same size and channels.
struct ImageComparison {
  double meanError = 0, rmsError = 0, psnr = 0, maxError = 0;
  int maxX = 0, maxY = 0, maxChannel = 0;
  std::uint64_t failing = 0;  // pixels with a channel differing by more than the tolerance
};

// The font of every label the suite draws into a picture (contact sheets, steps).
inline constexpr const char* kLabelFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";  // Debian: fonts-dejavu-core

// Each operation returns "" on success, or what went wrong (without the path: the
// caller names it).
struct ImageLibrary {
  std::string (*writeDepthExr)(const std::string& path, int width, int height, const float* depth);
  std::string (*readImage)(const std::string& path, Image& image);  // 8 bits per channel
  std::string (*compare)(const Image& first, const Image& second, double tolerance, ImageComparison& result);
  std::string (*resize)(const Image& image, int width, int height, Image& resized);  // RGBA, filtered
  // Draws `text` into an RGBA canvas with its baseline at y, in the TrueType `font`.
  std::string (*drawText)(Image& canvas, int x, int baseline, const std::string& text, int size, const std::string& font,
                          const float (&rgba)[4]);
  // How wide drawText would draw `text`, in pixels.
  std::string (*textWidth)(const std::string& text, int size, const std::string& font, int& width);
  // Writes frames of one size as an animation that loops forever (a GIF: every browser
  // and document viewer plays it, and OpenImageIO writes it with no further tool).
  std::string (*writeAnimation)(const std::string& path, const std::vector<Image>& frames, int framesPerSecond);
};

// The module, loaded on the first call; throws InputError when it cannot be loaded.
const ImageLibrary& imageLibrary();

}  // namespace hsr

// The one symbol the module exports.
extern "C" const hsr::ImageLibrary* hsrImageLibrary();
