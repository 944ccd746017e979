#include "renderer/lines/line_set.hpp"

#include <algorithm>

namespace hsr {

std::vector<EdgeVisibility> edgeVisibility(const LineSet& lines) {
  std::vector<EdgeVisibility> result(lines.edges.size());
  for (std::size_t e = 0; e < lines.edges.size(); ++e) result[e].lengthPixels = lines.edges[e].lengthPixels();
  for (const LineSegment& segment : lines.segments) {
    if (!segment.visible() || segment.end <= segment.begin) continue;
    std::vector<Interval>& visible = result[segment.edge].visible;
    if (!visible.empty() && visible.back().end >= segment.begin) visible.back().end = std::max(visible.back().end, segment.end);
    else visible.push_back({segment.begin, segment.end});
  }
  return result;
}

LineSet drawingOf(const LineSet& edges, std::span<const EdgeVisibility> visibility) {
  LineSet drawing;
  drawing.width = edges.width;
  drawing.height = edges.height;
  drawing.edges = edges.edges;
  drawing.curvePlaces = edges.curvePlaces;
  for (std::uint32_t e = 0; e < drawing.edges.size(); ++e) appendPieces(drawing, e, visibility[e].visible);
  return drawing;
}

void appendPieces(LineSet& lines, std::uint32_t edge, std::span<const Interval> visible) {
  double covered = 0;
  for (const Interval& part : visible) {
    if (part.begin > covered) lines.segments.push_back({edge, covered, part.begin, LineSegment::kHidden});
    lines.segments.push_back({edge, part.begin, part.end, 0});
    covered = part.end;
  }
  if (covered < 1) lines.segments.push_back({edge, covered, 1.0, LineSegment::kHidden});
}

}  // namespace hsr
