#include "algorithms/roberts/roberts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "renderer/geometry/camera.hpp"
#include "renderer/image/image_grid.hpp"
#include "renderer/lines/line_drawing.hpp"
#include "renderer/reference/metrics.hpp"

namespace hsr::roberts {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A plane n . x = offset; the body lies on the side n . x <= offset.
struct Plane {
  dvec3 normal;
  double offset;
  double height(const dvec3& x) const { return glm::dot(normal, x) - offset; }
};

double sizeOf(const Aabb& box) { return glm::length(box.hi - box.lo); }

// How far each coordinate of the body's vertices may lie from the solid its source meant:
// its file's decimals and its placement's rounding (Instance).
double coordinateRounding(const Instance& body) { return body.statedRounding + body.placementRounding; }

// The tolerance of the body's strict insideness tests, in world units: the larger of a
// billionth of its size (the double-precision arithmetic of its tests, far above their
// rounding and far below a pixel) and eight times its coordinates' rounding (twice for
// what first order leaves out, times a lever of up to four for neighbouring faces), so a
// body that is convex, or touches another, up to the precision of its coordinates is
// treated as it was meant.
double toleranceOf(const Instance& body, const Aabb& box) { return std::max(1e-9 * sizeOf(box), 8 * coordinateRounding(body)); }

// The body's faces: its triangles' planes, with the triangles coplanar up to the
// rounding of their coordinates merged into one (Roberts' volume matrix, one column per
// face). `faceOf` gets each triangle's face.
struct Face {
  Plane plane;
  RoundedPlane rounded;  // through the face's first triangle
};
std::vector<Face> facesOf(const PreparedScene& scene, const Instance& body, std::vector<std::uint32_t>* faceOf) {
  const double rounding = coordinateRounding(body);
  std::vector<Face> faces;
  for (std::uint32_t t = body.firstTriangle; t < body.firstTriangle + body.triangleCount; ++t) {
    const dvec3 normal = scene.faceNormal(t);
    const Triangle& corners = scene.triangles()[t];
    const auto coplanarWith = [&](const Face& face) {
      return glm::dot(face.plane.normal, normal) > 0 &&
             std::all_of(corners.begin(), corners.end(), [&](std::uint32_t v) { return face.rounded.couldHold(scene.positions()[v], rounding); });
    };
    const auto found = std::find_if(faces.begin(), faces.end(), coplanarWith);
    if (faceOf) faceOf->push_back(static_cast<std::uint32_t>(found - faces.begin()));
    if (found != faces.end()) continue;
    const dvec3 &a = scene.positions()[corners[0]], &b = scene.positions()[corners[1]], &c = scene.positions()[corners[2]];
    faces.push_back({{normal, glm::dot(normal, a)}, RoundedPlane(a, b, c, rounding)});
  }
  return faces;
}

Aabb boxOf(const PreparedScene& scene, const Instance& body) {
  Aabb box;
  for (std::uint32_t t = body.firstTriangle; t < body.firstTriangle + body.triangleCount; ++t)
    for (std::uint32_t v : scene.triangles()[t]) box.grow(scene.positions()[v]);
  return box;
}

}  // namespace

