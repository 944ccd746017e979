#include "renderer/reference/line_reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "renderer/geometry/exact.hpp"
#include "renderer/geometry/predicates.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr {
namespace {

// The vector plus - minus, kept as its two operands so it can be formed exactly.
struct Difference {
  dvec3 plus, minus;
};
// det[u, v, w] of three differences.
struct Determinant {
  Difference u, v, w;
};

double permanent(const dvec3& u, const dvec3& v, const dvec3& w) {
  const dvec3 au = glm::abs(u), av = glm::abs(v), aw = glm::abs(w);
  return glm::dot(au, dvec3(av.y * aw.z + av.z * aw.y, av.z * aw.x + av.x * aw.z, av.x * aw.y + av.y * aw.x));
}

double approximate(const Determinant& d, double& bound) {
  const dvec3 u = d.u.plus - d.u.minus, v = d.v.plus - d.v.minus, w = d.w.plus - d.w.minus;
  // Rounding the differences and the products errs by a few units in the last place of
  // the permanent; 1e-14 of it is a bound with a wide margin.
  bound = 1e-14 * permanent(u, v, w);
  return glm::dot(u, glm::cross(v, w));
}

// alpha + s beta is a determinant of differences times a double: degree four.
using Exact = ExactNumber<4>;

Exact exactly(const Determinant& d) {
  Exact u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = Exact(d.u.plus[i]) - d.u.minus[i];
    v[i] = Exact(d.v.plus[i]) - d.v.minus[i];
    w[i] = Exact(d.w.plus[i]) - d.w.minus[i];
  }
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// The sign of alpha + s beta, exactly.
int signOfLinear(const Determinant& alpha, const Determinant& beta, double s, std::int64_t& fallbacks) {
  double alphaBound = 0, betaBound = 0;
  const double a = approximate(alpha, alphaBound), b = approximate(beta, betaBound);
  const double value = a + s * b;
  const double bound = alphaBound + std::abs(s) * betaBound + 4e-16 * (std::abs(a) + 2 * std::abs(s * b));
  if (value > bound) return 1;
  if (value < -bound) return -1;
  ++fallbacks;
  return (exactly(alpha) + Exact(s) * exactly(beta)).sign();
}

const dvec3 kZero(0);

class EdgeJudge {
 public:
  EdgeJudge(const PreparedScene& scene, const CameraTransform& camera, const Bvh& bvh, const std::vector<dvec2>& pixel,
            const std::vector<double>& distance)
      : scene_(scene), camera_(camera), bvh_(bvh), pixel_(pixel), distance_(distance) {}

  EdgeVisibility judge(const FeatureEdge& edge) {
    EdgeVisibility result;
    result.lengthPixels = edge.lengthPixels();
    gatherCandidates(edge);
    const std::vector<double> events = visibilityEvents(edge);
    for (std::size_t i = 0; i + 1 < events.size(); ++i) {
      const double begin = events[i], end = events[i + 1];
      if (end <= begin) continue;
      ++intervals;
      if (hidden(edge, (begin + end) / 2)) continue;
      if (!result.visible.empty() && result.visible.back().end == begin) result.visible.back().end = end;
      else result.visible.push_back({begin, end});
    }
    return result;
  }

  std::int64_t candidates = 0, intervals = 0, fallbacks = 0;

