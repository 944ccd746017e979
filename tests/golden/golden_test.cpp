// Golden images: every scene under scenes/ rendered with the z-buffer and compared with
// images/golden/zbuffer/<scene>.png by OpenImageIO's ImageBufAlgo::compare.
//
// Tolerance: a pixel fails when any channel differs by more than 2/255 (lighting
// rounded differently by another libm), and an image fails when more than 0.05% of its
// pixels fail (a few ids flipped by a one-ulp vertex difference). On the CI machine
// kind the output is bit-identical; the slack is for other machines.
//
// HSR_UPDATE_GOLDEN=1 rewrites the goldens, but only for scenes where the independent
// check agrees: the full-frame and one-scanline z-buffers must give identical ids.
#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include <cstdlib>

#include "test_support.hpp"

namespace hsr {
namespace {

constexpr int kGoldenWidth = 320;
constexpr float kChannelTolerance = 2.0f / 255 + 1e-6f;
constexpr double kFailingPixelFraction = 0.0005;

std::vector<std::string> allScenes() {
  std::vector<std::string> scenes;
  const auto root = test::sourcePath("scenes");
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root))
    if (entry.path().extension() == ".toml")
      scenes.push_back(std::filesystem::relative(entry.path(), root).replace_extension().string());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

OIIO::ImageBuf toImageBuf(const Frame& frame) {
  OIIO::ImageBuf image(OIIO::ImageSpec(frame.width, frame.height, 4, OIIO::TypeDesc::UINT8));
  image.set_pixels(image.roi(), OIIO::TypeDesc::UINT8, frame.color.data());
  return image;
}

class Golden : public testing::TestWithParam<std::string> {};

TEST_P(Golden, ZBufferMatchesTheGoldenImage) {
  const std::string name = GetParam();
  const Scene scene = loadScene(test::sourcePath("scenes/" + name + ".toml"));
  PreparedScene prepared(scene);
  prepared.setSize(kGoldenWidth, std::max(1, kGoldenWidth * scene.height / scene.width));
  const Frame frame = test::renderZBuffer(prepared, zbuffer::Variant::full, DepthFormat::float32, 2);
  const std::filesystem::path golden = test::sourcePath("images/golden/zbuffer/" + name + ".png");

  if (std::getenv("HSR_UPDATE_GOLDEN")) {
    const Frame scanline = test::renderZBuffer(prepared, zbuffer::Variant::scanline, DepthFormat::float32, 2);
    ASSERT_EQ(frame.ids, scanline.ids) << "refusing to update " << golden << ": full-frame and scanline disagree";
    std::filesystem::create_directories(golden.parent_path());
    OutputFiles outputs;
    outputs.addColorPng(golden, frame);
    outputs.commit();
    GTEST_SKIP() << "updated " << golden;
  }

  ASSERT_TRUE(std::filesystem::exists(golden)) << golden << " is missing (HSR_UPDATE_GOLDEN=1 creates it)";
  const OIIO::ImageBuf expected(golden.string());
  const OIIO::ImageBuf actual = toImageBuf(frame);
  const auto result = OIIO::ImageBufAlgo::compare(actual, expected, kChannelTolerance, kChannelTolerance);
  ASSERT_FALSE(result.error) << "cannot compare with " << golden << ": " << OIIO::geterror();
  const double failing = double(result.nfail) / double(frame.pixelCount());
  if (failing > kFailingPixelFraction) {
    // Leave the evidence where a person can look at it.
    std::string flat = name;
    std::replace(flat.begin(), flat.end(), '/', '-');
    const auto actualPath = test::outputPath("golden-" + flat + ".actual.png");
    const auto diffPath = test::outputPath("golden-" + flat + ".diff.png");
    actual.write(actualPath.string());
    const OIIO::ImageBuf difference = OIIO::ImageBufAlgo::maxchan(OIIO::ImageBufAlgo::absdiff(actual, expected));
    OIIO::ImageBufAlgo::color_map(difference, 0, "inferno").write(diffPath.string());
    ADD_FAILURE() << name << ": " << result.nfail << " pixels differ by more than 2/255 (" << 100 * failing
                  << "%, allowed " << 100 * kFailingPixelFraction << "%), max error " << result.maxerror << " at ("
                  << result.maxx << ", " << result.maxy << ")\n  actual: " << actualPath << "\n  diff heat map: " << diffPath;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, Golden, testing::ValuesIn(allScenes()), [](const testing::TestParamInfo<std::string>& param) {
  std::string name = param.param;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

}  // namespace
}  // namespace hsr