std::string refusal(const PreparedScene& scene) {
  if (std::string nearPlane = nearPlaneRefusal(scene); !nearPlane.empty()) return nearPlane;
  // Merging faces and checking convexity compare every triangle with every face: bound it
  // before that work, not after.
  for (const Instance& body : scene.instances())
    if (body.triangleCount > kMaxBodyTriangles)
      return "object '" + scene.scene().objects[body.object].name + "' has " + std::to_string(body.triangleCount) +
             " triangles, more than the " + std::to_string(kMaxBodyTriangles) +
             " a Roberts body may have (its faces are tested against every other edge); use --algo appel";
  Stats ignored;
  const EdgeAdjacency& adjacency = scene.edgeAdjacency(ignored);
  for (const MeshEdge& edge : adjacency.edges) {
    if (edge.faceCount == 2 && edge.consistent) continue;
    const Instance& body = scene.instanceOf(edge.faces[0]);
    return "object '" + scene.scene().objects[body.object].name +
           "' is not a closed, consistently oriented surface; Roberts draws convex solids only";
  }
  // Convex up to the precision of its coordinates: no vertex lies outside a face plane by
  // more than their rounding can explain (rounding.hpp), so a UV sphere written with six
  // digits, whose quads are flat only up to those digits, is a convex solid.
  for (const Instance& body : scene.instances()) {
    const double rounding = coordinateRounding(body);
    double outside = 0;  // the farthest any vertex lies outside a face plane beyond its rounding
    for (const Face& face : facesOf(scene, body, nullptr))
      for (std::uint32_t t = body.firstTriangle; t < body.firstTriangle + body.triangleCount; ++t)
        for (const std::uint32_t v : scene.triangles()[t]) {
          const dvec3& x = scene.positions()[v];
          if (face.plane.height(x) > 0 && !face.rounded.couldHold(x, rounding)) outside = std::max(outside, face.plane.height(x));
        }
    if (outside == 0) continue;
    char amount[160];
    std::snprintf(amount, sizeof amount, "%.3g outside one of its face planes, more than its coordinates' rounding (%.3g) explains",
                  outside, rounding);
    return "object '" + scene.scene().objects[body.object].name + "' is not convex: a vertex lies " + amount +
           "; Roberts draws convex solids only";
  }
  return "";
}

namespace {

// A body in Roberts' screen space (x, y in pixels, z the nearness), where sight lines
// are parallel to z.
struct Body {
  std::vector<Plane> worldPlanes;
  std::vector<std::int8_t> frontFace;  // per world plane: does it face the viewer
  std::vector<Plane> screenPlanes;     // the same faces, outward, pulled in by the tolerance
  double tolerance = 0;                // toleranceOf, in world units
  std::vector<std::uint32_t> faceOfTriangle;
  Aabb worldBox;
  dvec2 lo{kInfinity}, hi{-kInfinity};  // projected box
  double nearest = -kInfinity;         // largest nearness of a vertex
};

class Roberts {
 public:
  Roberts(const PreparedScene& scene, const Knobs& knobs, Stats& stats, StepRecorder* steps, EdgeWitness* witness)
      : scene_(scene), knobs_(knobs), camera_(scene.camera()), stats_(stats), steps_(steps), witness_(witness) {}