 private:
  // Step 1: triangles whose projected box overlaps the edge's and whose nearest corner
  // is nearer than the edge's farthest point.
  void gatherCandidates(const FeatureEdge& edge) {
    candidates_.clear();
    const dvec2 lo = glm::min(edge.pixelFrom, edge.pixelTo) - 1e-6, hi = glm::max(edge.pixelFrom, edge.pixelTo) + 1e-6;
    const double farthest = std::max(camera_.clipFromWorld(edge.from).d, camera_.clipFromWorld(edge.to).d);
    bvh_.visitPrimitives([&](const BvhNode& node) { return boxMayCover(node, lo, hi, farthest); },
                         [&](std::uint32_t t, std::uint32_t) {
                           const Triangle& tri = scene_.triangles()[t];
                           dvec2 tlo(std::numeric_limits<double>::infinity()), thi(-std::numeric_limits<double>::infinity());
                           double nearest = std::numeric_limits<double>::infinity();
                           for (std::uint32_t v : tri) {
                             tlo = glm::min(tlo, pixel_[v]);
                             thi = glm::max(thi, pixel_[v]);
                             nearest = std::min(nearest, distance_[v]);
                           }
                           if (thi.x < lo.x || tlo.x > hi.x || thi.y < lo.y || tlo.y > hi.y || nearest >= farthest) return;
                           candidates_.push_back({t, tlo, thi});
                         });
    // The BVH order is fixed, but sort anyway so the work never depends on traversal details.
    std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) { return a.triangle < b.triangle; });
    candidates += static_cast<std::int64_t>(candidates_.size());
  }

  bool boxMayCover(const BvhNode& node, const dvec2& lo, const dvec2& hi, double farthest) const {
    dvec2 blo(std::numeric_limits<double>::infinity()), bhi(-std::numeric_limits<double>::infinity());
    double nearest = std::numeric_limits<double>::infinity();
    for (int corner = 0; corner < 8; ++corner) {
      const dvec3 p(node.bounds[corner & 1][0], node.bounds[(corner >> 1) & 1][1], node.bounds[(corner >> 2) & 1][2]);
      const ClipVertex clip = camera_.clipFromWorld(p);
      // A corner at or behind the eye projects nowhere useful: keep the node.
      if (clip.w <= 0) return true;
      const dvec2 q = camera_.pixelFromClip(clip);
      blo = glm::min(blo, q);
      bhi = glm::max(bhi, q);
      nearest = std::min(nearest, clip.d);
    }
    return !(bhi.x < lo.x || blo.x > hi.x || bhi.y < lo.y || blo.y > hi.y || nearest >= farthest);
  }

  // Step 2: where visibility may change, as sorted parameters from 0 to 1.
  std::vector<double> visibilityEvents(const FeatureEdge& edge) const {
    std::vector<double> events = {0.0, 1.0};
    const dvec2 p0 = edge.pixelFrom, dp = edge.pixelTo - edge.pixelFrom;
    const double lengthSquared = glm::dot(dp, dp);
    if (lengthSquared == 0) return events;
    const auto add = [&](double u) {
      if (u > 0 && u < 1) events.push_back(u);
    };
    const auto parameterOf = [&](const dvec2& q) { return glm::dot(q - p0, dp) / lengthSquared; };
    const auto cross = [](const dvec2& a, const dvec2& b) { return a.x * b.y - a.y * b.x; };
    for (const Candidate& candidate : candidates_) {
      const Triangle& tri = scene_.triangles()[candidate.triangle];
      for (int k = 0; k < 3; ++k) {
        const dvec2 q0 = pixel_[tri[k]], dq = pixel_[tri[(k + 1) % 3]] - q0;
        // The projected side crosses the edge...
        const double denominator = cross(dp, dq);
        if (denominator != 0) {
          const double u = cross(q0 - p0, dq) / denominator, v = cross(q0 - p0, dp) / denominator;
          if (v >= -1e-9 && v <= 1 + 1e-9) add(u);
        }
        // ...or its corner lies on the edge (collinear sides, a corner passed exactly).
        const double offLine = std::abs(cross(q0 - p0, dp)) / std::sqrt(lengthSquared);
        if (offLine < 1e-6) add(parameterOf(q0));
      }
      // The edge pierces the triangle's plane.
      const dvec3& a = scene_.positions()[tri[0]];
      const dvec3 normal = glm::cross(scene_.positions()[tri[1]] - a, scene_.positions()[tri[2]] - a);
      const double o0 = glm::dot(normal, edge.from - a), o1 = glm::dot(normal, edge.to - a);
      if ((o0 < 0 && o1 > 0) || (o0 > 0 && o1 < 0)) {
        const dvec3 x = edge.from + (o0 / (o0 - o1)) * (edge.to - edge.from);
        add(parameterOf(camera_.pixelFromClip(camera_.clipFromWorld(x))));
      }
    }
    std::sort(events.begin(), events.end());
    events.erase(std::unique(events.begin(), events.end()), events.end());
    return events;
  }

  // Step 3: is the point of the edge projected at u hidden? (The header's definition.)
  bool hidden(const FeatureEdge& edge, double u) {
    const double s = edge.edgeParameter(u);
    const dvec2 at = edge.pixelAt(u);
    const dvec3& from = edge.from;
    const Difference along{edge.to, edge.from};  // X = from + s (to - from)
    const bool perspective = camera_.perspective();
    const dvec3& eye = camera_.camera().eye;
    const dvec3& forward = camera_.forward();
    for (const Candidate& candidate : candidates_) {
      if (at.x < candidate.lo.x - 1e-6 || at.x > candidate.hi.x + 1e-6 || at.y < candidate.lo.y - 1e-6 ||
          at.y > candidate.hi.y + 1e-6)
        continue;
      const Triangle& tri = scene_.triangles()[candidate.triangle];
      const dvec3 &a = scene_.positions()[tri[0]], &b = scene_.positions()[tri[1]], &c = scene_.positions()[tri[2]];
      // Which side of the triangle's plane the viewer is on (0: seen edge-on, hides nothing)...
      const int viewerSide = perspective ? exact_.orient3d(a, b, c, eye) : exact_.facing(a, b, c, -forward);
      if (viewerSide == 0) continue;
      if (edge.kind == EdgeKind::junction && onPlane(a, b, c, edge.from + s * (edge.to - edge.from))) continue;
      // ...and X must be strictly on the other side, so the plane is crossed before X.
      const int pointSide = signOfLinear({{b, a}, {c, a}, {from, a}}, {{b, a}, {c, a}, along}, s, fallbacks);
      if (pointSide != -viewerSide) continue;
      // The line of sight through X meets the closed triangle: the three signs agree.
      int positive = 0, negative = 0;
      const dvec3* corners[3] = {&a, &b, &c};
      for (int k = 0; k < 3; ++k) {
        const dvec3 &p = *corners[k], &q = *corners[(k + 1) % 3];
        // perspective: det[X - eye, p - eye, q - eye]; orthographic: det[f, p - X, q - X] = det[f, p - X, q - p].
        const int sign = perspective
                             ? signOfLinear({{from, eye}, {p, eye}, {q, eye}}, {along, {p, eye}, {q, eye}}, s, fallbacks)
                             : signOfLinear({{forward, kZero}, {p, from}, {q, p}}, {along, {forward, kZero}, {q, p}}, s, fallbacks);
        positive += sign > 0;
        negative += sign < 0;
      }
      if (positive == 0 || negative == 0) return true;
    }
    return false;
  }

  // A junction's ends are computed, so it lies on the faces it joins only to rounding: a
  // plane passing within 1e-9 of the local size of its point holds the point, or within
  // 16 units in the last place of the point's largest coordinate, the rounding of a
  // point computed far from the origin (10^7 away, 2e-8, beyond 1e-9 of a unit box).
  bool onPlane(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& x) const {
    const dvec3 normal = glm::normalize(glm::cross(b - a, c - a));
    const double size = std::max({glm::length(b - a), glm::length(c - a), glm::length(x - a)});
    const double magnitude = std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    return std::abs(glm::dot(normal, x - a)) <= 1e-9 * size + 16 * std::numeric_limits<double>::epsilon() * magnitude;
  }

  struct Candidate {
    std::uint32_t triangle;
    dvec2 lo, hi;  // projected box
  };
  const PreparedScene& scene_;
  const CameraTransform& camera_;
  const Bvh& bvh_;
  const std::vector<dvec2>& pixel_;
  const std::vector<double>& distance_;
  ExactPredicates exact_;
  std::vector<Candidate> candidates_;
};

}  // namespace

