#include "algorithms/appel/appel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>

#include "renderer/camera.hpp"
#include "renderer/error.hpp"
#include "renderer/image_grid.hpp"
#include "renderer/predicates.hpp"

namespace hsr::appel {

namespace {

// The first mesh edge that passes through a triangle of another object copy, as
// "object 'a' passes through object 'b'", or "". (Strictly through: touching is fine.)
std::string interpenetration(const PreparedScene& scene) {
  if (scene.instances().size() < 2) return "";
  Stats ignored;
  const EdgeAdjacency& adjacency = scene.edgeAdjacency(ignored);
  const Bvh& bvh = scene.triangleBvh(ignored);
  ExactPredicates exact;
  for (const MeshEdge& edge : adjacency.edges) {
    const dvec3 &p = scene.positions()[edge.a], &q = scene.positions()[edge.b];
    const dvec3 lo = glm::min(p, q), hi = glm::max(p, q);
    const Instance& own = scene.instanceOf(edge.faces[0]);
    const Instance* other = nullptr;
    bvh.visitPrimitives(
        [&](const BvhNode& node) {
          for (int axis = 0; axis < 3; ++axis)
            if (double(node.bounds[0][axis]) > hi[axis] || double(node.bounds[1][axis]) < lo[axis]) return false;
          return other == nullptr;
        },
        [&](std::uint32_t t, std::uint32_t) {
          const Instance& owner = scene.instanceOf(t);
          if (&owner == &own || other) return;
          const Triangle& tri = scene.triangles()[t];
          const dvec3 &a = scene.positions()[tri[0]], &b = scene.positions()[tri[1]], &c = scene.positions()[tri[2]];
          if (exact.orient3d(a, b, c, p) * exact.orient3d(a, b, c, q) >= 0) return;
          const int s0 = exact.orient3d(p, q, a, b), s1 = exact.orient3d(p, q, b, c), s2 = exact.orient3d(p, q, c, a);
          if (s0 != 0 && s0 == s1 && s1 == s2) other = &owner;
        });
    if (other)
      return "object '" + scene.scene().objects[own.object].name + "' passes through object '" +
             scene.scene().objects[other->object].name + "'";
  }
  return "";
}

}  // namespace

std::string refusal(const PreparedScene& scene, const Knobs& knobs) {
  if (std::string nearPlane = nearPlaneRefusal(scene); !nearPlane.empty()) return nearPlane;
  // An edge entering another body changes its QI where no contour is crossed.
  if (std::string through = interpenetration(scene); !through.empty())
    return through + "; quantitative invisibility changes only at contours, so Appel needs bodies that do not interpenetrate";
  if (knobs.surfaces == Surfaces::any) return "";
  Stats ignored;
  const EdgeAdjacency& adjacency = scene.edgeAdjacency(ignored);
  for (const MeshEdge& edge : adjacency.edges) {
    if (edge.faceCount == 2 && edge.consistent) continue;
    const Instance& instance = scene.instanceOf(edge.faces[0]);
    const Triangle& first = scene.triangles()[instance.firstTriangle];
    const std::uint32_t base = *std::min_element(first.begin(), first.end());  // the instance's first vertex
    const std::string where = "object '" + scene.scene().objects[instance.object].name + "': the edge between its vertices " +
                              std::to_string(edge.a - base + 1) + " and " + std::to_string(edge.b - base + 1) + " ";
    const std::string why = edge.faceCount == 1   ? "bounds one triangle (the surface is open)"
                            : edge.faceCount > 2 ? "is shared by " + std::to_string(edge.faceCount) + " triangles"
                                                 : "joins two triangles that run it the same way (inconsistent orientation)";
    return where + why + "; quantitative invisibility by front faces needs closed, consistently oriented surfaces "
                         "(--knob surfaces=any counts every face instead)";
  }
  return "";
}

namespace {

constexpr std::uint32_t kUnknown = std::numeric_limits<std::uint32_t>::max();

struct PositionHash {
  std::size_t operator()(const std::array<double, 3>& p) const {
    const std::hash<double> hash;
    return hash(p[0]) ^ (hash(p[1]) * 0x9e3779b97f4a7c15ull) ^ (hash(p[2]) * 0xc2b2ae3d27d4eb4full);
  }
};

// An edge where the count of surfaces changes in the image: the counted faces around it
// do not balance (a contour: one front face; with every face counted, also a boundary or
// a non-manifold edge). The crossing test needs its ends and, per counted face, on which
// side of it (in the image) that face lies.
struct Contour {
  std::uint32_t from, to;          // scene vertices
  std::vector<std::int8_t> faceSides;  // ViewerPredicates::side(from, to, far corner) per counted face
  dvec2 pixelFrom, pixelTo;
};

// A change of QI along an edge.
struct Crossing {
  double u;
  int change;
};

class QuantitativeInvisibility {
 public:
  QuantitativeInvisibility(const PreparedScene& scene, const Knobs& knobs, Stats& stats)
      : scene_(scene),
        camera_(scene.scene().camera, scene.width(), scene.height()),
        viewer_(camera_),
        stats_(stats),
        adjacency_(scene.edgeAdjacency(stats)) {
    // Step 1: facing, feature edges, contours.
    facing_ = viewFacing(scene, camera_, stats);
    countEveryFace_ = knobs.surfaces == Surfaces::any;
    lines_.width = scene.width();
    lines_.height = scene.height();
    lines_.edges = featureEdges(scene, camera_, facing_, knobs.creaseDegrees, stats);
    for (const MeshEdge& mesh : adjacency_.edges) {
      Contour contour{mesh.a, mesh.b, {}, {}, {}};
      int balance = 0;
      for (const std::uint32_t face : adjacency_.aroundVertex.around(mesh.a)) {
        const Triangle& t = scene.triangles()[face];
        if (!counted(face) || (t[0] != mesh.b && t[1] != mesh.b && t[2] != mesh.b)) continue;
        contour.faceSides.push_back(static_cast<std::int8_t>(
            viewer_.side(position(mesh.a), position(mesh.b), position(thirdCorner(face, mesh.a, mesh.b)))));
        balance += contour.faceSides.back();
      }
      if (balance == 0) continue;  // as many counted faces on each side: crossing it changes nothing
      contour.pixelFrom = pixel(mesh.a);
      contour.pixelTo = pixel(mesh.b);
      contours_.push_back(std::move(contour));
    }
    stats.add("contour edges", static_cast<std::int64_t>(contours_.size()));
    // The grid covers every feature edge's projection and lists the contours through each cell.
    dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const FeatureEdge& edge : lines_.edges) {
      lo = glm::min(lo, glm::min(edge.pixelFrom, edge.pixelTo));
      hi = glm::max(hi, glm::max(edge.pixelFrom, edge.pixelTo));
    }
    grid_.emplace(lo, hi, knobs.cellPixels);
    grid_->bin(contours_.size(), [&](std::size_t i, auto&& add) { grid_->cellsOnSegment(contours_[i].pixelFrom, contours_[i].pixelTo, add); });
    stats.add("grid cells", static_cast<std::int64_t>(grid_->cellCount()));
    seen_.assign(contours_.size(), kUnknown);
    // Vertices of different meshes at the same position (solids touching at a corner or
    // along an edge) are one point: the faces of both meet there, and a contour ending
    // there ends at the walk's vertex.
    std::unordered_map<std::array<double, 3>, std::uint32_t, PositionHash> firstAt;
    point_.resize(scene.positions().size());
    for (std::uint32_t v = 0; v < point_.size(); ++v) point_[v] = firstAt.try_emplace({position(v).x, position(v).y, position(v).z}, v).first->second;
    std::vector<Triangle> welded(scene.triangles().begin(), scene.triangles().end());
    for (Triangle& t : welded)
      for (std::uint32_t& v : t) v = point_[v];
    aroundPoint_ = buildVertexTriangles(point_.size(), welded);
    // Feature edges around each vertex, for the walk.
    edgesAt_.resize(scene.positions().size());
    for (std::uint32_t e = 0; e < lines_.edges.size(); ++e) {
      edgesAt_[lines_.edges[e].vertexFrom].push_back(e);
      edgesAt_[lines_.edges[e].vertexTo].push_back(e);
    }
  }

