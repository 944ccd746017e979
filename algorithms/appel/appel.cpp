#include "algorithms/appel/appel.hpp"

#include "renderer/scene/intersections.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "renderer/geometry/camera.hpp"
#include "renderer/geometry/predicates.hpp"
#include "renderer/image/image_grid.hpp"
#include "renderer/lines/line_drawing.hpp"
#include "renderer/scene/intersections.hpp"
#include "renderer/util/error.hpp"

namespace hsr::appel {

std::string refusal(const PreparedScene& scene, const Knobs& knobs) {
  if (std::string nearPlane = nearPlaneRefusal(scene); !nearPlane.empty()) return nearPlane;
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
// A change of QI along an edge: by `change`, or, after a degenerate piercing
// (renderer/scene/intersections.hpp) or where a contour's projection runs along the edge's, to
// whatever a fresh count finds.
struct Crossing {
  double u;
  int change;
  bool recount = false;
  // What made it, for hsr why --edge: a contour (an index into the contours), or a face
  // the edge passes through (a piercing); kUnknown for the other.
  std::uint32_t contour = kUnknown, face = kUnknown;
};

// Every change along an edge, sorted, and whether the QI at either end rests on a
// convention (a contour's projection running along the edge's up to that end).
struct Changes {
  std::vector<Crossing> crossings;
  bool conventionalStart = false, conventionalEnd = false;
};

class QuantitativeInvisibility {
 public:
  QuantitativeInvisibility(const PreparedScene& scene, const Knobs& knobs, Stats& stats, StepRecorder* steps, EdgeWitness* witness)
      : steps_(steps),
        witness_(witness),
        scene_(scene),
        camera_(scene.camera()),
        viewer_(camera_),
        stats_(stats),
        adjacency_(scene.edgeAdjacency(stats)),
        point_(scene.distinctPoints(stats)),
        intersections_(surfaceIntersectionsOf(scene, stats)) {
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
    // Vertices of different meshes at the same position (solids touching at a corner or
    // along an edge) are one point: the faces of both meet there, and a contour ending
    // there ends at the walk's vertex.
    std::vector<Triangle> welded(scene.triangles().begin(), scene.triangles().end());
    for (Triangle& t : welded)
      for (std::uint32_t& v : t) v = point_[v];
    aroundPoint_ = buildVertexTriangles(point_.size(), welded);
    // Where surfaces pass through each other (renderer/scene/intersections.hpp): the lines where
    // faces cross join the drawing's edges.
    firstJunction_ = static_cast<std::uint32_t>(lines_.edges.size());
    for (const Junction& junction : intersections_.junctions) {
      lines_.edges.push_back(projectEdge(camera_, junction.from, junction.to, EdgeKind::junction));
      lines_.edges.back().faces = {junction.faces[0], junction.faces[1]};
    }
    // The grid covers every edge's projection in the view and lists the contours through
    // each cell.
    dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const FeatureEdge& edge : lines_.edges) {
      lo = glm::min(lo, glm::min(edge.pixelFrom, edge.pixelTo));
      hi = glm::max(hi, glm::max(edge.pixelFrom, edge.pixelTo));
    }
    grid_.emplace(lo, hi, dvec2(lines_.width, lines_.height), knobs.cellPixels);
    grid_->bin(contours_.size(), [&](std::size_t i, auto&& add) { grid_->cellsOnSegment(contours_[i].pixelFrom, contours_[i].pixelTo, add); });
    stats.add("grid cells", static_cast<std::int64_t>(grid_->cellCount()));
    seen_.assign(contours_.size(), kUnknown);
    // Mesh edges around each vertex, for the walk.
    edgesAt_.resize(scene.positions().size());
    for (std::uint32_t e = 0; e < firstJunction_; ++e) {
      edgesAt_[lines_.edges[e].vertexFrom].push_back(e);
      edgesAt_[lines_.edges[e].vertexTo].push_back(e);
    }
  }

  LineSet run() {
    // Steps 2 and 3, once per connected set of mesh edges.
    baseQi_.assign(scene_.positions().size(), kUnknownQi);
    conventional_.assign(scene_.positions().size(), 0);
    std::vector<std::vector<LineSegment>> pieces(lines_.edges.size());
    std::vector<std::uint8_t> walked(firstJunction_, 0);
    std::size_t decided = 0;  // edges whose pieces are known, for the steps
    for (std::uint32_t seed = 0; seed < firstJunction_; ++seed) {
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
          if (steps_)
            recordStep(pieces, e, "step 3: edge " + std::to_string(++decided) + " of " + std::to_string(lines_.edges.size()) +
                                      " walked from a vertex of QI " + std::to_string(baseQi_[vertex]) + ", its QI changing by +1 or -1 where it passes behind a contour");
        }
      }
    }
    // Step 4: the intersection lines.
    for (std::uint32_t e = firstJunction_; e < lines_.edges.size(); ++e) {
      drawJunction(e, intersections_.junctions[e - firstJunction_], pieces[e]);
      if (steps_)
        recordStep(pieces, e, "step 4: intersection line " + std::to_string(++decided) + " of " + std::to_string(lines_.edges.size()) +
                                  ": QI of its longest piece by a ray cast, then carried along it");
    }
    for (auto& edgePieces : pieces) lines_.segments.insert(lines_.segments.end(), edgePieces.begin(), edgePieces.end());
    stats_.add("crossings tested", crossingsTested_);
    stats_.add("QI changes", qiChanges_);
    stats_.add("vertex corrections", vertexCorrections_);
    stats_.add("QI mismatches", mismatches_);
    stats_.add("negative QI", negativeQi_);
    stats_.add("exact fall-backs", viewer_.exact().exactFallbacks);
    // A count that does not close is a configuration the tie rules do not settle (an edge
    // passing exactly through a corner of another surface): say so rather than draw it
    // silently wrong.
    if (mismatches_ > 0 || negativeQi_ > 0)
      lines_.partial = "appel: " + std::to_string(mismatches_) + " edges ended with another QI than their vertex had and " +
                       std::to_string(negativeQi_) + " pieces got a negative QI (surfaces touching exactly at a corner or an edge); "
                       "the drawing may be wrong near them";
    return std::move(lines_);
  }

 private:
  static constexpr int kUnknownQi = std::numeric_limits<int>::min();

  // A step (renderer/steps/steps.hpp): the pieces known so far, edge e just decided.
  void recordStep(const std::vector<std::vector<LineSegment>>& pieces, std::uint32_t e, std::string caption,
                  SourceLocation where = SourceLocation::current()) {
    if (!steps_->due(recorded_++, lines_.edges.size())) return;
    LineSet sofar;
    sofar.width = lines_.width, sofar.height = lines_.height, sofar.edges = lines_.edges;
    for (const auto& edgePieces : pieces) sofar.segments.insert(sofar.segments.end(), edgePieces.begin(), edgePieces.end());
    steps_->record(std::move(caption), lineStepPicture(sofar, std::span(&e, 1), LineStyle::qi), where);
  }

  StepRecorder* steps_;
  std::size_t recorded_ = 0;
  EdgeWitness* witness_;  // hsr why --edge's edge, or null

  // hsr why --edge: the walk along the edge asked about, in the order it met it: where
  // it started and with what QI, each change and what made it, where it arrived.
  bool watched(std::uint32_t e) const { return witness_ && witness_->edge == e; }
  void witnessChanges(const std::vector<Crossing>& crossings, bool forward) {
    std::vector<Crossing> met(crossings);
    if (!forward) std::reverse(met.begin(), met.end());
    for (const Crossing& crossing : met) {
      const int change = forward ? crossing.change : -crossing.change;  // as the walk meets it
      const std::string by = crossing.contour != kUnknown
                                 ? "the contour edge from vertex " + std::to_string(contours_[crossing.contour].from) + " to vertex " +
                                       std::to_string(contours_[crossing.contour].to) + ", which lies in front of this edge there"
                             : crossing.face != kUnknown ? "triangle " + std::to_string(crossing.face) + ", which the edge passes through"
                                                         : "";
      if (crossing.recount)
        witness_->events.push_back({crossing.u, 0, "counted afresh by a ray cast",
                                    crossing.face != kUnknown ? "it passes exactly through a side or corner of " + by
                                                              : "a contour's projection runs along the edge's here"});
      else
        witness_->events.push_back({crossing.u, change, std::string(change > 0 ? "+" : "") + std::to_string(change) +
                                                    (change > 0 ? ": it passes behind " : ": it comes out from behind ") + by,
                                    crossing.contour != kUnknown ? "its projection crosses the contour's: the change is the contour's "
                                                                   "counted faces on the side the walk enters, less those on the side it leaves"
                                                                 : "a piercing: one side of the edge lies behind the face"});
    }
  }

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
      const int qi = facesBefore(position(vertex), degenerate, [&](std::uint32_t face) {
        const Triangle& corners = scene_.triangles()[face];
        return std::find(corners.begin(), corners.end(), vertex) != corners.end();
      });
      stats_.add("start-vertex ray casts");
      for (const std::uint32_t e : edgesAt_[vertex]) {
        const std::uint32_t other = lines_.edges[e].vertexFrom == vertex ? lines_.edges[e].vertexTo : lines_.edges[e].vertexFrom;
        if (std::find(tried.begin(), tried.end(), other) == tried.end()) tried.push_back(other);
      }
      if (!degenerate || i + 1 == tried.size() || i + 1 == kAttempts) {
        if (degenerate) stats_.add("degenerate start rays");
        baseQi_[vertex] = qi;
        conventional_[vertex] = degenerate;
        return vertex;
      }
    }
  }

  // The counted faces crossed by the line of sight to a point before it reaches it, but
  // those that skip() names: at a vertex, the faces around it, which are the walk's to
  // count (vertexHiding); on an intersection line, the two faces it lies on.
  template <typename Skip>
  int facesBefore(const dvec3& v, bool& degenerate, Skip&& skip) {
    const Ray ray = camera_.perspective() ? Ray{camera_.camera().eye, v - camera_.camera().eye} : Ray{v, -camera_.forward()};
    const double reach = camera_.perspective() ? 1.0 : std::numeric_limits<double>::infinity();
    const RayBoxTest boxTest(ray.origin, ray.direction);
    const auto& triangles = scene_.leafTriangles(stats_);
    int count = 0;
    scene_.triangleBvh(stats_).visitPrimitives(
        [&](const BvhNode& node) { return boxTest.entry(node, reach) != std::numeric_limits<double>::infinity(); },
        [&](std::uint32_t triangle, std::uint32_t slot) {
          const auto& t = triangles[slot];
          if (!counted(triangle) || skip(triangle)) return;
          // The point must lie behind the plane, on the side away from the viewer.
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
  // `onASide` is set when the projection runs exactly along a side of a face behind which
  // the edge leaves: there the count is the convention's, and the walk counts afresh.
  int vertexHiding(std::uint32_t vertex, std::uint32_t toward, bool& onASide) {
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
      onASide = onASide || sideOfA == 0 || sideOfB == 0;
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
  // it leaves, and where it passes through a counted face (addPiercings). A point on a
  // contour's line counts as behind all of its faces (closed, as the line reference's
  // triangles are), and a contour end on the edge's line counts as on its positive side,
  // so a contour chain through that line is crossed once, not twice.
  Changes changesAlong(std::uint32_t e) {
    const FeatureEdge& edge = lines_.edges[e];
    const dvec3 &p = edge.from, &q = edge.to;
    Changes changes;
    std::vector<Crossing>& found = changes.crossings;
    grid_->cellsOnSegment(edge.pixelFrom, edge.pixelTo, [&](std::size_t cell) { grid_->itemsIn(cell, [&](std::uint32_t index) {
      if (seen_[index] == e) return;
      seen_[index] = e;
      const Contour& c = contours_[index];
      if (edge.vertexFrom != FeatureEdge::kNone) {  // a mesh edge
        const std::uint32_t p0 = point_[edge.vertexFrom], p1 = point_[edge.vertexTo];
        if (point_[c.from] == p0 || point_[c.from] == p1 || point_[c.to] == p0 || point_[c.to] == p1) return;  // meets at a vertex
      } else {  // an intersection line: it ends on a side of one of its faces, and passes behind none of them
        const Junction& junction = intersections_.junctions[e - firstJunction_];
        if (hasSide(junction.faces[0], c.from, c.to) || hasSide(junction.faces[1], c.from, c.to)) return;
      }
      // A first look in the image: projections that clearly miss each other (a margin of a
      // millionth of their sizes, far above the projection's rounding) cannot cross, and
      // the exact signs below would say so.
      if (clearlyApart(edge.pixelFrom, edge.pixelTo, c.pixelFrom, c.pixelTo)) return;
      ++crossingsTested_;
      const dvec3 &r = position(c.from), &s = position(c.to);
      const int sideOfR = viewer_.side(p, q, r), sideOfS = viewer_.side(p, q, s);
      if (sideOfR == 0 && sideOfS == 0) {
        // The contour's projection runs along the edge's (both in one sight plane): no
        // crossing rule applies, and whether the contour's face covers the edge is a
        // matter of closed triangles. Count afresh where the two overlap.
        const dvec2 along = edge.pixelTo - edge.pixelFrom;
        if (glm::dot(along, along) == 0) return;  // an edge seen end-on has no length to recount
        const auto at = [&](const dvec2& x) { return glm::dot(x - edge.pixelFrom, along) / glm::dot(along, along); };
        const double u0 = std::max(0.0, std::min(at(c.pixelFrom), at(c.pixelTo))), u1 = std::min(1.0, std::max(at(c.pixelFrom), at(c.pixelTo)));
        if (!(u0 < u1)) return;
        found.push_back({u0, 0, true, index});
        found.push_back({u1, 0, true, index});
        changes.conventionalStart |= u0 == 0;
        changes.conventionalEnd |= u1 == 1;
        return;
      }
      if ((sideOfR >= 0) == (sideOfS >= 0)) return;
      // BEGIN SOLUTION
      const int sideOfP = viewer_.side(r, s, p), sideOfQ = viewer_.side(r, s, q);
      int change = 0;
      for (const std::int8_t faceSide : c.faceSides) change += (sideOfQ == faceSide || sideOfQ == 0) - (sideOfP == faceSide || sideOfP == 0);
      if (change == 0) return;
      // In front: the sign of orient3d(p, q, r, s) against the sign of the view rays'
      // spread across the edge (README of this folder derives it).
      const int order = viewer_.exact().orient3d(p, q, r, s);
      const int spread = sideOfR != 0 ? sideOfR : -sideOfS;
      if (order == 0 || order == spread) return;
      found.push_back({crossingParameter(edge, c), change, false, index});
      // SKELETON
      // // Exercise 5: the projections of edge pq and contour rs cross. By how much does the
      // // QI change there? Per face of the contour (c.faceSides: on which side of the sight
      // // plane through r and s each face lies), +1 when the edge's end q lies on that side
      // // (viewer_.side(r, s, q); 0, on the plane, counts as on it) and -1 when its start p
      // // does. A change of 0 is no change. And does the contour pass in front of the edge,
      // // or behind it? The sign of viewer_.exact().orient3d(p, q, r, s) against the spread
      // // of the eye rays across the edge (sideOfR, or -sideOfS where sideOfR is 0): in
      // // front when they differ and neither is 0 (README of this folder derives it). Record
      // // a change in front: found.push_back({crossingParameter(edge, c), change, false, index});
      // (void)sideOfR, (void)sideOfS;
      // END SOLUTION
    }); });
    if (edge.meshEdge != FeatureEdge::kNone) {
      addPiercings(edge, intersections_.byEdge[edge.meshEdge], edge.vertexFrom != adjacency_.edges[edge.meshEdge].a, found);
    } else {
      // Its two faces hold it, and their neighbours across a side meet it only at its ends.
      const Junction& junction = intersections_.junctions[e - firstJunction_];
      std::vector<std::uint32_t> skip;
      for (const std::uint32_t face : junction.faces)
        for (int k = 0; k < 3; ++k) {
          const Triangle& t = scene_.triangles()[face];
          for (const std::uint32_t other : aroundPoint_.around(point_[t[std::size_t(k)]]))
            if (hasSide(other, t[std::size_t(k)], t[std::size_t(k + 1) % 3])) skip.push_back(other);
        }
      const double rounding = std::max(scene_.instanceOf(junction.faces[0]).placementRounding,
                                       scene_.instanceOf(junction.faces[1]).placementRounding);
      addPiercings(edge, segmentPiercings(scene_, edge.from, edge.to, rounding, skip), false, found);
    }
    std::sort(found.begin(), found.end(), [](const Crossing& a, const Crossing& b) { return a.u < b.u; });
    qiChanges_ += static_cast<std::int64_t>(found.size());
    return changes;
  }

  // Where an edge passes through a counted face (intersections.hpp), that face lies in
  // front of its points on one side and not on the other: +1 going behind it, -1 coming
  // out. A point on the face's plane is not behind it (a face through a point does not
  // hide it, as in the line reference). After a degenerate piercing the QI is counted
  // afresh. `reversed`: the piercings' parameter runs from the edge's end to its start.
  void addPiercings(const FeatureEdge& edge, const std::vector<Piercing>& piercings, bool reversed, std::vector<Crossing>& found) {
    for (const Piercing& piercing : piercings) {
      if (!counted(piercing.face)) continue;
      const double u = edge.projectedParameter(reversed ? 1 - piercing.s : piercing.s);
      if (piercing.degenerate) {
        found.push_back({u, 0, true, kUnknown, piercing.face});
        continue;
      }
      const bool firstBehind = piercing.first * facing_[piercing.face] < 0;
      const bool startBehind = reversed ? !firstBehind : firstBehind;
      found.push_back({u, startBehind ? -1 : 1, false, kUnknown, piercing.face});
    }
  }

  // Whether segments ab and cd, in pixels, are certainly disjoint: their boxes are apart,
  // or c and d lie on the same side of line ab, each beyond the margin.
  static bool clearlyApart(const dvec2& a, const dvec2& b, const dvec2& c, const dvec2& d) {
    const double margin = 1e-6 * (glm::length(b - a) + glm::length(d - c)) + 1e-9;
    if (std::max(c.x, d.x) < std::min(a.x, b.x) - margin || std::min(c.x, d.x) > std::max(a.x, b.x) + margin ||
        std::max(c.y, d.y) < std::min(a.y, b.y) - margin || std::min(c.y, d.y) > std::max(a.y, b.y) + margin)
      return true;
    const dvec2 along = b - a;
    const double sideOfC = along.x * (c.y - a.y) - along.y * (c.x - a.x), sideOfD = along.x * (d.y - a.y) - along.y * (d.x - a.x);
    const double threshold = margin * glm::length(along);
    return (sideOfC > threshold && sideOfD > threshold) || (sideOfC < -threshold && sideOfD < -threshold);
  }

  // Whether the face has a side from the point of vertex a to the point of vertex b.
  bool hasSide(std::uint32_t face, std::uint32_t a, std::uint32_t b) const {
    const Triangle& t = scene_.triangles()[face];
    const auto has = [&](std::uint32_t v) { return point_[t[0]] == point_[v] || point_[t[1]] == point_[v] || point_[t[2]] == point_[v]; };
    return has(a) && has(b);
  }

  static bool onJunction(const Junction& junction, std::uint32_t face) {
    return face == junction.faces[0] || face == junction.faces[1];
  }

  static double crossingParameter(const FeatureEdge& edge, const Contour& contour) {
    const dvec2 dp = edge.pixelTo - edge.pixelFrom, dq = contour.pixelTo - contour.pixelFrom, offset = contour.pixelFrom - edge.pixelFrom;
    const double denominator = dp.x * dq.y - dp.y * dq.x;
    if (denominator == 0) return 0.5;  // parallel projections cannot cross; only rounding brings this here
    return std::clamp((offset.x * dq.y - offset.y * dq.x) / denominator, 0.0, 1.0);
  }

  // The QI of a piece of edge e, [from, to] in u, counted afresh by a ray cast to a
  // point inside it, not counting the faces the edge lies on (skip). A sight line grazing
  // a side is passed over for another point, as at the start vertices.
  template <typename Skip>
  int recount(std::uint32_t e, double from, double to, Skip&& skip) {
    const FeatureEdge& edge = lines_.edges[e];
    int qi = 0;
    for (const double at : {0.5, 0.3, 0.7}) {
      bool degenerate = false;
      const double s = edge.edgeParameter(from + at * (to - from));
      qi = facesBefore(edge.from + s * (edge.to - edge.from), degenerate, skip);
      stats_.add("recount ray casts");
      if (!degenerate) return qi;
    }
    stats_.add("degenerate recounts");
    return qi;
  }

  // The pieces of edge e between its changes (sorted), with their QIs, filled outward
  // from one piece whose QI is known: the first (`anchor` 0) or the last (`anchor`
  // kLastPiece) with QI *known, or, when `known` is null, the longest, counted afresh.
  // Returns the QIs of the first and the last piece.
  static constexpr std::size_t kLastPiece = std::numeric_limits<std::size_t>::max();
  template <typename Skip>
  std::pair<int, int> appendPieces(std::uint32_t e, const std::vector<Crossing>& changes, std::size_t anchor, const int* known,
                                   Skip&& skip, std::vector<LineSegment>& pieces) {
    std::vector<double> bounds = {0.0};
    for (const Crossing& crossing : changes) bounds.push_back(crossing.u);
    bounds.push_back(1.0);
    const std::size_t count = changes.size() + 1;
    if (anchor == kLastPiece) anchor = count - 1;
    if (!known)
      for (std::size_t piece = 0; piece < count; ++piece)
        if (bounds[piece + 1] - bounds[piece] > bounds[anchor + 1] - bounds[anchor]) anchor = piece;
    std::vector<int> qi(count);
    qi[anchor] = known ? *known : recount(e, bounds[anchor], bounds[anchor + 1], skip);
    for (std::size_t piece = anchor + 1; piece < count; ++piece) {  // forward, across changes[piece - 1]
      const Crossing& between = changes[piece - 1];
      qi[piece] = between.recount ? recount(e, bounds[piece], bounds[piece + 1], skip) : qi[piece - 1] + between.change;
    }
    for (std::size_t piece = anchor; piece-- > 0;) {  // backward, across changes[piece]
      const Crossing& between = changes[piece];
      qi[piece] = between.recount ? recount(e, bounds[piece], bounds[piece + 1], skip) : qi[piece + 1] - between.change;
    }
    for (std::size_t piece = 0; piece < count; ++piece) {
      if (piece > 0 && qi[piece] == qi[piece - 1]) {  // a recount that found no change: one piece
        pieces.back().end = bounds[piece + 1];
        continue;
      }
      pieces.push_back({e, bounds[piece], bounds[piece + 1], qi[piece]});
      negativeQi_ += qi[piece] < 0;
    }
    return {qi.front(), qi.back()};
  }

  // Walks edge e from `from` (whose QI is known) and returns its other vertex when that
  // vertex's QI was not known before, else kUnknown. Where a vertex's count rests on a
  // convention (a sight line grazing a side, an edge running along one: axis-aligned
  // views of grids meet it at every vertex), the edge's QI is counted afresh instead of
  // carried from it, and such a vertex is no evidence of a mismatch.
  std::uint32_t walkEdge(std::uint32_t e, std::uint32_t from, std::vector<LineSegment>& pieces) {
    const FeatureEdge& edge = lines_.edges[e];
    const bool forward = edge.vertexFrom == from;
    const std::uint32_t to = forward ? edge.vertexTo : edge.vertexFrom;
    // The QI just after `from`: its own, plus the faces around it that hide the edge's start.
    const Changes changes = changesAlong(e);
    bool startOnASide = forward ? changes.conventionalStart : changes.conventionalEnd;
    const int leaving = baseQi_[from] + vertexHiding(from, to, startOnASide);
    const bool carried = !startOnASide && !conventional_[from];
    // A recount along the edge must not count the faces the edge lies on.
    const auto onEdge = [&](std::uint32_t face) { return hasSide(face, from, to); };
    const auto [atStart, atEnd] = appendPieces(e, changes.crossings, forward ? 0 : kLastPiece, carried ? &leaving : nullptr, onEdge, pieces);
    const int arriving = forward ? atEnd : atStart;
    // The QI just before `to`, less what the faces around `to` add: the QI of `to` itself.
    bool endOnASide = forward ? changes.conventionalEnd : changes.conventionalStart;
    const int hiding = vertexHiding(to, from, endOnASide);
    vertexCorrections_ += hiding != 0;
    const int base = arriving - hiding;
    if (watched(e)) [[unlikely]] {
      const int hidingStart = leaving - baseQi_[from];
      witness_->events.push_back(
          {forward ? 0.0 : 1.0, 0, "the walk starts at vertex " + std::to_string(from) + ", of QI " + std::to_string(baseQi_[from]),
           carried ? "QI " + std::to_string(leaving) + " just after it: " + std::to_string(hidingStart) +
                         (hidingStart == 1 ? " face" : " faces") + " around the vertex hide the edge where the walk leaves it"
                   : "the QI just after it rests on a convention (a sight line along a side): counted afresh by a ray cast"});
      witnessChanges(changes.crossings, forward);
      witness_->events.push_back({forward ? 1.0 : 0.0, 0, "the walk arrives at vertex " + std::to_string(to),
                                  "QI " + std::to_string(arriving) + " just before it, less " + std::to_string(hiding) +
                                      (hiding == 1 ? " face" : " faces") + " around it hiding the edge where the walk reaches it: vertex QI " +
                                      std::to_string(base) +
                                      (baseQi_[to] == kUnknownQi ? " (new: the walk goes on from it)"
                                       : baseQi_[to] == base     ? " (as it was already known)"
                                                                 : " (it was known as " + std::to_string(baseQi_[to]) + ": a mismatch)")});
    }
    if (baseQi_[to] == kUnknownQi) {
      baseQi_[to] = base;
      conventional_[to] = endOnASide;
      return to;
    }
    if (!endOnASide && !conventional_[to]) mismatches_ += baseQi_[to] != base;
    return kUnknown;
  }

  // Step 4: an intersection line belongs to no walk (its ends are no vertices), so the QI
  // of its longest piece is counted by a ray cast, not counting the two faces it lies on,
  // and changes along it as along any edge.
  void drawJunction(std::uint32_t e, const Junction& junction, std::vector<LineSegment>& pieces) {
    const Changes changes = changesAlong(e);
    appendPieces(e, changes.crossings, 0, nullptr, [&](std::uint32_t face) { return onJunction(junction, face); }, pieces);
    if (watched(e)) [[unlikely]] {
      witness_->events.push_back({0.0, 0, "an intersection line: no walk reaches it",
                                  "the QI of its longest piece is counted by a ray cast, not counting triangles " +
                                      std::to_string(junction.faces[0]) + " and " + std::to_string(junction.faces[1]) + " it lies on"});
      witnessChanges(changes.crossings, true);
    }
  }

  const PreparedScene& scene_;
  CameraTransform camera_;
  ViewerPredicates viewer_;
  Stats& stats_;
  const EdgeAdjacency& adjacency_;
  const std::vector<std::uint32_t>& point_;  // per vertex: the first vertex at the same position
  const SurfaceIntersections& intersections_;
  std::vector<std::int8_t> facing_;
  bool countEveryFace_ = false;
  LineSet lines_;
  std::vector<Contour> contours_;
  std::optional<ImageGrid> grid_;
  std::vector<std::uint32_t> seen_;  // per contour: the last edge that tested it
  std::vector<std::vector<std::uint32_t>> edgesAt_;  // per vertex: the mesh edges of the drawing there
  std::uint32_t firstJunction_ = 0;  // lines_.edges from here on are intersection lines
  VertexTriangles aroundPoint_;      // the triangles around each such point
  std::vector<int> baseQi_;  // per vertex: its QI, not counting the faces around it
  std::vector<std::uint8_t> conventional_;  // per vertex: its QI rests on a convention (walkEdge)
  std::int64_t crossingsTested_ = 0, qiChanges_ = 0, vertexCorrections_ = 0, mismatches_ = 0, negativeQi_ = 0;
};

}  // namespace

LineSet run(const PreparedScene& scene, const Knobs& knobs, Stats& stats, StepRecorder* steps, EdgeWitness* edge) {
  PhaseTimer timer(stats, "appel");
  return QuantitativeInvisibility(scene, knobs, stats, steps, edge).run();
}

AlgorithmEntry entry() {
  AlgorithmEntry entry;
  entry.name = "appel";
  entry.kind = AlgorithmKind::line;
  entry.summary = "quantitative invisibility: walk the edges of closed meshes, counting the faces in front (Appel 1967)";
  setKnobs(entry, knobTable());
  entry.keyCounters = {"feature edges", "contour edges", "crossings tested", "QI changes", "start-vertex ray casts",
                       "QI mismatches"};
  setRefusal(entry, refusal);
  setDrawing(entry, run);
  entry.judgeLines = judgedByLineReference;
  return entry;
}

}  // namespace hsr::appel