std::vector<EdgeVisibility> traceLineReference(const PreparedScene& scene, std::span<const FeatureEdge> edges, int threads,
                                               Stats& stats) {
  const Bvh& bvh = scene.triangleBvh(stats, threads);
  PhaseTimer timer(stats, "line reference");
  const CameraTransform& camera = scene.camera();
  std::vector<dvec2> pixel(scene.positions().size());
  std::vector<double> distance(scene.positions().size());
  for (std::size_t v = 0; v < pixel.size(); ++v) {
    const ClipVertex clip = camera.clipFromWorld(scene.positions()[v]);
    pixel[v] = camera.pixelFromClip(clip);
    distance[v] = clip.d;
  }
  std::vector<EdgeVisibility> result(edges.size());
  const int workers = resolveThreadCount(threads);
  std::vector<EdgeJudge> judges;
  for (int worker = 0; worker < workers; ++worker) judges.emplace_back(scene, camera, bvh, pixel, distance);
  parallelFor(edges.size(), workers, [&](std::size_t e, int worker) { result[e] = judges[worker].judge(edges[e]); });
  for (const EdgeJudge& judge : judges) {
    stats.add("line reference candidates", judge.candidates);
    stats.add("line reference intervals", judge.intervals);
    stats.add("line reference exact fall-backs", judge.fallbacks);
  }
  stats.add("line reference edges", static_cast<std::int64_t>(edges.size()));
  return result;
}

}  // namespace hsr