  LineSet run() {
    // Steps 2 and 3, once per connected set of feature edges.
    baseQi_.assign(scene_.positions().size(), kUnknownQi);
    std::vector<std::vector<LineSegment>> pieces(lines_.edges.size());
    std::vector<std::uint8_t> walked(lines_.edges.size(), 0);
    for (std::uint32_t seed = 0; seed < lines_.edges.size(); ++seed) {
      if (walked[seed]) continue;
      const std::uint32_t start = startVertex(lines_.edges[seed].vertexFrom);
      std::vector<std::uint32_t> frontier = {start};
      while (!frontier.empty()) {
        const std::uint32_t vertex = frontier.back();
        frontier.pop_back();
        for (const std::uint32_t e : edgesAt_[vertex]) {
          if (walked[e]) continue;
          walked[e] = 1;
          if (const std::uint32_t reached = walkEdge(e, vertex, pieces[e]); reached != kUnknown) frontier.push_back(reached);
        }
      }
    }
    for (auto& edgePieces : pieces) lines_.segments.insert(lines_.segments.end(), edgePieces.begin(), edgePieces.end());
    stats_.add("crossings tested", crossingsTested_);
    stats_.add("QI changes", qiChanges_);
    stats_.add("vertex corrections", vertexCorrections_);
    stats_.add("QI mismatches", mismatches_);
    stats_.add("negative QI", negativeQi_);
    stats_.add("exact fall-backs", viewer_.exact().exactFallbacks);
    return std::move(lines_);
  }