  LineSet run() {
    const std::vector<std::int8_t> facing = viewFacing(scene_, camera_, stats_);
    for (const Instance& instance : scene_.instances()) bodies_.push_back(makeBody(instance));
    stats_.add("bodies", static_cast<std::int64_t>(bodies_.size()));

    LineSet lines;
    lines.width = scene_.width();
    lines.height = scene_.height();
    lines.edges = featureEdges(scene_, camera_, facing, knobs_.creaseDegrees, stats_);
    // The owner body of each edge, and whether both its faces are back faces (step 1).
    std::vector<std::uint32_t> owner;
    std::vector<std::uint8_t> selfHidden;
    const EdgeAdjacency& adjacency = scene_.edgeAdjacency(stats_);
    for (const FeatureEdge& edge : lines.edges) {
      const MeshEdge& mesh = adjacency.edges[edge.meshEdge];
      owner.push_back(bodyOf(mesh.faces[0]));
      selfHidden.push_back(facing[mesh.faces[0]] <= 0 && facing[mesh.faces[1]] <= 0);
    }
    // Step 3's lines join the list, owned by both bodies they lie on.
    std::vector<std::uint32_t> secondOwner(lines.edges.size(), kNoBody);
    addJunctions(lines, owner, secondOwner, selfHidden);

    buildGrid();
    for (std::uint32_t e = 0; e < lines.edges.size(); ++e) {
      const FeatureEdge& edge = lines.edges[e];
      std::vector<Interval> hidden;
      const std::int64_t testsBefore = bodyTests_;
      EdgeWitness* const watched = witness_ && witness_->edge == e ? witness_ : nullptr;
      if (selfHidden[e]) {
        stats_.add("back-face edges");
        hidden.push_back({0, 1});
        if (watched) [[unlikely]]
          watched->events.push_back({kWholeEdge, 0, "hidden by its own body (step 1)", edge.kind == EdgeKind::junction
              ? "it lies on a back face of one of the two bodies it joins, inside that body's shadow of itself"
              : "both its faces face away from the eye; so its convex body hides all of it, and no other body is tested"});
      } else {
        // Step 2: the other bodies.
        const dvec3 s0 = screenPoint(edge.from), s1 = screenPoint(edge.to);
        std::size_t listed = 0;
        forEachCandidate(edge, [&](std::uint32_t b) {
          ++listed;
          EdgeEvent* const event = watched ? &watched->events.emplace_back(bodyEvent(b)) : nullptr;
          if (b == owner[e] || b == secondOwner[e]) {
            if (event) [[unlikely]]
              event->outcome = "not tested: the edge lies on it",
              event->detail = "a convex body hides none of its own edges but those between two back faces (step 1)";
            return;
          }
          if (const std::optional<Interval> part = hiddenBy(bodies_[b], s0, s1, event)) hidden.push_back(*part);
        });
        if (watched && grid_) [[unlikely]]
          watched->events.insert(watched->events.begin(), {kWholeEdge, 0, "the screen grid lists " + std::to_string(listed) + " of the " +
                                 std::to_string(bodies_.size()) + " bodies",
                                 "those whose projected boxes cover a cell of " + whyNumber(knobs_.cellPixels) +
                                 " pixels that the edge crosses; the others cannot hide it and are not looked at"});
      }
      appendPieces(e, std::move(hidden), lines.segments);
      if (steps_ && steps_->due(e, lines.edges.size()))
        steps_->record("step 2: edge " + std::to_string(e + 1) + " of " + std::to_string(lines.edges.size()) + " (green) " +
                           (selfHidden[e] ? "lies between two back faces: hidden by its own body (step 1)"
                                          : "tested in full against " + std::to_string(bodyTests_ - testsBefore) +
                                                (bodyTests_ - testsBefore == 1 ? " body" : " bodies") + " the minimax boxes could not rule out"),
                       lineStepPicture(lines, std::span(&e, 1), LineStyle::hidden));
    }
    stats_.add("edge-body pairs", pairs_);
    stats_.add("minimax rejections", minimaxRejections_);
    stats_.add("body tests", bodyTests_);
    stats_.add("hidden intervals", hiddenIntervals_);
    return lines;
  }

 private:
  static constexpr std::uint32_t kNoBody = std::numeric_limits<std::uint32_t>::max();
  // A face plane along the edge: its height h(u) = h0 + u h1 above S(u), and alpha's coefficient g.
  struct Row {
    double h0, h1, g;
  };

  std::uint32_t bodyOf(std::uint32_t triangle) const {
    return static_cast<std::uint32_t>(&scene_.instanceOf(triangle) - scene_.instances().data());
  }

  double nearness(const dvec3& p) const {
    const double d = camera_.clipFromWorld(p).d;
    return camera_.perspective() ? 1 / d : -d;
  }
  dvec3 screenPoint(const dvec3& p) const { return dvec3(camera_.pixelFromClip(camera_.clipFromWorld(p)), nearness(p)); }

