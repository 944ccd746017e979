// The image files every render writes: PNG through libpng, read back the same by libpng
// and by OpenImageIO (the module loaded on use), and bad files refused with their path.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <limits>

#include "renderer/image/frame.hpp"
#include "renderer/image/image_library.hpp"
#include "renderer/image/pfm.hpp"
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

// A PFM is written rows from the bottom up, little-endian, and read back as it was;
// a file that is not one, or not of the size asked for, is refused in words.
TEST(ImageFiles, PfmDepthRoundTripsAndBadOnesAreNamed) {
  const std::vector<float> topDown = {1.5f, 2.5f, 3.5f, std::numeric_limits<float>::infinity(), -0.0f, 1e-30f};
  const std::string bytes = pfmBytes(3, 2, topDown);
  ASSERT_EQ(bytes.substr(0, 12), "Pf\n3 2\n-1.0\n");
  ASSERT_EQ(bytes.size(), 12u + 6 * 4);
  EXPECT_EQ(bytes.substr(12, 4), std::string("\x00\x00\x80\x7f", 4));  // the bottom row first: +infinity
  const auto path = test::outputPath("depth.pfm");
  std::ofstream(path, std::ios::binary) << bytes;
  std::vector<float> read;
  ASSERT_EQ(readPfm(path, 3, 2, read), "");
  EXPECT_EQ(std::memcmp(read.data(), topDown.data(), topDown.size() * 4), 0);
  // Big-endian (a positive scale) reads as well.
  std::string bigEndian = "Pf\n1 1\n1.0\n";
  bigEndian += std::string("\x3f\xc0\x00\x00", 4);
  std::ofstream(path, std::ios::binary) << bigEndian;
  ASSERT_EQ(readPfm(path, 1, 1, read), "");
  EXPECT_EQ(read[0], 1.5f);

  const struct {
    std::string file, problem;
  } bad[] = {
      {"hello", "its depth image depth.pfm is not a PFM: it starts with \"hello\"; expected Pf"},
      {"PF\n3 2\n-1.0\n", "its depth image depth.pfm is a colour PFM (PF); expected Pf, one float per pixel"},
      {"Pf\n3\n", "its depth image depth.pfm: its header is not \"Pf W H SCALE\""},
      {"Pf\n3 2\nlittle\n", "its depth image depth.pfm: its scale \"little\" is not a number; expected -1.0 (little-endian)"},
      {"Pf\n3 2\n0\n", "its depth image depth.pfm: its scale is 0; expected -1.0 (little-endian) or 1.0 (big-endian)"},
      {"Pf\n2 3\n-1.0\n", "its depth image depth.pfm is 2x3; expected 3x2, the scene's size line"},
      {"Pf\n3 2\n-1.0", "its depth image depth.pfm: its header is not followed by the floats"},
      {"Pf\n3 2\n-1.0\n" + std::string(20, '\0'), "its depth image depth.pfm holds 20 bytes of floats; expected 24 (3 x 2 float32s)"},
  };
  for (const auto& [file, problem] : bad) {
    std::ofstream(path, std::ios::binary) << file;
    EXPECT_EQ(readPfm(path, 3, 2, read), problem) << file;
  }
  EXPECT_EQ(readPfm(test::outputPath("no-such-depth.pfm"), 3, 2, read), "wrote no depth image at no-such-depth.pfm");
  // A folder (or a pipe) is no file to read; a file far larger than 3 x 2 floats is
  // refused before it is read.
  const auto folder = test::outputPath("depth-folder.pfm");
  std::filesystem::create_directories(folder);
  EXPECT_EQ(readPfm(folder, 3, 2, read), "wrote no depth image at depth-folder.pfm");
  std::ofstream(path, std::ios::binary) << "Pf\n3 2\n-1.0\n" + std::string(1000, '\0');
  EXPECT_EQ(readPfm(path, 3, 2, read), "its depth image depth.pfm holds 1012 bytes; expected about 24 (3 x 2 float32s and a header)");
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
