// The OpenImageIO module (renderer/image/image_library.hpp): built as its own shared library and
// loaded by the hsr program only when it needs one of these, so that OpenImageIO's
// dependencies are loaded then and not on every command.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "renderer/image/frame.hpp"
#include "renderer/image/image_library.hpp"

namespace hsr {
namespace {

// An ImageBuf over the image's own pixels, not a copy: drawing into it draws into the
// image. OpenImageIO takes the buffer as writable; the operations given a const image
// only read it.
OIIO::ImageBuf wrap(const Image& image) {
  return OIIO::ImageBuf(OIIO::ImageSpec(image.width, image.height, image.channels, OIIO::TypeDesc::UINT8),
                        const_cast<std::uint8_t*>(image.pixels.data()));
}

Image unwrap(const OIIO::ImageBuf& buffer) {
  const OIIO::ImageSpec& spec = buffer.spec();
  Image image{spec.width, spec.height, spec.nchannels, {}};
  image.pixels.resize(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
  buffer.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, image.pixels.data());
  return image;
}

std::string writeDepthExr(const std::string& path, int width, int height, const float* depth) {
  OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"Z"};
  spec.z_channel = 0;
  auto output = OIIO::ImageOutput::create(path);
  if (!output) return "no writer for this extension";
  if (!output->open(path, spec) || !output->write_image(spec.format, depth) || !output->close()) return output->geterror();
  return "";
}

std::string readImage(const std::string& path, Image& image) {
  auto input = OIIO::ImageInput::open(path);
  if (!input) return OIIO::geterror();
  const OIIO::ImageSpec& spec = input->spec();
  image = Image{spec.width, spec.height, spec.nchannels, {}};
  image.pixels.resize(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, image.pixels.data())) return input->geterror();
  return "";
}

std::string compare(const Image& first, const Image& second, double tolerance, ImageComparison& result) {
  const auto limit = static_cast<float>(tolerance);
  const OIIO::ImageBufAlgo::CompareResults compared = OIIO::ImageBufAlgo::compare(wrap(first), wrap(second), limit, limit);
  result = {compared.meanerror, compared.rms_error,  compared.PSNR,   compared.maxerror,
            compared.maxx,      compared.maxy,       compared.maxc,   std::uint64_t(compared.nfail)};
  return "";
}

std::string resize(const Image& image, int width, int height, Image& resized) {
  const OIIO::ImageBuf result =
      OIIO::ImageBufAlgo::resize(wrap(image), "", 0, OIIO::ROI(0, width, 0, height, 0, 1, 0, image.channels));
  if (result.has_error()) return result.geterror();
  resized = unwrap(result);
  return "";
}

std::string drawText(Image& canvas, int x, int baseline, const std::string& text, int size, const std::string& font,
                     const float (&rgba)[4]) {
  OIIO::ImageBuf buffer = wrap(canvas);
  if (!OIIO::ImageBufAlgo::render_text(buffer, x, baseline, text, size, font, rgba)) return buffer.geterror();
  return "";
}

std::string textWidth(const std::string& text, int size, const std::string& font, int& width) {
  const OIIO::ROI box = OIIO::ImageBufAlgo::text_size(text, size, font);
  if (!box.defined()) return "cannot measure text in that font";
  width = box.width();
  return "";
}

std::string writeAnimation(const std::string& path, const std::vector<Image>& frames, int framesPerSecond) {
  auto output = OIIO::ImageOutput::create(path);
  if (!output) return "no writer for this extension";
  if (!output->supports("multiimage")) return "this format holds one image, not an animation";
  std::vector<OIIO::ImageSpec> specs;
  for (const Image& frame : frames) {
    OIIO::ImageSpec& spec = specs.emplace_back(frame.width, frame.height, frame.channels, OIIO::TypeDesc::UINT8);
    const int rate[2] = {framesPerSecond, 1};
    spec.attribute("FramesPerSecond", OIIO::TypeRational, rate);
    spec.attribute("oiio:LoopCount", 0);  // play forever
  }
  if (!output->open(path, int(specs.size()), specs.data())) return output->geterror();
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (f > 0 && !output->open(path, specs[f], OIIO::ImageOutput::AppendSubimage)) return output->geterror();
    if (!output->write_image(OIIO::TypeDesc::UINT8, frames[f].pixels.data())) return output->geterror();
  }
  if (!output->close()) return output->geterror();
  return "";
}

const ImageLibrary kLibrary{writeDepthExr, readImage, compare, resize, drawText, textWidth, writeAnimation};

}  // namespace
}  // namespace hsr

extern "C" const hsr::ImageLibrary* hsrImageLibrary() { return &hsr::kLibrary; }