  Body makeBody(const Instance& instance) {
    Body body;
    body.worldBox = boxOf(scene_, instance);
    body.tolerance = toleranceOf(instance, body.worldBox);
    for (const Face& face : facesOf(scene_, instance, &body.faceOfTriangle)) body.worldPlanes.push_back(face.plane);
    stats_.add("body faces", static_cast<std::int64_t>(body.worldPlanes.size()));
    // Screen-space planes through each face's largest triangle, turned so the image of
    // the body's centroid (inside a convex body, and the map keeps insides inside) is below.
    dvec3 centroid(0), screenLo(kInfinity), screenHi(-kInfinity);
    std::size_t corners = 0;
    for (std::uint32_t t = instance.firstTriangle; t < instance.firstTriangle + instance.triangleCount; ++t)
      for (std::uint32_t v : scene_.triangles()[t]) {
        centroid += scene_.positions()[v];
        ++corners;
        const dvec3 s = screenPoint(scene_.positions()[v]);
        screenLo = glm::min(screenLo, s);
        screenHi = glm::max(screenHi, s);
      }
    body.lo = dvec2(screenLo);
    body.hi = dvec2(screenHi);
    body.nearest = screenHi.z;
    const dvec3 inside = screenPoint(centroid / double(corners));
    const dvec3 extent = screenHi - screenLo;
    std::vector<double> largestArea(body.worldPlanes.size(), -1);
    body.screenPlanes.resize(body.worldPlanes.size());
    body.frontFace.resize(body.worldPlanes.size());
    for (std::uint32_t k = 0; k < instance.triangleCount; ++k) {
      const Triangle& t = scene_.triangles()[instance.firstTriangle + k];
      const dvec3 a = screenPoint(scene_.positions()[t[0]]), b = screenPoint(scene_.positions()[t[1]]), c = screenPoint(scene_.positions()[t[2]]);
      const dvec3 normal = glm::cross(b - a, c - a);
      const double area = glm::length(glm::cross(b - a, c - a) / (extent + 1e-300));
      const std::uint32_t face = body.faceOfTriangle[k];
      if (area <= largestArea[face]) continue;
      largestArea[face] = area;
      Plane plane{normal, glm::dot(normal, a)};
      if (plane.height(inside) > 0) plane = {-plane.normal, -plane.offset};
      plane.offset -= body.tolerance / sizeOf(body.worldBox) * glm::dot(glm::abs(plane.normal), extent);
      body.screenPlanes[face] = plane;
      body.frontFace[face] = plane.normal.z > 0;  // the outward normal points toward the viewer
    }
    return body;
  }

  // An event of hsr why --edge about body b, its outcome and detail still to say.
  EdgeEvent bodyEvent(std::uint32_t b) const {
    return {kWholeEdge, 0, "", "", "body " + scene_.instanceName(scene_.instances()[b])};
  }

  // Step 2's linear program: the open interval of u in (0, 1) over which S(u) + alpha z
  // is strictly inside the body for some alpha > 0, or nothing. `event`: hsr why's, or null.
  std::optional<Interval> hiddenBy(const Body& body, const dvec3& s0, const dvec3& s1, EdgeEvent* event) {
    ++pairs_;
    // The minimax test: projections apart, or the body wholly behind the edge.
    const dvec2 lo = glm::min(dvec2(s0), dvec2(s1)), hi = glm::max(dvec2(s0), dvec2(s1));
    const bool apart = body.hi.x < lo.x || body.lo.x > hi.x || body.hi.y < lo.y || body.lo.y > hi.y;
    if (apart || body.nearest <= std::min(s0.z, s1.z)) {
      ++minimaxRejections_;
      if (event) [[unlikely]]
        event->outcome = "ruled out by the minimax test",
        event->detail = apart ? "its projected box misses the edge's"
                              : "its nearest point is no nearer than the edge's farther end: it lies wholly behind the edge";
      return std::nullopt;
    }
    ++bodyTests_;
    std::vector<Row>& upper = upper_;
    std::vector<Row>& lower = lower_;
    upper.clear();
    lower.clear();
    double begin = 0, end = 1;
    // a u + b < 0 narrows [begin, end].
    const auto require = [&](double a, double b) {
      if (a > 0) end = std::min(end, -b / a);
      else if (a < 0) begin = std::max(begin, -b / a);
      else if (b >= 0) end = -1;
    };
    for (const Plane& plane : body.screenPlanes) {
      const Row row{plane.height(s0), glm::dot(plane.normal, s1 - s0), plane.normal.z};
      if (row.g > 0) upper.push_back(row);       // alpha < -h / g
      else if (row.g < 0) lower.push_back(row);  // alpha > -h / g
      else require(row.h1, row.h0);              // h(u) < 0 whatever alpha is
    }
    // Every lower bound (and alpha > 0) below every upper bound: one inequality in u per pair.
    for (const Row& i : upper) {
      require(i.h1, i.h0);  // 0 < -h_i / g_i
      for (const Row& j : lower)  // -h_j / g_j < -h_i / g_i, times g_i g_j < 0
        require(-(i.h1 * j.g - j.h1 * i.g), -(i.h0 * j.g - j.h0 * i.g));
    }
    if (event) [[unlikely]]
      event->detail = std::to_string(body.screenPlanes.size()) + " face planes along the sight lines from the edge: " +
                      std::to_string(upper.size()) + " bound alpha from above, " + std::to_string(lower.size()) + " from below, " +
                      std::to_string(body.screenPlanes.size() - upper.size() - lower.size()) +
                      " are parallel to the sight lines; every pair of bounds, alpha > 0 and the parallel planes leave u " +
                      (begin < end ? "in (" + whyNumber(begin) + ", " + whyNumber(end) + ")" : "nowhere in (0, 1)");
    if (begin >= end) {
      if (event) [[unlikely]]
        event->outcome = "hides none of it";
      return std::nullopt;
    }
    if (event) [[unlikely]]
      event->u = begin, event->change = 1, event->outcome = "hides part of it: u = " + whyNumber(begin) + " to " + whyNumber(end);
    ++hiddenIntervals_;
    return Interval{begin, end};
  }

