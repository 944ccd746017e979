#include "renderer/image/pfm.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

namespace hsr {
namespace {

constexpr std::uintmax_t kLongestHeader = 256;  // "Pf", two sizes and a scale, with room to spare

// A float as little-endian bytes, whatever the machine's order. (memcpy, not
// std::bit_cast: emscripten's libc++ lacks it.)
void appendLittleEndian(std::string& bytes, float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  for (int shift = 0; shift < 32; shift += 8) bytes.push_back(char((bits >> shift) & 0xff));
}

float fromEndian(const unsigned char* four, bool littleEndian) {
  std::uint32_t bits = 0;
  for (int k = 0; k < 4; ++k) bits |= std::uint32_t(four[littleEndian ? k : 3 - k]) << (8 * k);
  float value = 0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace

std::string pfmBytes(int width, int height, std::span<const float> topDown) {
  std::string bytes = "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
  bytes.reserve(bytes.size() + topDown.size() * 4);
  for (int row = height - 1; row >= 0; --row)
    for (int x = 0; x < width; ++x) appendLittleEndian(bytes, topDown[std::size_t(row) * std::size_t(width) + std::size_t(x)]);
  return bytes;
}

std::string readPfm(const std::filesystem::path& file, int width, int height, std::vector<float>& topDown) {
  // A regular file, and no larger than a header and the floats could be: a pipe or a
  // runaway program's gigabytes are refused before they are read.
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) return "wrote no depth image at " + file.filename().string();
  const std::string name = "its depth image " + file.filename().string();
  const std::uintmax_t floatBytes = 4 * std::uintmax_t(width) * std::uintmax_t(height), size = std::filesystem::file_size(file, error);
  if (error || size > floatBytes + kLongestHeader)
    return name + " holds " + std::to_string(size) + " bytes; expected about " + std::to_string(floatBytes) + " (" + std::to_string(width) +
           " x " + std::to_string(height) + " float32s and a header)";
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The header: three whitespace-separated words after the magic, then one whitespace
  // character before the floats.
  std::istringstream header(bytes.substr(0, kLongestHeader));
  std::string magic, scaleWord;
  long fileWidth = 0, fileHeight = 0;
  header >> magic;
  if (magic == "PF") return name + " is a colour PFM (PF); expected Pf, one float per pixel";
  if (magic != "Pf") return name + " is not a PFM: it starts with \"" + magic.substr(0, 8) + "\"; expected Pf";
  if (!(header >> fileWidth >> fileHeight >> scaleWord)) return name + ": its header is not \"Pf W H SCALE\"";
  double scale = 0;
  try {
    scale = std::stod(scaleWord);
  } catch (const std::exception&) {
    return name + ": its scale \"" + scaleWord + "\" is not a number; expected -1.0 (little-endian)";
  }
  if (scale == 0) return name + ": its scale is 0; expected -1.0 (little-endian) or 1.0 (big-endian)";
  if (fileWidth != width || fileHeight != height)
    return name + " is " + std::to_string(fileWidth) + "x" + std::to_string(fileHeight) + "; expected " + std::to_string(width) + "x" +
           std::to_string(height) + ", the scene's size line";
  const std::streamoff afterScale = header.tellg();
  if (afterScale < 0) return name + ": its header is not followed by the floats";
  const std::size_t start = std::size_t(afterScale) + 1;  // the one whitespace character after the scale
  const std::size_t count = std::size_t(width) * std::size_t(height);
  if (bytes.size() != start + 4 * count)
    return name + " holds " + std::to_string(bytes.size() < start ? 0 : bytes.size() - start) + " bytes of floats; expected " +
           std::to_string(4 * count) + " (" + std::to_string(width) + " x " + std::to_string(height) + " float32s)";
  topDown.resize(count);
  const auto* floats = reinterpret_cast<const unsigned char*>(bytes.data() + start);
  for (int row = height - 1, k = 0; row >= 0; --row)
    for (int x = 0; x < width; ++x, ++k)
      topDown[std::size_t(row) * std::size_t(width) + std::size_t(x)] = fromEndian(floats + 4 * std::size_t(k), scale < 0);
  return "";
}

}  // namespace hsr
