#include "renderer/lines.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>

#include "renderer/error.hpp"
#include "renderer/raster.hpp"

namespace hsr {

int ViewerPredicates::facing(const dvec3& a, const dvec3& b, const dvec3& c) {
  // The front side is the one the normal (b - a) x (c - a) points to; the viewer is on it
  // when the eye is, or (orthographic) when the normal points against the view direction.
  if (camera_.perspective()) return exact_.orient3d(a, b, c, camera_.camera().eye);
  return exact_.facing(a, b, c, -camera_.forward());
}

int ViewerPredicates::side(const dvec3& p, const dvec3& q, const dvec3& y) {
  // orient3d(eye, p, q, y); with the eye at infinity behind the view direction f it tends
  // to a positive multiple of det[f, q - p, y - p] = facing(p, q, y, f).
  if (camera_.perspective()) return exact_.orient3d(camera_.camera().eye, p, q, y);
  return exact_.facing(p, q, y, camera_.forward());
}

std::vector<std::int8_t> viewFacing(const PreparedScene& scene, const CameraTransform& camera, Stats& stats) {
  ViewerPredicates viewer(camera);
  std::vector<std::int8_t> facing(scene.triangleCount());
  for (std::size_t t = 0; t < facing.size(); ++t) {
    const Triangle& triangle = scene.triangles()[t];
    const auto& p = scene.positions();
    facing[t] = static_cast<std::int8_t>(viewer.facing(p[triangle[0]], p[triangle[1]], p[triangle[2]]));
  }
  stats.add("facing tests", static_cast<std::int64_t>(facing.size()));
  stats.add("exact fall-backs", viewer.exact().exactFallbacks);
  return facing;
}

const char* edgeKindName(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::boundary: return "boundary";
    case EdgeKind::contour: return "contour";
    case EdgeKind::crease: return "crease";
    case EdgeKind::junction: return "junction";
    case EdgeKind::curve: return "curve";
  }
  return "?";
}

double FeatureEdge::lengthPixels() const { return glm::length(pixelTo - pixelFrom); }

double FeatureEdge::edgeParameter(double u) const {
  // s / w and 1 / w are affine in screen space; s = (u / w1) / ((1 - u) / w0 + u / w1).
  const double denominator = (1 - u) * divisorTo + u * divisorFrom;
  return denominator > 0 ? u * divisorFrom / denominator : u;
}

double FeatureEdge::projectedParameter(double s) const {
  const double denominator = (1 - s) * divisorFrom + s * divisorTo;
  return denominator > 0 ? s * divisorTo / denominator : s;
}

FeatureEdge projectEdge(const CameraTransform& camera, const dvec3& from, const dvec3& to, EdgeKind kind) {
  FeatureEdge edge;
  edge.from = from;
  edge.to = to;
  const ClipVertex a = camera.clipFromWorld(from), b = camera.clipFromWorld(to);
  edge.pixelFrom = camera.pixelFromClip(a);
  edge.pixelTo = camera.pixelFromClip(b);
  edge.divisorFrom = a.w;
  edge.divisorTo = b.w;
  edge.kind = kind;
  return edge;
}

std::vector<FeatureEdge> featureEdges(const PreparedScene& scene, const CameraTransform& camera,
                                      std::span<const std::int8_t> facing, double creaseDegrees, Stats& stats) {
  const EdgeAdjacency& adjacency = scene.edgeAdjacency(stats);
  const double creaseCosine = std::cos(creaseDegrees * std::numbers::pi / 180);
  std::vector<FeatureEdge> edges;
  for (std::uint32_t index = 0; index < adjacency.edges.size(); ++index) {
    const MeshEdge& mesh = adjacency.edges[index];
    EdgeKind kind;
    if (mesh.faceCount == 1) {
      kind = EdgeKind::boundary;
    } else if ((facing[mesh.faces[0]] > 0) != (facing[mesh.faces[1]] > 0)) {
      kind = EdgeKind::contour;
    } else if (mesh.faceCount > 2 ||
               glm::dot(scene.faceNormal(mesh.faces[0]), scene.faceNormal(mesh.faces[1])) < creaseCosine) {
      kind = EdgeKind::crease;
    } else {
      continue;
    }
    FeatureEdge edge = projectEdge(camera, scene.positions()[mesh.a], scene.positions()[mesh.b], kind);
    edge.vertexFrom = mesh.a;
    edge.vertexTo = mesh.b;
    edge.meshEdge = index;
    edges.push_back(edge);
  }
  stats.add("feature edges", static_cast<std::int64_t>(edges.size()));
  return edges;
}