  // Step 3: for every pair of bodies whose boxes meet, and every pair of their faces, the
  // line where the two planes meet, clipped to both bodies, is a junction when its middle
  // lies inside both faces (strictly within every other plane of both bodies).
  void addJunctions(LineSet& lines, std::vector<std::uint32_t>& owner, std::vector<std::uint32_t>& secondOwner,
                    std::vector<std::uint8_t>& selfHidden) {
    for (std::uint32_t a = 0; a < bodies_.size(); ++a)
      for (std::uint32_t b = a + 1; b < bodies_.size(); ++b) {
        const Body &A = bodies_[a], &B = bodies_[b];
        if (glm::any(glm::lessThan(A.worldBox.hi, B.worldBox.lo)) || glm::any(glm::lessThan(B.worldBox.hi, A.worldBox.lo))) continue;
        const double tolerance = std::max(A.tolerance, B.tolerance);
        for (std::uint32_t f = 0; f < A.worldPlanes.size(); ++f)
          for (std::uint32_t g = 0; g < B.worldPlanes.size(); ++g) {
            const Plane &P = A.worldPlanes[f], &Q = B.worldPlanes[g];
            const dvec3 direction = glm::cross(P.normal, Q.normal);
            if (glm::length(direction) < 1e-9) continue;  // parallel or coplanar faces meet in no line
            // A point on both planes, then the line clipped by every plane of both bodies.
            const dvec3 point = glm::cross(P.offset * Q.normal - Q.offset * P.normal, direction) / glm::dot(direction, direction);
            double t0 = -kInfinity, t1 = kInfinity;
            const auto clip = [&](const Body& body, std::uint32_t skip) {
              for (std::uint32_t k = 0; k < body.worldPlanes.size(); ++k) {
                if (k == skip) continue;
                const double along = glm::dot(body.worldPlanes[k].normal, direction), at = body.worldPlanes[k].height(point);
                if (std::abs(along) < 1e-15) {
                  if (at > tolerance) t1 = -kInfinity;
                } else if (along > 0) {
                  t1 = std::min(t1, -at / along);
                } else {
                  t0 = std::max(t0, -at / along);
                }
              }
            };
            clip(A, f);
            clip(B, g);
            if (!(t0 < t1) || (t1 - t0) * glm::length(direction) <= tolerance) continue;
            const dvec3 from = point + t0 * direction, to = point + t1 * direction, middle = (from + to) * 0.5;
            const auto strictlyInside = [&](const Body& body, std::uint32_t skip) {
              for (std::uint32_t k = 0; k < body.worldPlanes.size(); ++k)
                if (k != skip && body.worldPlanes[k].height(middle) > -tolerance) return false;
              return true;
            };
            if (!strictlyInside(A, f) || !strictlyInside(B, g)) continue;
            lines.edges.push_back(projectEdge(camera_, from, to, EdgeKind::junction));
            lines.edges.back().faces = {scene_.instances()[a].firstTriangle, scene_.instances()[b].firstTriangle};
            owner.push_back(a);
            secondOwner.push_back(b);
            // On a back face of either body, the line is inside that body's shadow of itself.
            selfHidden.push_back(!A.frontFace[f] || !B.frontFace[g]);
            stats_.add("junction lines");
          }
      }
  }