 private:
  static constexpr int kUnknownQi = std::numeric_limits<int>::min();

  const dvec3& position(std::uint32_t vertex) const { return scene_.positions()[vertex]; }
  std::uint32_t thirdCorner(std::uint32_t triangle, std::uint32_t a, std::uint32_t b) const {
    for (std::uint32_t v : scene_.triangles()[triangle])
      if (v != a && v != b) return v;
    HSR_CHECK(false);
  }
  // The faces QI counts: the front faces, or with surfaces=any every face not seen edge-on.
  bool counted(std::uint32_t triangle) const { return countEveryFace_ ? facing_[triangle] != 0 : facing_[triangle] > 0; }
  dvec2 pixel(std::uint32_t vertex) const { return camera_.pixelFromClip(camera_.clipFromWorld(position(vertex))); }

  // Step 2: a vertex of this connected set whose QI is known, from a ray cast. A ray that
  // grazes a triangle's side or corner counts it, as the line reference does, but another
  // vertex of the set is tried first (up to a few), since at such a vertex QI is a
  // convention rather than a count.
  std::uint32_t startVertex(std::uint32_t first) {
    constexpr std::size_t kAttempts = 8;
    std::vector<std::uint32_t> tried = {first};
    for (std::size_t i = 0;; ++i) {
      const std::uint32_t vertex = tried[i];
      bool degenerate = false;
      const int qi = frontFacesBefore(vertex, degenerate);
      stats_.add("start-vertex ray casts");
      for (const std::uint32_t e : edgesAt_[vertex]) {
        const std::uint32_t other = lines_.edges[e].vertexFrom == vertex ? lines_.edges[e].vertexTo : lines_.edges[e].vertexFrom;
        if (std::find(tried.begin(), tried.end(), other) == tried.end()) tried.push_back(other);
      }
      if (!degenerate || i + 1 == tried.size() || i + 1 == kAttempts) {
        if (degenerate) stats_.add("degenerate start rays");
        baseQi_[vertex] = qi;
        return vertex;
      }
    }
  }

  // The counted faces crossed by the line of sight to a vertex before it reaches the
  // vertex; the faces around the vertex are the walk's to count (vertexHiding).
  int frontFacesBefore(std::uint32_t vertex, bool& degenerate) {
    const dvec3& v = position(vertex);
    const Ray ray = camera_.perspective() ? Ray{camera_.camera().eye, v - camera_.camera().eye} : Ray{v, -camera_.forward()};
    const double reach = camera_.perspective() ? 1.0 : std::numeric_limits<double>::infinity();
    const RayBoxTest boxTest(ray.origin, ray.direction);
    const auto& triangles = scene_.leafTriangles(stats_);
    int count = 0;
    scene_.triangleBvh(stats_).visitPrimitives(
        [&](const BvhNode& node) { return boxTest.entry(node, reach) != std::numeric_limits<double>::infinity(); },
        [&](std::uint32_t triangle, std::uint32_t slot) {
          const auto& t = triangles[slot];
          const Triangle& corners = scene_.triangles()[triangle];
          if (!counted(triangle) || std::find(corners.begin(), corners.end(), vertex) != corners.end()) return;
          // The vertex must lie behind the plane, on the side away from the viewer.
          if (viewer_.exact().orient3d(t.a, t.b, t.c, v) != -facing_[triangle]) return;
          const int sides[3] = {viewer_.side(v, t.a, t.b), viewer_.side(v, t.b, t.c), viewer_.side(v, t.c, t.a)};
          const bool positive = sides[0] >= 0 && sides[1] >= 0 && sides[2] >= 0;
          const bool negative = sides[0] <= 0 && sides[1] <= 0 && sides[2] <= 0;
          if (!positive && !negative) return;
          ++count;
          degenerate = degenerate || sides[0] == 0 || sides[1] == 0 || sides[2] == 0;
        });
    return count;
  }

