#include "renderer/image/png.hpp"

#include <csetjmp>
#include <cstdio>
#include <memory>

#include <png.h>

#include "renderer/util/error.hpp"

namespace hsr {
namespace {

// libpng reports an error by longjmp-ing out of the call that failed. The jump crosses
// only this function's plain C state, so no C++ destructor is skipped; its message is
// kept in `error` and thrown as an exception once back in C++.
bool writeRows(std::FILE* file, int width, int height, int channels, const std::uint8_t* pixels, const char* description,
               char (&error)[256]) {
  png_structp png = png_create_write_struct(
      PNG_LIBPNG_VER_STRING, error,
      [](png_structp failing, png_const_charp message) {
        std::snprintf(static_cast<char*>(png_get_error_ptr(failing)), 256, "%s", message);
        png_longjmp(failing, 1);
      },
      [](png_structp, png_const_charp) {});  // warnings: nothing a reader of the file would notice
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, channels == 4 ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_text text{};
  if (description[0] != '\0') {
    text.compression = PNG_TEXT_COMPRESSION_NONE;
    text.key = const_cast<char*>("Description");
    text.text = const_cast<char*>(description);
    png_set_text(png, info, &text, 1);
  }
  png_write_info(png, info);
  const std::size_t stride = std::size_t(width) * std::size_t(channels);
  for (int y = 0; y < height; ++y) png_write_row(png, pixels + std::size_t(y) * stride);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void writePng(const std::filesystem::path& path, int width, int height, int channels, const std::uint8_t* pixels,
              const std::string& description) {
  HSR_CHECK(channels == 3 || channels == 4);
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "wb"), std::fclose);
  if (!file) throw InputError(path.string() + ": cannot write the image: cannot create the file");
  char error[256] = "the disk refused the data";
  if (!writeRows(file.get(), width, height, channels, pixels, description.c_str(), error) || std::ferror(file.get()))
    throw InputError(path.string() + ": cannot write the image: " + error);
}

Image readPng(const std::filesystem::path& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw InputError(path.string() + ": cannot read the image: " + png.message);
  // The file's own channels, as 8-bit sRGB values (a 16-bit file is rounded to 8 bits).
  png.format &= ~png_uint_32(PNG_FORMAT_FLAG_COLORMAP | PNG_FORMAT_FLAG_LINEAR);
  Image image{int(png.width), int(png.height), int(PNG_IMAGE_SAMPLE_CHANNELS(png.format)), {}};
  image.pixels.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    throw InputError(path.string() + ": cannot read the image: " + message);
  }
  return image;
}

}  // namespace hsr
