#include "renderer/lines/line_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "renderer/raster/raster.hpp"
#include "renderer/steps/steps.hpp"
#include "renderer/util/markup.hpp"

namespace hsr {

namespace {

// How one piece is drawn in a style, or nothing.
struct Pen {
  bool draw = false;
  bool dashed = false;
  Rgb color = {0, 0, 0};
  bool operator==(const Pen&) const = default;
};

Pen penFor(int qi, LineStyle style) {
  if (qi == 0) return {true, false, kQiColors[0]};
  if (style == LineStyle::visible) return {};
  if (style == LineStyle::qi && qi > 0) return {true, true, kQiColors[std::min<std::size_t>(std::size_t(qi), kQiColors.size() - 1)]};
  return {true, true, kHiddenLineColor};
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

EdgeNamer edgeNamesOf(const PreparedScene& scene) {
  return [&scene](const FeatureEdge& edge) {
    const auto objectOf = [&](std::uint32_t triangle) { return "\"" + scene.scene().objects[scene.instanceOf(triangle).object].name + "\""; };
    if (edge.faces[0] == FeatureEdge::kNone) return std::string();
    if (edge.kind == EdgeKind::junction && edge.faces[1] != FeatureEdge::kNone)
      return "junction where " + objectOf(edge.faces[0]) + " meets " + objectOf(edge.faces[1]);
    return std::string(edgeKindName(edge.kind)) + " edge of " + objectOf(edge.faces[0]);
  };
}

namespace {

// A stroke's <title>: what it is, and its quantitative invisibility.
std::string strokeTitle(const FeatureEdge& edge, int qi, const EdgeNamer& names) {
  std::string title = names ? names(edge) : std::string();
  if (!title.empty()) title += ", ";
  return escapedMarkup(title + "QI " + std::to_string(qi) + (qi == 0 ? " (visible)" : " (hidden)"));
}

}  // namespace

std::string lineSetSvg(const LineSet& lines, LineStyle style, const EdgeNamer& names) {
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(lines.width) + "\" height=\"" +
                    std::to_string(lines.height) + "\" viewBox=\"0 0 " + std::to_string(lines.width) + " " +
                    std::to_string(lines.height) + "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  // Strokes that continue one another (each solid, in the same grey, starting where the
  // last ended) become one <polyline>, a point dropped where it lies on the straight line
  // between its neighbours: the floating horizon draws a curve as hundreds of pieces a
  // pixel long, which as one <line> each made a drawing megabytes large.
  std::vector<dvec2> path;
  Pen pathPen;
  std::string pathTitle;
  char text[160];
  const auto stroke = [](const Pen& pen) {
    char attributes[128];
    std::snprintf(attributes, sizeof attributes, "\" stroke=\"rgb(%d,%d,%d)\" stroke-width=\"%g\" stroke-linecap=\"round\"", pen.color[0],
                  pen.color[1], pen.color[2], kLineWidthPixels);
    return std::string(attributes);
  };
  const auto flush = [&] {
    if (path.size() == 2) {
      std::snprintf(text, sizeof text, "<line x1=\"%.3f\" y1=\"%.3f\" x2=\"%.3f\" y2=\"%.3f", path[0].x, path[0].y, path[1].x,
                    path[1].y);
      svg += text;
      svg += stroke(pathPen) + "><title>" + pathTitle + "</title></line>\n";
    } else if (path.size() > 2) {
      svg += "<polyline points=\"";
      for (std::size_t i = 0; i < path.size(); ++i) {
        std::snprintf(text, sizeof text, "%s%.3f,%.3f", i ? " " : "", path[i].x, path[i].y);
        svg += text;
      }
      svg += "\" fill=\"none" + stroke(pathPen) + " stroke-linejoin=\"round\"><title>" + pathTitle + "</title></polyline>\n";
    }
    path.clear();
  };
  for (const LineSegment* segment : drawingOrder(lines)) {
    const Pen pen = penFor(segment->qi, style);
    if (!pen.draw) continue;
    const FeatureEdge& edge = lines.edges[segment->edge];
    const std::string title = strokeTitle(edge, segment->qi, names);
    forEachStroke(pen, edge.lengthPixels(), segment->begin, segment->end, [&](double from, double to) {
      const dvec2 a = edge.pixelAt(from), b = edge.pixelAt(to);
      const bool continues = !path.empty() && !pen.dashed && pen == pathPen && title == pathTitle &&
                             glm::length(path.back() - a) < 1e-6;
      if (!continues) {
        flush();
        path = {a};
        pathPen = pen;
        pathTitle = title;
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
  if (style == LineStyle::qi) {
    // The legend, top left: a sample of each pen and what it means.
    const auto entries = qiLegend();
    std::snprintf(text, sizeof text, "<rect x=\"0\" y=\"0\" width=\"150\" height=\"%zu\" fill=\"white\" fill-opacity=\"0.8\"/>\n",
                  10 + 17 * entries.size());
    svg += text;
    for (std::size_t e = 0; e < entries.size(); ++e) {
      const double y = 5 + 17 * (double(e) + 0.5);
      const Pen pen = penFor(int(e), style);
      std::snprintf(text, sizeof text, "<line x1=\"5\" y1=\"%.1f\" x2=\"27\" y2=\"%.1f", y, y);
      svg += text;
      svg += stroke(pen) + (pen.dashed ? " stroke-dasharray=\"6 4\"" : "") + "/>\n";
      std::snprintf(text, sizeof text, "<text x=\"32\" y=\"%.1f\" font-family=\"DejaVu Sans, sans-serif\" font-size=\"12\">", y + 4);
      svg += text + entries[e].second + "</text>\n";
    }
  }
  svg += "</svg>\n";
  return svg;
}

std::vector<std::pair<Rgb, std::string>> qiLegend() {
  std::vector<std::pair<Rgb, std::string>> entries;
  for (std::size_t qi = 0; qi < kQiColors.size(); ++qi)
    entries.emplace_back(kQiColors[qi], qi == 0 ? "QI 0: visible"
                                        : qi + 1 < kQiColors.size() ? "QI " + std::to_string(qi) + ": behind " + std::to_string(qi) + " surface" + (qi > 1 ? "s" : "")
                                                                  : "QI " + std::to_string(qi) + " or more");
  return entries;
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
        pixel[0] = pen.color[0], pixel[1] = pen.color[1], pixel[2] = pen.color[2];
      });
    });
  }
  if (style == LineStyle::qi) {
    Image picture{frame.width, frame.height, 4, {frame.color.begin(), frame.color.end()}};
    drawLegend(picture, qiLegend());
    frame.color.assign(picture.pixels.begin(), picture.pixels.end());
  }
  return frame;
}

}  // namespace hsr

namespace hsr {

Image lineStepPicture(const LineSet& lines, std::span<const std::uint32_t> justDecided, LineStyle style) {
  constexpr double kLabelMinimumPixels = 24;
  Image picture = blankPicture(lines.width, lines.height);
  for (const std::uint32_t e : justDecided) drawSegment(picture, lines.edges[e].pixelFrom, lines.edges[e].pixelTo, kJustDecided, 6);
  const Frame drawing = lineSetFrame(lines, style);
  for (std::size_t p = 0; p < drawing.pixelCount(); ++p) {
    const std::uint8_t* pixel = &drawing.color[4 * p];
    if (pixel[0] != 255 || pixel[1] != 255 || pixel[2] != 255) std::copy_n(pixel, 4, &picture.pixels[4 * p]);
  }
  if (style != LineStyle::qi) return picture;
  for (const LineSegment& segment : lines.segments) {
    const FeatureEdge& edge = lines.edges[segment.edge];
    if (std::find(justDecided.begin(), justDecided.end(), segment.edge) == justDecided.end() ||
        (segment.end - segment.begin) * edge.lengthPixels() < kLabelMinimumPixels)
      continue;
    // Beside the piece's middle, off the line by 10 pixels, on a white patch.
    const dvec2 along = glm::normalize(edge.pixelTo - edge.pixelFrom);
    dvec2 side{along.y, -along.x};
    if (side.y > 0) side = -side;  // above the line
    const dvec2 at = edge.pixelAt((segment.begin + segment.end) / 2) + 10.0 * side;
    const std::string label = std::to_string(segment.qi);
    for (int y = int(at.y) - 11; y <= int(at.y) + 2; ++y)
      for (int x = int(at.x) - 2; x <= int(at.x) + 8 * int(label.size()); ++x)
        if (x >= 0 && y >= 0 && x < picture.width && y < picture.height)
          std::fill_n(&picture.pixels[(std::size_t(y) * std::size_t(picture.width) + std::size_t(x)) * 4], 3, std::uint8_t{255});
    drawLabel(picture, int(at.x), int(at.y), label, penFor(segment.qi, style).color, kSmallLabelSize);
  }
  return picture;
}

std::string visibleSegmentsText(const LineSet& lines) {
  std::string text = "# visible segments, x0 y0 x1 y1 in pixels (y down)\n";
  for (const LineSegment& segment : lines.segments) {
    if (!segment.visible()) continue;
    const FeatureEdge& edge = lines.edges[segment.edge];
    const dvec2 from = edge.pixelAt(segment.begin), to = edge.pixelAt(segment.end);
    char line[128];
    std::snprintf(line, sizeof line, "%.6f %.6f %.6f %.6f\n", from.x, from.y, to.x, to.y);
    text += line;
  }
  return text;
}

}  // namespace hsr
