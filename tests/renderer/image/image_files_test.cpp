// The image files every render writes: PNG through libpng, read back the same by libpng
// and by OpenImageIO (the module loaded on use), and bad files refused with their path.
#include <gtest/gtest.h>

#include <fstream>

#include "renderer/image/frame.hpp"
#include "renderer/image/image_library.hpp"
#include "renderer/image/png.hpp"
#include "renderer/util/error.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

// A small image whose every channel of every pixel differs from its neighbours'.
std::vector<std::uint8_t> pattern(int width, int height, int channels) {
  std::vector<std::uint8_t> pixels(std::size_t(width) * std::size_t(height) * std::size_t(channels));
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<std::uint8_t>(i * 37 + i / 7);
  return pixels;
}

TEST(ImageFiles, PngKeepsEveryByteForLibpngAndOpenImageIO) {
  for (const int channels : {3, 4}) {
    const auto path = test::outputPath("png-round-trip-" + std::to_string(channels) + ".png");
    const std::vector<std::uint8_t> pixels = pattern(13, 7, channels);
    writePng(path, 13, 7, channels, pixels.data(), "partial image: a test");
    const Image ours = readImage(path);
    EXPECT_EQ(ours.width, 13);
    EXPECT_EQ(ours.height, 7);
    EXPECT_EQ(ours.channels, channels);
    EXPECT_EQ(ours.pixels, pixels);
    // The description is in the file, where an image viewer shows it.
    std::ifstream file(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    EXPECT_NE(bytes.find("partial image: a test"), std::string::npos);
    // OpenImageIO reads the same file the same, once opaque: it premultiplies color by
    // alpha on reading, which libpng (and hsr) leave alone.
    std::vector<std::uint8_t> opaque = pixels;
    if (channels == 4)
      for (std::size_t alpha = 3; alpha < opaque.size(); alpha += 4) opaque[alpha] = 255;
    writePng(path, 13, 7, channels, opaque.data());
    Image theirs;
    ASSERT_EQ(imageLibrary().readImage(path.string(), theirs), "");
    EXPECT_EQ(theirs.channels, channels);
    EXPECT_EQ(theirs.pixels, opaque);
  }
}

TEST(ImageFiles, ExrDepthIsReadBackByOpenImageIO) {
  Frame frame(4, 3);
  for (std::size_t i = 0; i < frame.depth.size(); ++i) frame.depth[i] = 0.5f + float(i);
  const auto path = test::outputPath("depth-round-trip.exr");
  OutputFiles files;
  files.addDepthExr(path, frame);
  files.commit();
  Image image;
  ASSERT_EQ(imageLibrary().readImage(path.string(), image), "");
  EXPECT_EQ(image.width, 4);
  EXPECT_EQ(image.height, 3);
  EXPECT_EQ(image.channels, 1);
}

TEST(ImageFiles, BadFilesAreRefusedWithTheirPath) {
  const auto notPng = test::outputPath("not-a-png.png");
  std::ofstream(notPng) << "plain text";
  try {
    readImage(notPng);
    ADD_FAILURE() << "read a text file as a PNG";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind(notPng.string() + ": cannot read the image: ", 0), 0u) << error.what();
  }
  const auto nowhere = test::outputPath("no-such-folder/image.png");
  const std::vector<std::uint8_t> pixels = pattern(2, 2, 3);
  try {
    writePng(nowhere, 2, 2, 3, pixels.data());
    ADD_FAILURE() << "wrote into a missing folder";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), nowhere.string() + ": cannot write the image: cannot create the file");
  }
}

}  // namespace
}  // namespace hsr
