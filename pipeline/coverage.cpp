#include "pipeline/coverage.hpp"

#include "renderer/util/parallel.hpp"

namespace hsr::pipeline {

void shadeCoverage(const PreparedScene& scene, const PixelCoverage& coverage, PixelShader<float>& shader, int threads, Frame& frame,
                   Stats& stats) {
  PhaseTimer timer(stats, "shading");
  std::vector<std::uint32_t> shown;
  shown.reserve(coverage.surfaces.size());
  for (const CoveredSurface& surface : coverage.surfaces) shown.push_back(surface.triangle);
  shader.setUp(shown, threads, stats);
  const dvec3 background = scene.scene().background;
  std::vector<ShadingCounts> counts(static_cast<std::size_t>(frame.height));
  parallelFor(static_cast<std::size_t>(frame.height), threads, [&](std::size_t y, int) {
    for (int x = 0; x < frame.width; ++x) {
      const std::size_t pixel = y * std::size_t(frame.width) + std::size_t(x);
      dvec3 color(0);
      double shares = 0;
      for (std::uint32_t s = coverage.first[pixel]; s < coverage.first[pixel + 1]; ++s) {
        const CoveredSurface& surface = coverage.surfaces[s];
        color += double(surface.share) * dvec3(shader.shade(surface.triangle, x, int(y), counts[y]));
        shares += surface.share;
      }
      color += std::max(0.0, 1 - shares) * background;
      std::uint8_t* rgba = frame.color.data() + 4 * pixel;
      rgba[0] = channelByte(color.x), rgba[1] = channelByte(color.y), rgba[2] = channelByte(color.z), rgba[3] = 255;
    }
  });
  ShadingCounts total;
  for (const ShadingCounts& row : counts) total += row;
  total.addTo(stats);
}

}  // namespace hsr::pipeline