  // The counted faces around `vertex` that hide the start of the edge from `vertex`
  // toward `toward`: the edge leaves behind the face's plane, and its projection starts
  // inside the face's projected corner at the vertex. The corner is closed on its second
  // side and open on its first, so a projection running exactly along a side shared by two
  // counted faces that lie on either side of it counts one of them; a first side with no
  // such neighbour (a contour, a rim) is closed, as the line reference's triangles are.
  int vertexHiding(std::uint32_t vertex, std::uint32_t toward) {
    int count = 0;
    const dvec3 &v = position(vertex), &w = position(toward);
    for (const std::uint32_t face : aroundPoint_.around(point_[vertex])) {
      if (!counted(face)) continue;
      const Triangle& t = scene_.triangles()[face];
      const std::uint32_t there = point_[toward];
      if (point_[t[0]] == there || point_[t[1]] == there || point_[t[2]] == there) continue;  // faces along the edge
      const int k = point_[t[0]] == point_[vertex] ? 0 : point_[t[1]] == point_[vertex] ? 1 : 2;
      const dvec3 &a = position(t[(k + 1) % 3]), &b = position(t[(k + 2) % 3]);
      if (viewer_.exact().orient3d(v, a, b, w) != -facing_[face]) continue;  // not behind the face's plane
      const int sideOfA = viewer_.side(v, a, w), sideOfB = viewer_.side(v, b, w);
      const int sideOfFace = viewer_.side(v, a, b);
      const MeshEdge& firstSide = adjacency_.edges[adjacency_.edgesOf[3 * face + k]];
      const std::uint32_t across = firstSide.faces[0] == face ? firstSide.faces[1] : firstSide.faces[0];
      const bool balanced = firstSide.faceCount == 2 && firstSide.consistent && counted(across) &&
                            viewer_.side(v, a, position(thirdCorner(across, t[k], t[(k + 1) % 3]))) == -sideOfFace;
      const bool pastFirst = sideOfA == sideOfFace || (sideOfA == 0 && !balanced);
      const bool beforeSecond = sideOfB == viewer_.side(v, b, a) || sideOfB == 0;
      if (pastFirst && beforeSecond) ++count;
    }
    return count;
  }

  // Step 3 along one edge: its QI changes where its projection crosses a contour edge in
  // front of it, by the faces of the contour whose side it enters less those whose side
  // it leaves. A point on a contour's line counts as behind all of its faces (closed, as
  // the line reference's triangles are), and a contour end on the edge's line counts as
  // on its positive side, so a contour chain through that line is crossed once, not twice.
  std::vector<Crossing> crossings(std::uint32_t e) {
    const FeatureEdge& edge = lines_.edges[e];
    const dvec3 &p = edge.from, &q = edge.to;
    std::vector<Crossing> found;
    grid_->cellsOnSegment(edge.pixelFrom, edge.pixelTo, [&](std::size_t cell) { grid_->itemsIn(cell, [&](std::uint32_t index) {
      if (seen_[index] == e) return;
      seen_[index] = e;
      const Contour& c = contours_[index];
      const std::uint32_t p0 = point_[edge.vertexFrom], p1 = point_[edge.vertexTo];
      if (point_[c.from] == p0 || point_[c.from] == p1 || point_[c.to] == p0 || point_[c.to] == p1) return;  // meets at a vertex
      ++crossingsTested_;
      const dvec3 &r = position(c.from), &s = position(c.to);
      const int sideOfR = viewer_.side(p, q, r), sideOfS = viewer_.side(p, q, s);
      if ((sideOfR >= 0) == (sideOfS >= 0)) return;
      const int sideOfP = viewer_.side(r, s, p), sideOfQ = viewer_.side(r, s, q);
      int change = 0;
      for (const std::int8_t faceSide : c.faceSides) change += (sideOfQ == faceSide || sideOfQ == 0) - (sideOfP == faceSide || sideOfP == 0);
      if (change == 0) return;
      // In front: the sign of orient3d(p, q, r, s) against the sign of the view rays'
      // spread across the edge (README of this folder derives it).
      const int order = viewer_.exact().orient3d(p, q, r, s);
      const int spread = sideOfR != 0 ? sideOfR : -sideOfS;
      if (order == 0 || order == spread) return;
      found.push_back({crossingParameter(edge, c), change});
    }); });
    std::sort(found.begin(), found.end(), [](const Crossing& a, const Crossing& b) { return a.u < b.u; });
    qiChanges_ += static_cast<std::int64_t>(found.size());
    return found;
  }

