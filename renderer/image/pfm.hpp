// PFM, the portable float map: a depth image a program in any language can write in a
// few lines (no library), which hsr writes with --depth FILE.pfm and hsr grade reads
// (Exercise 1's depth image). The greyscale kind, as Paul Debevec's HDRShop defined it:
//
//   Pf\n                   a float per pixel ("PF" would be three)
//   W H\n                  width and height, in decimal
//   -1.0\n                 a negative scale: the floats are little-endian
//   W * H float32s         rows from the BOTTOM of the image up, each left to right
//
// +infinity is a float like any other (hsr's background depth).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace hsr {

// The file's bytes for a width x height image whose values are given in rows from the
// top down (as hsr's frames hold them).
std::string pfmBytes(int width, int height, std::span<const float> topDown);

// Reads a greyscale PFM of exactly width x height into rows from the top down. Returns ""
// or what is wrong with the file, in words ("its header says 64x32; expected 128x64").
std::string readPfm(const std::filesystem::path& file, int width, int height, std::vector<float>& topDown);

}  // namespace hsr
