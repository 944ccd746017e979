#include "renderer/line_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "renderer/raster.hpp"

namespace hsr {

namespace {

// How one piece is drawn in a style, or nothing.
struct Pen {
  bool draw = false;
  bool dashed = false;
  std::uint8_t grey = 0;  // 0 black .. 255 white
};

Pen penFor(int qi, LineStyle style) {
  if (qi == 0) return {true, false, 0};
  if (style == LineStyle::visible) return {};
  if (style == LineStyle::qi && qi >= 2) return {true, true, 204};
  return {true, true, 136};
}

// The drawn parts of [begin, end] of an edge of `length` pixels: all of it, or its dashes,
// which are laid from the edge's start so that neighbouring pieces continue one pattern.
template <typename Part>
void forEachStroke(const Pen& pen, double length, double begin, double end, Part&& part) {
  if (!pen.dashed) return part(begin, end);
  const double period = kDashPixels + kGapPixels;
  if (length <= 0) return;
  for (double start = std::floor(begin * length / period) * period; start < end * length; start += period) {
    const double from = std::max(begin, start / length), to = std::min(end, (start + kDashPixels) / length);
    if (from < to) part(from, to);
  }
}

// The z component of the cross product of two vectors in the image plane.
double cross(const dvec2& a, const dvec2& b) { return a.x * b.y - a.y * b.x; }

// The pieces in drawing order: hidden ones first, so visible lines lie on top.
std::vector<const LineSegment*> drawingOrder(const LineSet& lines) {
  std::vector<const LineSegment*> order;
  for (const LineSegment& segment : lines.segments) order.push_back(&segment);
  std::stable_sort(order.begin(), order.end(), [](const LineSegment* a, const LineSegment* b) { return !a->visible() && b->visible(); });
  return order;
}

}  // namespace

std::string lineSetSvg(const LineSet& lines, LineStyle style) {
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(lines.width) + "\" height=\"" +
                    std::to_string(lines.height) + "\" viewBox=\"0 0 " + std::to_string(lines.width) + " " +
                    std::to_string(lines.height) + "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  // Strokes that continue one another (each solid, in the same grey, starting where the
  // last ended) become one <polyline>, a point dropped where it lies on the straight line
  // between its neighbours: the floating horizon draws a curve as hundreds of pieces a
  // pixel long, which as one <line> each made a drawing megabytes large.
  std::vector<dvec2> path;
  Pen pathPen;
  char text[160];
  const auto stroke = [](const Pen& pen) {
    char attributes[128];
    std::snprintf(attributes, sizeof attributes, "\" stroke=\"rgb(%d,%d,%d)\" stroke-width=\"%g\" stroke-linecap=\"round\"", pen.grey,
                  pen.grey, pen.grey, kLineWidthPixels);
    return std::string(attributes);
  };
  const auto flush = [&] {
    if (path.size() == 2) {
      std::snprintf(text, sizeof text, "<line x1=\"%.3f\" y1=\"%.3f\" x2=\"%.3f\" y2=\"%.3f", path[0].x, path[0].y, path[1].x,
                    path[1].y);
      svg += text;
      svg += stroke(pathPen) + "/>\n";
    } else if (path.size() > 2) {
      svg += "<polyline points=\"";
      for (std::size_t i = 0; i < path.size(); ++i) {
        std::snprintf(text, sizeof text, "%s%.3f,%.3f", i ? " " : "", path[i].x, path[i].y);
        svg += text;
      }
      svg += "\" fill=\"none" + stroke(pathPen) + " stroke-linejoin=\"round\"/>\n";
    }
    path.clear();
  };
  for (const LineSegment* segment : drawingOrder(lines)) {
    const Pen pen = penFor(segment->qi, style);
    if (!pen.draw) continue;
    const FeatureEdge& edge = lines.edges[segment->edge];
    forEachStroke(pen, edge.lengthPixels(), segment->begin, segment->end, [&](double from, double to) {
      const dvec2 a = edge.pixelAt(from), b = edge.pixelAt(to);
      const bool continues = !path.empty() && !pen.dashed && !pathPen.dashed && pen.grey == pathPen.grey &&
                             glm::length(path.back() - a) < 1e-6;
      if (!continues) {
        flush();
        path = {a};
        pathPen = pen;
      }
      const std::size_t n = path.size();
      const bool straightOn = n >= 2 && std::abs(cross(path[n - 1] - path[n - 2], b - path[n - 1])) <=
                                            1e-12 * glm::length(path[n - 1] - path[n - 2]) * glm::length(b - path[n - 1]) &&
                              glm::dot(path[n - 1] - path[n - 2], b - path[n - 1]) > 0;
      if (straightOn) path.back() = b;
      else path.push_back(b);
    });
  }
  flush();
  svg += "</svg>\n";
  return svg;
}

Frame lineSetFrame(const LineSet& lines, LineStyle style) {
  Frame frame(lines.width, lines.height);
  std::fill(frame.color.begin(), frame.color.end(), std::uint8_t{255});
  for (const LineSegment* segment : drawingOrder(lines)) {
    const Pen pen = penFor(segment->qi, style);
    if (!pen.draw) continue;
    const FeatureEdge& edge = lines.edges[segment->edge];
    forEachStroke(pen, edge.lengthPixels(), segment->begin, segment->end, [&](double from, double to) {
      rasterizeLine(edge.pixelAt(from), edge.pixelAt(to), kLineWidthPixels, lines.width, lines.height, [&](int x, int y) {
        std::uint8_t* pixel = &frame.color[(std::size_t(y) * std::size_t(lines.width) + std::size_t(x)) * 4];
        pixel[0] = pixel[1] = pixel[2] = pen.grey;
      });
    });
  }
  return frame;
}

}  // namespace hsr