  static double crossingParameter(const FeatureEdge& edge, const Contour& contour) {
    const dvec2 dp = edge.pixelTo - edge.pixelFrom, dq = contour.pixelTo - contour.pixelFrom, offset = contour.pixelFrom - edge.pixelFrom;
    const double denominator = dp.x * dq.y - dp.y * dq.x;
    if (denominator == 0) return 0.5;  // parallel projections cannot cross; only rounding brings this here
    return std::clamp((offset.x * dq.y - offset.y * dq.x) / denominator, 0.0, 1.0);
  }

  // Walks edge e from `from` (whose QI is known) and returns its other vertex when that
  // vertex's QI was not known before, else kUnknown.
  std::uint32_t walkEdge(std::uint32_t e, std::uint32_t from, std::vector<LineSegment>& pieces) {
    const FeatureEdge& edge = lines_.edges[e];
    const bool forward = edge.vertexFrom == from;
    const std::uint32_t to = forward ? edge.vertexTo : edge.vertexFrom;
    const std::vector<Crossing> changes = crossings(e);
    int total = 0;
    for (const Crossing& crossing : changes) total += crossing.change;
    // The QI just after `from`, then at the edge's own start (u = 0).
    const int leaving = baseQi_[from] + vertexHiding(from, to);
    int qi = forward ? leaving : leaving - total;
    double u = 0;
    for (const Crossing& crossing : changes) {
      pieces.push_back({e, u, crossing.u, qi});
      negativeQi_ += qi < 0;
      qi += crossing.change;
      u = crossing.u;
    }
    pieces.push_back({e, u, 1.0, qi});
    negativeQi_ += qi < 0;
    // The QI just before `to`, less what the faces around `to` add: the QI of `to` itself.
    const int atEnd = forward ? qi : leaving - total;
    const int hiding = vertexHiding(to, from);
    vertexCorrections_ += hiding != 0;
    const int base = atEnd - hiding;
    if (baseQi_[to] == kUnknownQi) {
      baseQi_[to] = base;
      return to;
    }
    mismatches_ += baseQi_[to] != base;
    return kUnknown;
  }

  const PreparedScene& scene_;
  CameraTransform camera_;
  ViewerPredicates viewer_;
  Stats& stats_;
  const EdgeAdjacency& adjacency_;
  std::vector<std::int8_t> facing_;
  bool countEveryFace_ = false;
  LineSet lines_;
  std::vector<Contour> contours_;
  std::optional<ImageGrid> grid_;
  std::vector<std::uint32_t> seen_;  // per contour: the last edge that tested it
  std::vector<std::vector<std::uint32_t>> edgesAt_;
  std::vector<std::uint32_t> point_;  // per vertex: the first vertex at the same position
  VertexTriangles aroundPoint_;      // the triangles around each such point
  std::vector<int> baseQi_;  // per vertex: its QI, not counting the faces around it
  std::int64_t crossingsTested_ = 0, qiChanges_ = 0, vertexCorrections_ = 0, mismatches_ = 0, negativeQi_ = 0;
};

}  // namespace

LineSet run(const PreparedScene& scene, const Knobs& knobs, Stats& stats) {
  PhaseTimer timer(stats, "appel");
  return QuantitativeInvisibility(scene, knobs, stats).run();
}

}  // namespace hsr::appel