  // The screen grid: the bodies whose projected boxes cover each cell.
  void buildGrid() {
    if (!knobs_.grid) return;
    dvec2 lo(kInfinity), hi(-kInfinity);
    for (const Body& body : bodies_) lo = glm::min(lo, body.lo), hi = glm::max(hi, body.hi);
    grid_.emplace(lo, hi, dvec2(scene_.width(), scene_.height()), knobs_.cellPixels);
    grid_->bin(bodies_.size(), [&](std::size_t b, auto&& add) { grid_->cellsInBox(bodies_[b].lo, bodies_[b].hi, add); });
    seen_.assign(bodies_.size(), kNoBody);
  }

  template <typename Visit>
  void forEachCandidate(const FeatureEdge& edge, Visit&& visit) {
    if (!grid_) {
      for (std::uint32_t b = 0; b < bodies_.size(); ++b) visit(b);
      return;
    }
    ++stamp_;
    grid_->cellsOnSegment(edge.pixelFrom, edge.pixelTo, [&](std::size_t cell) {
      grid_->itemsIn(cell, [&](std::uint32_t b) {
        if (seen_[b] == stamp_) return;
        seen_[b] = stamp_;
        visit(b);
      });
    });
  }

  // The edge's pieces: the union of the hidden intervals, and the gaps between them visible.
  static void appendPieces(std::uint32_t e, std::vector<Interval> hidden, std::vector<LineSegment>& out) {
    std::sort(hidden.begin(), hidden.end(), [](const Interval& a, const Interval& b) { return a.begin < b.begin; });
    double u = 0;  // the edge is drawn up to here
    for (const Interval& part : hidden) {
      if (part.end <= u) continue;
      if (part.begin > u) out.push_back({e, u, part.begin, 0});
      if (part.begin <= u && u > 0) out.back().end = part.end;  // overlaps the hidden piece before it
      else out.push_back({e, part.begin, part.end, LineSegment::kHidden});
      u = part.end;
    }
    if (u < 1) out.push_back({e, u, 1.0, 0});
  }

  const PreparedScene& scene_;
  const Knobs& knobs_;
  CameraTransform camera_;
  Stats& stats_;
  StepRecorder* steps_;
  EdgeWitness* witness_;  // hsr why --edge's edge, or null
  std::vector<Body> bodies_;
  std::optional<ImageGrid> grid_;
  std::vector<std::uint32_t> seen_;
  std::uint32_t stamp_ = 0;
  std::vector<Row> upper_, lower_;  // step 2's bounds on alpha, kept to reuse their storage
  std::int64_t pairs_ = 0, minimaxRejections_ = 0, bodyTests_ = 0, hiddenIntervals_ = 0;
};

}  // namespace

LineSet run(const PreparedScene& scene, const Knobs& knobs, Stats& stats, StepRecorder* steps, EdgeWitness* edge) {
  PhaseTimer timer(stats, "roberts");
  return Roberts(scene, knobs, stats, steps, edge).run();
}

AlgorithmEntry entry() {
  AlgorithmEntry entry;
  entry.name = "roberts";
  entry.kind = AlgorithmKind::line;
  entry.summary = "every edge against every convex body by linear inequalities along the sight lines (Roberts 1963)";
  setKnobs(entry, knobTable());
  entry.keyCounters = {"feature edges", "junction lines", "back-face edges", "edge-body pairs", "body tests", "hidden intervals"};
  setRefusal(entry, refusal);
  setDrawing(entry, run);
  entry.whyDecisions = {"hidden by its own body (step 1)", "not tested", "ruled out by the minimax test", "hides none of it",
                        "hides part of it"};
  entry.judgeLines = judgedByLineReference;
  return entry;
}

}  // namespace hsr::roberts
