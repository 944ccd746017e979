#include "renderer/shading/fog.hpp"

#include <algorithm>
#include <cmath>

#include "renderer/shading/shading.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/parallel.hpp"
#include "renderer/util/portable_math.hpp"

namespace hsr {

double fogClearFraction(const FogSettings& fog, double distance) {
  if (fog.kind == FogSettings::Kind::exponential) return portable::exp(-fog.density * distance);
  return std::clamp((fog.end - distance) / (fog.end - fog.start), 0.0, 1.0);
}

void applyFog(const FogSettings& fog, Frame& frame, int threads, Stats& stats) {
  PhaseTimer timer(stats, "fog");
  const PixelBuffer<float>& distance = frame.distances(&stats);
  std::vector<std::int64_t> blends(static_cast<std::size_t>(frame.height), 0);
  parallelFor(static_cast<std::size_t>(frame.height), threads, [&](std::size_t row, int) {
    std::int64_t rowBlends = 0;  // stored once: neighbouring rows' counts share cache lines
    for (int x = 0; x < frame.width; ++x) {
      const std::size_t pixel = row * std::size_t(frame.width) + std::size_t(x);
      if (frame.ids[pixel] == conventions::kBackgroundId) continue;
      const double clear = fogClearFraction(fog, distance[pixel]);
      std::uint8_t* rgba = &frame.color[4 * pixel];
      for (int c = 0; c < 3; ++c) rgba[c] = channelByte(clear * rgba[c] / 255.0 + (1 - clear) * fog.color[c]);
      ++rowBlends;
    }
    blends[row] = rowBlends;
  });
  std::int64_t total = 0;
  for (std::int64_t count : blends) total += count;
  stats.add("fog blends", total);
}

}  // namespace hsr
