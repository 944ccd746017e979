#include "renderer/image/polygon_svg.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <unordered_map>

namespace hsr {

std::string visiblePolygonsSvg(const std::vector<VisiblePolygon>& polygons, const Frame& shaded) {
  // The mean colour of each triangle's pixels, in one pass over the image.
  std::unordered_map<std::uint32_t, std::array<std::uint64_t, 4>> sums;  // r, g, b, pixels
  for (std::size_t p = 0; p < shaded.pixelCount(); ++p) {
    if (shaded.ids[p] == 0) continue;
    auto& sum = sums[shaded.ids[p] - 1];
    for (int c = 0; c < 3; ++c) sum[std::size_t(c)] += shaded.color[4 * p + std::size_t(c)];
    ++sum[3];
  }
  // The background in the image's background colour (white when none shows).
  std::array<unsigned, 3> background = {255, 255, 255};
  const auto firstBackground = std::find(shaded.ids.begin(), shaded.ids.end(), 0u);
  if (firstBackground != shaded.ids.end())
    for (std::size_t c = 0; c < 3; ++c) background[c] = shaded.color[4 * std::size_t(firstBackground - shaded.ids.begin()) + c];
  char text[200];
  std::snprintf(text, sizeof text,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\">\n<rect width=\"100%%\" "
                "height=\"100%%\" fill=\"rgb(%u,%u,%u)\"/>\n",
                shaded.width, shaded.height, shaded.width, shaded.height, background[0], background[1], background[2]);
  std::string svg = text;
  for (const VisiblePolygon& polygon : polygons) {
    // A piece with no pixel center inside (a sliver) takes its triangle's colour from its
    // other pieces, or grey when none has a pixel.
    std::array<unsigned, 3> colour = {160, 160, 160};
    if (const auto found = sums.find(polygon.triangle); found != sums.end())
      for (std::size_t c = 0; c < 3; ++c) colour[c] = unsigned((found->second[c] + found->second[3] / 2) / found->second[3]);
    svg += "<polygon points=\"";
    for (std::size_t i = 0; i < polygon.corners.size(); ++i) {
      std::snprintf(text, sizeof text, "%s%.4f,%.4f", i ? " " : "", polygon.corners[i].x, polygon.corners[i].y);
      svg += text;
    }
    std::snprintf(text, sizeof text,
                  "\" fill=\"rgb(%u,%u,%u)\" stroke=\"black\" stroke-opacity=\"0.35\" stroke-width=\"0.3\" stroke-linejoin=\"round\"/>\n",
                  colour[0], colour[1], colour[2]);
    svg += text;
  }
  return svg + "</svg>\n";
}

}  // namespace hsr
