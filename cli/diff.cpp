// hsr diff: image regression for scripts. The numbers OpenImageIO's compare gives,
// an optional heat map, and the exit status: 0 within tolerance, 1 beyond.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli/commands.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/image/image_library.hpp"
#include "renderer/util/error.hpp"

namespace hsr::cli {

int diff(const DiffOptions& options) {
  if (!(options.tolerance >= 0 && options.tolerance <= 1))
    throw InputError("--tolerance " + std::to_string(options.tolerance) + ": expected a channel difference in [0, 1]");
  const Image first = readImage(options.first), second = readImage(options.second);
  if (first.width != second.width || first.height != second.height || first.channels != second.channels)
    throw InputError(options.second + ": is " + std::to_string(second.width) + "x" + std::to_string(second.height) + " with " +
                     std::to_string(second.channels) + " channels; expected " + std::to_string(first.width) + "x" +
                     std::to_string(first.height) + " with " + std::to_string(first.channels) + " like " + options.first);

  ImageComparison result;
  if (const std::string error = imageLibrary().compare(first, second, options.tolerance, result); !error.empty())
    throw InputError(options.first + ": cannot compare with " + options.second + ": " + error);
  OutputFiles files;  // written only once everything has succeeded
  if (!options.heatmap.empty()) {
    // The first image dimmed to grey; each differing pixel in red, brighter the larger its
    // largest channel difference, and full red beyond the tolerance.
    std::vector<std::uint8_t> heat(std::size_t(first.width) * std::size_t(first.height) * 4);
    const std::size_t channels = std::size_t(first.channels);
    for (std::size_t pixel = 0; pixel < std::size_t(first.width) * std::size_t(first.height); ++pixel) {
      const std::uint8_t* a = &first.pixels[pixel * channels];
      const std::uint8_t* b = &second.pixels[pixel * channels];
      int largest = 0;
      for (std::size_t c = 0; c < channels; ++c) largest = std::max(largest, std::abs(int(a[c]) - int(b[c])));
      const int colorChannels = int(std::min<std::size_t>(channels, 3));
      int sum = 0;
      for (int c = 0; c < colorChannels; ++c) sum += a[c];
      std::uint8_t* out = &heat[4 * pixel];
      const auto grey = static_cast<std::uint8_t>(30 + sum / colorChannels / 4);
      out[0] = out[1] = out[2] = grey;
      out[3] = 255;
      if (largest > 0) {
        const bool beyond = largest / 255.0 > options.tolerance;
        out[0] = beyond ? 255 : static_cast<std::uint8_t>(std::min(255, 120 + largest * 4));
        out[1] = out[2] = beyond ? 0 : 60;
      }
    }
    files.addRgbaPng(options.heatmap, first.width, first.height, heat);
  }
  const double pixels = double(first.width) * first.height;
  std::printf("mean error %.6g, rms %.6g, PSNR %.2f dB, max error %.6g at (%d, %d) channel %d\n", result.meanError,
              result.rmsError, result.psnr, result.maxError, result.maxX, result.maxY, result.maxChannel);
  std::printf("pixels over tolerance %.6g: %llu (%.4f%%)\n", options.tolerance, static_cast<unsigned long long>(result.failing),
              100.0 * double(result.failing) / pixels);

  files.commit();
  return result.failing == 0 ? 0 : 1;
}

}  // namespace hsr::cli
