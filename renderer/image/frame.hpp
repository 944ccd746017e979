// Frame: what a surface algorithm produces, and how it is written. Writers go through
// OutputFiles, which writes every file under a temporary name and renames them into
// place only when all were written, so a failed run leaves no partial output behind.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "renderer/image/image.hpp"
#include "renderer/util/memory.hpp"
#include "renderer/util/stats.hpp"

namespace hsr {

// What Frame::distances() counts when it decodes: the pixels decoded.
inline constexpr const char* kDistancesDecodedCounter = "distances decoded";

// How a pass that left its depth buffer in its own format turns it into view distances:
// into `depth` (which may be where the stored values wait), from what it kept, with the
// ids telling the background from the surfaces.
using DistanceDecoder = std::function<void(std::span<float> depth, std::span<const std::uint32_t> ids)>;

struct Frame {
  int width = 0, height = 0;
  PixelBuffer<std::uint8_t> color;  // RGBA8, row 0 at the top
  // Distance along the view axis; +infinity = background. Read it through distances():
  // a pass may leave its own depth here undecoded (the z-buffer's fast path, its values
  // as stored) with a decoder (leaveUndecoded). Mutable: decoding on first read is not a
  // change a reader of a const Frame sees.
  mutable PixelBuffer<float> depth;
  PixelBuffer<std::uint32_t> ids;   // global triangle index + 1; 0 = background
  // Why the image is known to be wrong in places (an algorithm stopped at a limit), or
  // "" when it is not: hsr render warns and records it in the PNG's description.
  std::string partial;

  Frame() = default;
  // Black, background ids, infinite depth; the rows are filled on `threads` threads, so
  // each thread first touches the pages it fills (a frame's first touch on one thread
  // was half the z-buffer's pass on counters at 1920x1080).
  Frame(int w, int h, int threads = 1);
  std::size_t pixelCount() const { return std::size_t(width) * std::size_t(height); }

  // The view distances: decoded on the first call when the pass left them undecoded, and
  // then counted as "distances decoded" in `stats` (when given); once only. The first call
  // is not to be made from several threads at once.
  const PixelBuffer<float>& distances(Stats* stats = nullptr) const;
  // What a pass that keeps its depth in its own format leaves: the decoder distances()
  // will run. An empty one: `depth` holds distances (as a pass that writes them leaves it).
  void leaveUndecoded(DistanceDecoder decoder) { decoder_ = std::move(decoder); }
  bool decoded() const { return !decoder_; }

 private:
  mutable DistanceDecoder decoder_;
};

// A colour, 8 bits per channel.
using Rgb = std::array<std::uint8_t, 3>;

// Decodes an --ids image pixel: (R << 16 | G << 8 | B) = global triangle index + 1.
inline std::uint32_t idFromRgb(const std::uint8_t* rgb) {
  return std::uint32_t(rgb[0]) << 16 | std::uint32_t(rgb[1]) << 8 | rgb[2];
}

// Temporary files of OutputFiles start with this prefix (then the process id and the
// extension), in the final file's folder.
std::string partialFilePrefix(const std::filesystem::path& final);

class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();  // removes the temporary files of an uncommitted set

  // Each throws InputError naming the path when it cannot be written (missing folder,
  // wrong extension, no permission).
  void addColorPng(const std::filesystem::path& path, const Frame& frame);
  void addIdsPng(const std::filesystem::path& path, const Frame& frame);
  void addDepthExr(const std::filesystem::path& path, const Frame& frame);
  void addRgbaPng(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> rgba);
  void addText(const std::filesystem::path& path, const std::string& text);
  // For a file another program writes (gnuplot): the temporary name to write it under.
  std::filesystem::path addWrittenElsewhere(const std::filesystem::path& path);
  void commit();  // renames every file into place

 private:
  std::filesystem::path stage(const std::filesystem::path& path, const std::string& extension);
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged_;  // temporary, final
};

// Reads an image as 8 bits per channel for tests and comparisons (a PNG through libpng,
// any other format through OpenImageIO); throws InputError.
Image readImage(const std::filesystem::path& path);

}  // namespace hsr
