#include "renderer/lines.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

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
  }
  return "?";
}

double FeatureEdge::lengthPixels() const { return glm::length(pixelTo - pixelFrom); }

double FeatureEdge::edgeParameter(double u) const {
  // s / w and 1 / w are affine in screen space; s = (u / w1) / ((1 - u) / w0 + u / w1).
  const double denominator = (1 - u) * divisorTo + u * divisorFrom;
  return denominator > 0 ? u * divisorFrom / denominator : u;
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

std::vector<std::uint8_t> lineErrorMap(const LineSet& lines, std::span<const EdgeVisibility> truth) {
  HSR_CHECK(truth.size() == lines.edges.size());
  std::vector<std::uint8_t> rgba(std::size_t(lines.width) * std::size_t(lines.height) * 4, 255);
  const std::vector<EdgeVisibility> drawn = edgeVisibility(lines);
  const auto paint = [&](const FeatureEdge& edge, const std::vector<Interval>& parts, double width, std::array<std::uint8_t, 3> color) {
    for (const Interval& part : parts)
      // Parts shorter than a millionth of a pixel are the rounding of event positions, not errors.
      if ((part.end - part.begin) * edge.lengthPixels() > 1e-6)
        rasterizeLine(edge.pixelAt(part.begin), edge.pixelAt(part.end), width, lines.width, lines.height, [&](int x, int y) {
        std::uint8_t* pixel = &rgba[(std::size_t(y) * std::size_t(lines.width) + std::size_t(x)) * 4];
        pixel[0] = color[0], pixel[1] = color[1], pixel[2] = color[2];
      });
  };
  for (std::size_t e = 0; e < lines.edges.size(); ++e) paint(lines.edges[e], truth[e].visible, kLineWidthPixels, {187, 187, 187});
  // Errors drawn wider, so a short one is still seen.
  for (std::size_t e = 0; e < lines.edges.size(); ++e) {
    paint(lines.edges[e], difference(drawn[e].visible, truth[e].visible), 3, {220, 30, 30});
    paint(lines.edges[e], difference(truth[e].visible, drawn[e].visible), 3, {30, 60, 220});
  }
  return rgba;
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
