#include "renderer/image/frame.hpp"

#include <algorithm>
#include <fstream>
#include <limits>

#include <unistd.h>

#include "renderer/image/image_library.hpp"
#include "renderer/image/png.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr {

std::string partialFilePrefix(const std::filesystem::path& final) {
  std::string prefix(1, '.');
  prefix += final.stem().string();
  prefix += ".partial-";
  return prefix;
}

Frame::Frame(int w, int h, int threads)
    : width(w), height(h), color(pixelCount() * 4), depth(pixelCount()), ids(pixelCount()) {
  parallelFor(std::size_t(h), threads, [&](std::size_t row, int) {
    const std::size_t first = row * std::size_t(w), end = first + std::size_t(w);
    std::fill(color.begin() + std::ptrdiff_t(first * 4), color.begin() + std::ptrdiff_t(end * 4), std::uint8_t(0));
    std::fill(depth.begin() + std::ptrdiff_t(first), depth.begin() + std::ptrdiff_t(end), std::numeric_limits<float>::infinity());
    std::fill(ids.begin() + std::ptrdiff_t(first), ids.begin() + std::ptrdiff_t(end), std::uint32_t(0));
  });
}

const PixelBuffer<float>& Frame::distances(Stats* stats) const {
  if (decoder_) {
    decoder_(depth, ids);
    decoder_ = nullptr;
    if (stats) stats->add(kDistancesDecodedCounter, static_cast<std::int64_t>(pixelCount()));
  }
  return depth;
}

OutputFiles::~OutputFiles() {
  for (const auto& [temporary, final] : staged_) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
  }
}

std::filesystem::path OutputFiles::stage(const std::filesystem::path& path, const std::string& extension) {
  if (path.extension() != extension)
    throw InputError(path.string() + ": expected a file name ending in " + extension);
  const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
  if (!std::filesystem::is_directory(folder))
    throw InputError(path.string() + ": the folder " + folder.string() + " does not exist");
  // Same folder, same extension (an image's format goes by it), a name no one else uses.
  std::filesystem::path temporary = path;
  temporary.replace_filename(partialFilePrefix(path) + std::to_string(::getpid()) + extension);
  staged_.emplace_back(temporary, path);
  return temporary;
}

void OutputFiles::addColorPng(const std::filesystem::path& path, const Frame& frame) {
  HSR_CHECK(frame.color.size() == frame.pixelCount() * 4);
  const auto temporary = stage(path, ".png");
  // A partial image says so in the file itself, not only on the terminal.
  writePng(temporary, frame.width, frame.height, 4, frame.color.data(),
           frame.partial.empty() ? "" : "partial image: " + frame.partial);
}

void OutputFiles::addRgbaPng(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> rgba) {
  HSR_CHECK(rgba.size() == std::size_t(width) * std::size_t(height) * 4);
  const auto temporary = stage(path, ".png");
  writePng(temporary, width, height, 4, rgba.data());
}

void OutputFiles::addText(const std::filesystem::path& path, const std::string& text) {
  const auto temporary = stage(path, path.extension().string());
  std::ofstream file(temporary, std::ios::binary);
  file << text;
  file.close();
  if (!file) throw InputError(path.string() + ": cannot write the file");
}

std::filesystem::path OutputFiles::addWrittenElsewhere(const std::filesystem::path& path) {
  return stage(path, path.extension().string());
}

void OutputFiles::addIdsPng(const std::filesystem::path& path, const Frame& frame) {
  const auto temporary = stage(path, ".png");
  std::vector<std::uint8_t> rgb(frame.pixelCount() * 3);
  for (std::size_t i = 0; i < frame.pixelCount(); ++i) {
    rgb[3 * i + 0] = static_cast<std::uint8_t>(frame.ids[i] >> 16);
    rgb[3 * i + 1] = static_cast<std::uint8_t>(frame.ids[i] >> 8);
    rgb[3 * i + 2] = static_cast<std::uint8_t>(frame.ids[i]);
  }
  writePng(temporary, frame.width, frame.height, 3, rgb.data());
}

void OutputFiles::addDepthExr(const std::filesystem::path& path, const Frame& frame) {
  const auto temporary = stage(path, ".exr");
  const std::string error = imageLibrary().writeDepthExr(temporary.string(), frame.width, frame.height, frame.distances().data());
  if (!error.empty()) throw InputError(path.string() + ": cannot write the image: " + error);
}

void OutputFiles::commit() {
  for (const auto& [temporary, final] : staged_) std::filesystem::rename(temporary, final);
  staged_.clear();
}

Image readImage(const std::filesystem::path& path) {
  if (path.extension() == ".png") return readPng(path);
  Image image;
  const std::string error = imageLibrary().readImage(path.string(), image);
  if (!error.empty()) throw InputError(path.string() + ": cannot read the image: " + error);
  return image;
}

}  // namespace hsr