std::string nearPlaneRefusal(const PreparedScene& scene) {
  const Camera& camera = scene.scene().camera;
  const CameraTransform transform(camera, scene.width(), scene.height());
  for (const Instance& instance : scene.instances()) {
    for (std::uint32_t t = instance.firstTriangle; t < instance.firstTriangle + instance.triangleCount; ++t)
      for (std::uint32_t v : scene.triangles()[t]) {
        const double d = transform.clipFromWorld(scene.positions()[v]).d;
        if (d > camera.near) continue;
        char message[256];
        std::snprintf(message, sizeof message,
                      "object '%s' reaches %.6g from the eye along the view axis, not beyond the near plane (%g): "
                      "line drawings do not clip, so every vertex must lie beyond it",
                      scene.scene().objects[instance.object].name.c_str(), d, camera.near);
        return message;
      }
  }
  return "";
}

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
  char element[320];
  for (const LineSegment* segment : drawingOrder(lines)) {
    const Pen pen = penFor(segment->qi, style);
    if (!pen.draw) continue;
    const FeatureEdge& edge = lines.edges[segment->edge];
    forEachStroke(pen, edge.lengthPixels(), segment->begin, segment->end, [&](double from, double to) {
      const dvec2 a = edge.pixelAt(from), b = edge.pixelAt(to);
      std::snprintf(element, sizeof element,
                    "<line x1=\"%.3f\" y1=\"%.3f\" x2=\"%.3f\" y2=\"%.3f\" stroke=\"rgb(%d,%d,%d)\" stroke-width=\"%g\" "
                    "stroke-linecap=\"round\"/>\n",
                    a.x, a.y, b.x, b.y, pen.grey, pen.grey, pen.grey, kLineWidthPixels);
      svg += element;
    });
  }
  svg += "</svg>\n";
  return svg;
}

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

namespace {

using Rgb = std::array<std::uint8_t, 3>;
constexpr Rgb kExactLineGrey = {187, 187, 187}, kWronglyDrawnRed = {220, 30, 30}, kWronglyHiddenBlue = {30, 60, 220};
constexpr double kErrorLineWidth = 3;  // errors drawn wider, so a short one is still seen

// An RGBA8 picture of a drawing's errors, white to start with.
class ErrorPicture {
 public:
  ErrorPicture(int width, int height)
      : width_(width), height_(height), rgba_(std::size_t(width) * std::size_t(height) * 4, 255) {}
  void line(const dvec2& a, const dvec2& b, double width, Rgb color) {
    rasterizeLine(a, b, width, width_, height_, [&](int x, int y) {
      std::uint8_t* pixel = &rgba_[(std::size_t(y) * std::size_t(width_) + std::size_t(x)) * 4];
      pixel[0] = color[0], pixel[1] = color[1], pixel[2] = color[2];
    });
  }
  // Parts of an edge; those shorter than a millionth of a pixel are the rounding of event
  // positions, not errors.
  void parts(const FeatureEdge& edge, const std::vector<Interval>& parts, double width, Rgb color) {
    for (const Interval& part : parts)
      if ((part.end - part.begin) * edge.lengthPixels() > 1e-6) line(edge.pixelAt(part.begin), edge.pixelAt(part.end), width, color);
  }
  std::vector<std::uint8_t> take() { return std::move(rgba_); }

 private:
  int width_, height_;
  std::vector<std::uint8_t> rgba_;
};

bool contains(const std::vector<Interval>& sorted, double u) {
  const auto after = std::upper_bound(sorted.begin(), sorted.end(), u, [](double x, const Interval& i) { return x < i.begin; });
  return after != sorted.begin() && u <= std::prev(after)->end;
}

// A drawing of curves looked up by curve and running coordinate.
class CurveLookup {
 public:
  CurveLookup(const LineSet& lines, std::vector<EdgeVisibility> visibility, std::size_t curves)
      : lines_(lines), visibility_(std::move(visibility)), byCurve_(curves) {
    HSR_CHECK(lines.curvePlaces.size() == lines.edges.size());
    for (std::uint32_t e = 0; e < lines.edges.size(); ++e) byCurve_.at(lines.curvePlaces[e].curve).push_back(e);
    for (auto& edges : byCurve_)
      std::sort(edges.begin(), edges.end(), [&](auto a, auto b) { return lines.curvePlaces[a].from < lines.curvePlaces[b].from; });
  }

  const LineSet& lines() const { return lines_; }
  const EdgeVisibility& visibility(std::size_t edge) const { return visibility_[edge]; }

