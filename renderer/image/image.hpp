// Image: pixels of 8 bits per channel, rows top to bottom, as files hold them and
// pictures (the steps', the contact sheet's) are drawn; a Frame (frame.hpp) is what an
// algorithm produces, and becomes an Image when written.
#pragma once

#include <cstdint>
#include <vector>

namespace hsr {

struct Image {
  int width = 0, height = 0, channels = 0;  // channels: 1 grey, 2 grey and alpha, 3 RGB, 4 RGBA
  std::vector<std::uint8_t> pixels;
};

}  // namespace hsr
