// PNG files in a build of the core alone (HSR_CORE_ONLY: arm64 under test, WebAssembly),
// which has no libpng: asking for one says so. The browser draws its images on a canvas,
// and the cross-target check compares hashes of the pixels, not files.
#include "renderer/image/png.hpp"

#include "renderer/util/error.hpp"

namespace hsr {

void writePng(const std::filesystem::path& path, int, int, int, const std::uint8_t*, const std::string&) {
  throw InputError(path.string() + ": this build of hsr has no libpng to write PNG files with");
}

Image readPng(const std::filesystem::path& path) {
  throw InputError(path.string() + ": this build of hsr has no libpng to read PNG files with");
}

}  // namespace hsr