  // The point of the curve at that coordinate, if the drawing has it, and whether it is drawn visible.
  struct Point {
    bool visible = false;
    dvec2 pixel{0};
  };
  std::optional<Point> at(std::uint32_t curve, double coordinate) const {
    const std::vector<std::uint32_t>& edges = byCurve_[curve];
    const auto after = std::upper_bound(edges.begin(), edges.end(), coordinate,
                                        [&](double c, std::uint32_t e) { return c < lines_.curvePlaces[e].from; });
    if (after == edges.begin()) return std::nullopt;
    const std::uint32_t e = *std::prev(after);
    const CurvePlace& place = lines_.curvePlaces[e];
    if (coordinate > place.to) return std::nullopt;
    const double u = lines_.edges[e].projectedParameter((coordinate - place.from) / (place.to - place.from));
    return Point{contains(visibility_[e].visible, u), lines_.edges[e].pixelAt(u)};
  }

 private:
  const LineSet& lines_;
  std::vector<EdgeVisibility> visibility_;
  std::vector<std::vector<std::uint32_t>> byCurve_;
};

// Walks every edge of `walked` in steps of at most a quarter pixel. For each step: its
// ends in pixels, its length, whether `walked` shows it, and whether `other` shows the same
// curve within kCurveTolerancePixels at the same coordinate.
template <typename Visit>
void walkCurves(const CurveLookup& walked, const CurveLookup& other, Visit&& visit) {
  const LineSet& lines = walked.lines();
  for (std::size_t e = 0; e < lines.edges.size(); ++e) {
    const FeatureEdge& edge = lines.edges[e];
    const CurvePlace& place = lines.curvePlaces[e];
    const int steps = std::max(1, static_cast<int>(std::ceil(edge.lengthPixels() / 0.25)));
    for (int i = 0; i < steps; ++i) {
      const double u0 = double(i) / steps, u1 = double(i + 1) / steps, middle = 0.5 * (u0 + u1);
      const bool shown = contains(walked.visibility(e).visible, middle);
      const double coordinate = place.from + edge.edgeParameter(middle) * (place.to - place.from);
      const auto there = other.at(place.curve, coordinate);
      const bool matched = there && there->visible && glm::length(there->pixel - edge.pixelAt(middle)) <= kCurveTolerancePixels;
      visit(edge.pixelAt(u0), edge.pixelAt(u1), (u1 - u0) * edge.lengthPixels(), shown, matched);
    }
  }
}

}  // namespace

std::vector<std::uint8_t> lineErrorMap(const LineSet& lines, std::span<const EdgeVisibility> truth) {
  HSR_CHECK(truth.size() == lines.edges.size());
  ErrorPicture picture(lines.width, lines.height);
  const std::vector<EdgeVisibility> drawn = edgeVisibility(lines);
  for (std::size_t e = 0; e < lines.edges.size(); ++e) picture.parts(lines.edges[e], truth[e].visible, kLineWidthPixels, kExactLineGrey);
  for (std::size_t e = 0; e < lines.edges.size(); ++e) {
    picture.parts(lines.edges[e], difference(drawn[e].visible, truth[e].visible), kErrorLineWidth, kWronglyDrawnRed);
    picture.parts(lines.edges[e], difference(truth[e].visible, drawn[e].visible), kErrorLineWidth, kWronglyHiddenBlue);
  }
  return picture.take();
}

CurveComparison compareCurveDrawings(const LineSet& drawn, const LineSet& exact, std::span<const EdgeVisibility> exactVisibility) {
  HSR_CHECK(exactVisibility.size() == exact.edges.size());
  std::size_t curves = 0;
  for (const LineSet* lines : {&drawn, &exact})
    for (const CurvePlace& place : lines->curvePlaces) curves = std::max<std::size_t>(curves, place.curve + 1);
  const CurveLookup drawnCurves(drawn, edgeVisibility(drawn), curves);
  const CurveLookup exactCurves(exact, {exactVisibility.begin(), exactVisibility.end()}, curves);
  CurveComparison result;
  ErrorPicture picture(exact.width, exact.height);
  walkCurves(exactCurves, drawnCurves, [&](dvec2 a, dvec2 b, double, bool shown, bool) {
    if (shown) picture.line(a, b, kLineWidthPixels, kExactLineGrey);
  });
  LineError& error = result.error;
  walkCurves(exactCurves, drawnCurves, [&](dvec2 a, dvec2 b, double length, bool shown, bool matched) {
    if (!shown) return;
    error.visibleLength += length;
    if (!matched) error.wronglyHidden += length, picture.line(a, b, kErrorLineWidth, kWronglyHiddenBlue);
  });
  walkCurves(drawnCurves, exactCurves, [&](dvec2 a, dvec2 b, double length, bool shown, bool matched) {
    if (shown && !matched) error.wronglyDrawn += length, picture.line(a, b, kErrorLineWidth, kWronglyDrawnRed);
  });
  error.error = error.visibleLength > 0 ? (error.wronglyDrawn + error.wronglyHidden) / error.visibleLength : 0;
  result.errorMap = picture.take();
  return result;
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
