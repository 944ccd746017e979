#include "renderer/lines/line_errors.hpp"

#include <algorithm>

#include "renderer/lines/line_drawing.hpp"
#include "renderer/raster/raster.hpp"
#include "renderer/util/error.hpp"

namespace hsr {
namespace {

// The parts of sorted disjoint intervals `from` not covered by `minus`.
std::vector<Interval> difference(const std::vector<Interval>& from, const std::vector<Interval>& minus) {
  std::vector<Interval> result;
  for (Interval piece : from) {
    for (const Interval& cut : minus) {
      if (cut.end <= piece.begin || cut.begin >= piece.end) continue;
      if (cut.begin > piece.begin) result.push_back({piece.begin, cut.begin});
      piece.begin = std::max(piece.begin, cut.end);
      if (piece.begin >= piece.end) break;
    }
    if (piece.begin < piece.end) result.push_back(piece);
  }
  return result;
}

}  // namespace

double strayDrawnLength(const LineSet& lines, std::span<const EdgeVisibility> truth) {
  HSR_CHECK(truth.size() == lines.edges.size());
  const std::vector<EdgeVisibility> drawn = edgeVisibility(lines);
  const auto visibleAt = [&](std::size_t edge, double u) {
    return std::any_of(truth[edge].visible.begin(), truth[edge].visible.end(), [&](const Interval& v) { return v.begin <= u && u <= v.end; });
  };
  const auto onAVisibleLine = [&](std::size_t edge, const dvec2& at) {
    for (std::size_t other = 0; other < lines.edges.size(); ++other)
      for (const Interval& v : truth[other].visible)
        if (other != edge && squaredDistanceToSegment(at, lines.edges[other].pixelAt(v.begin), lines.edges[other].pixelAt(v.end)) < 1e-12)
          return true;
    return false;
  };
  double stray = 0;
  for (std::size_t e = 0; e < lines.edges.size(); ++e) {
    const double length = lines.edges[e].lengthPixels();
    if (length == 0) continue;
    const double step = 0.5 / length;
    for (const Interval& part : drawn[e].visible)
      for (double u = part.begin + step / 2; u < part.end; u += step)
        if (!visibleAt(e, u) && !onAVisibleLine(e, lines.edges[e].pixelAt(u))) stray += std::min(step, part.end - u) * length;
  }
  return stray;
}

std::vector<std::uint8_t> lineErrorMap(const LineSet& lines, std::span<const EdgeVisibility> truth) {
  HSR_CHECK(truth.size() == lines.edges.size());
  LineErrorPicture picture(lines.width, lines.height);
  const std::vector<EdgeVisibility> drawn = edgeVisibility(lines);
  for (std::size_t e = 0; e < lines.edges.size(); ++e) picture.parts(lines.edges[e], truth[e].visible, kLineWidthPixels, kExactLineGrey);
  for (std::size_t e = 0; e < lines.edges.size(); ++e) {
    picture.parts(lines.edges[e], difference(drawn[e].visible, truth[e].visible), kErrorLineWidth, kWronglyDrawnRed);
    picture.parts(lines.edges[e], difference(truth[e].visible, drawn[e].visible), kErrorLineWidth, kWronglyHiddenBlue);
  }
  return picture.take();
}

}  // namespace hsr
