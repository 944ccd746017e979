// PNG files through libpng: the images hsr writes on every render (color, ids, heat
// maps) and reads back to compare. A small library on purpose: the command line's start
// should not pay for a general image library's dependencies (renderer/image/image_library.hpp
// loads OpenImageIO only for what needs it).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "renderer/image/image.hpp"

namespace hsr {

// 8 bits per channel, rows top to bottom; `channels` is 3 (RGB) or 4 (RGBA). A non-empty
// `description` is stored as the file's Description text. Throws InputError naming the
// path when the file cannot be written.
void writePng(const std::filesystem::path& path, int width, int height, int channels, const std::uint8_t* pixels,
              const std::string& description = "");

// Any PNG, as 8 bits per channel with its own channel count (grey 1, grey and alpha 2,
// RGB 3, RGBA 4; a palette becomes RGB or RGBA). Throws InputError naming the path.
Image readPng(const std::filesystem::path& path);

}  // namespace hsr
