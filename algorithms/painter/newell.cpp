// Newell, Newell and Sancha (1972): the depth sort made right.
//
// Work in screen space, where the projection is orthographic: x and y in pixels, and a
// depth z that is affine in screen space (so planes stay planes) and grows away from
// the eye. Then:
//   1. Sort the polygons by their farthest z; the farthest is the candidate to paint.
//   2. Before painting the candidate P, look at every polygon Q whose depth range
//      overlaps P's. P may be painted before Q if any of these tests, cheapest first,
//      proves that P does not hide part of Q:
//        a. the depth extents do not overlap;
//        b. the screen bounding boxes do not overlap;
//        c. P lies wholly behind Q's plane;
//        d. Q lies wholly in front of P's plane;
//        e. the projections do not overlap.
//   3. If all five fail, try the reverse: if Q lies wholly behind P's plane, or P wholly
//      in front of Q's, Q must be painted first: move Q to the front of the list and mark
//      it. If neither holds, P and Q pierce or overlap cyclically: split P by Q's plane
//      (or Q by P's) and put the pieces back in the list.
//   4. A marked Q that must move again closes a cycle of three or more polygons: split.
//
// The sign tests (c, d, e and the splits) are exact (renderer/geometry/predicates) on the
// screen-space coordinates. The one tolerance: a polygon whose world triangle lies within
// what the placements' rounding can move of another's world plane
// (PreparedScene::liesOn, renderer/geometry/rounding.hpp: relative to the coordinates' magnitude)
// is taken as coplanar with it, because faces coplanar as modelled are coplanar only up
// to that rounding, and either order is right for them (the reference marks their pixels
// ambiguous, or orders them by a depth difference within rounding). A piece cut from a
// polygon by Q's plane is on its side of that plane by construction and is never tested
// against it again, so rounding of the split points cannot make it straddle the plane
// that made it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "algorithms/painter/order.hpp"

namespace hsr::painter {
namespace {

// A convex polygon in screen space: a screen triangle, or a piece of one.
struct Polygon {
  std::uint32_t screenTriangle = 0;
  std::vector<dvec3> vertices;  // (x, y, z), in the winding of the screen triangle's corners
  std::vector<Cut> cuts;        // the planes that cut it out of its triangle, for drawing
  double minX = 0, maxX = 0, minY = 0, maxY = 0, minZ = 0, maxZ = 0;
  bool moved = false;  // moved to the front since the last polygon was painted

  void updateBounds() {
    minX = minY = minZ = std::numeric_limits<double>::infinity();
    maxX = maxY = maxZ = -std::numeric_limits<double>::infinity();
    for (const dvec3& v : vertices) {
      minX = std::min(minX, v.x), maxX = std::max(maxX, v.x);
      minY = std::min(minY, v.y), maxY = std::max(maxY, v.y);
      minZ = std::min(minZ, v.z), maxZ = std::max(maxZ, v.z);
    }
  }
};

// Where a polygon lies relative to another polygon's plane.
enum class Side { behind, inFront, straddles, coplanar };

class Newell {
 public:
  Newell(const PreparedScene& scene, const ScreenGeometry& geometry, const Knobs& knobs, Stats& stats, StepRecorder* steps)
      : scene_(scene), geometry_(geometry), knobs_(knobs), stats_(stats), steps_(steps) {
    const std::size_t count = geometry.triangles.size();
    planes_.resize(count);
    winding_.resize(count);
    worldPlanes_.resize(count);
    for (std::uint32_t s = 0; s < count; ++s) {
      for (int k = 0; k < 3; ++k) planes_[s][k] = screenPoint(geometry.corners[s][k]);
      winding_[s] = predicates_.orient2d(planes_[s][0], planes_[s][1], planes_[s][2]);
      Polygon polygon;
      polygon.screenTriangle = s;
      polygon.vertices.assign(planes_[s].begin(), planes_[s].end());
      polygon.updateBounds();
      pool_.push_back(std::move(polygon));
    }
  }

  PaintOrder run() {
    // Step 1: the list, farthest maxZ at the back (so the candidate is popped in O(1)).
    for (std::uint32_t i = 0; i < pool_.size(); ++i) pending_.push_back(i);
    std::stable_sort(pending_.begin(), pending_.end(), [&](std::uint32_t a, std::uint32_t b) { return farther(b, a); });
    std::size_t movesSinceLastPaint = 0;
    while (!pending_.empty() || !ahead_.empty()) {
      const std::uint32_t candidate = ahead_.empty() ? pending_.back() : ahead_.back();
      const std::optional<std::uint32_t> hidden = firstPolygonHiddenBy(candidate);
      if (!hidden) {
        paint(candidate);
        movesSinceLastPaint = 0;
        continue;
      }
      // Step 3: the reverse order, unless that polygon was already moved (step 4).
      const Polygon &p = pool_[candidate], &q = pool_[*hidden];
      const bool canMove = isBehindOrIn(side(q, p.screenTriangle)) || isInFrontOrIn(side(p, q.screenTriangle));
      if (canMove && !q.moved) {
        recordConflict(candidate, *hidden, "step 3: the candidate P = " + polygonName(candidate) + " (red) hides part of Q = " +
                                               polygonName(*hidden) + " (blue), so Q must be painted first: Q moves to the head of the list "
                                               "(reorder " + std::to_string(reorders_ + 1) + ")");
        moveToFront(*hidden);
        ++movesSinceLastPaint;
        continue;
      }
      const bool outOfSplits = double(splits_) >= knobs_.splitCap;
      if (!outOfSplits)
        recordConflict(candidate, *hidden,
                       "P = " + polygonName(candidate) + " (red), Q = " + polygonName(*hidden) + " (blue): " +
                           (q.moved ? "step 4: Q was moved already, so the polygons overlap in a cycle"
                                    : "step 3: neither order is proven (P is not wholly in front of Q's plane, nor Q wholly behind P's)") +
                           ", so one is split by the other's plane (split " + std::to_string(splits_ + 1) + ")");
      if (outOfSplits || !splitSomething(candidate, *hidden)) {
        // Out of splits, or no plane left to split by: paint out of order and say so,
        // rather than loop. The second happens in about 1 random scene in 300 (the
        // property tests, tests/property, count them), always at the point where three
        // mutually piercing triangles' planes meet: each pair's pieces are already cut
        // by each other's planes, rounding of the split points lets their projections
        // overlap by slivers, and the three orders the cuts give close a cycle
        // (algorithms/painter/README.md, "Known limits").
        if (canMove && !outOfSplits && movesSinceLastPaint <= pool_.size()) {
          moveToFront(*hidden);
          ++movesSinceLastPaint;
          continue;
        }
        ++(outOfSplits ? unresolvedAtCap_ : unresolvedWithoutSplit_);
        paint(candidate);
      }
    }
    stats_.add("newell splits", splits_);
    stats_.add("newell pairs tested", pairsTested_);
    stats_.add("newell reorders", reorders_);
    for (int test = 0; test < 5; ++test) stats_.add(kTestNames[test], decidedBy_[test]);
    stats_.add("newell unresolved conflicts", unresolvedAtCap_ + unresolvedWithoutSplit_);
    stats_.add("predicate evaluations", predicates_.evaluations);
    stats_.add("predicate exact fall-backs", predicates_.exactFallbacks);
    if (unresolvedAtCap_ > 0)
      order_.partial = "newell: the split cap (--knob split-cap=" + std::to_string(static_cast<long long>(knobs_.splitCap)) +
                       ") was reached; " + std::to_string(unresolvedAtCap_) + " polygons were painted in an unproven order";
    else if (unresolvedWithoutSplit_ > 0)
      order_.partial = "newell: " + std::to_string(unresolvedWithoutSplit_) +
                       " polygons in a cycle no plane splits were painted in an unproven order";
    return std::move(order_);
  }

 private:
  // Named by the textbook's letters, so that --stats (which sorts by name) lists them in
  // the order they are tried.
  static constexpr const char* kTestNames[5] = {
      "newell test a: depth extents", "newell test b: bounding boxes", "newell test c: P behind Q's plane",
      "newell test d: Q in front of P's plane", "newell test e: projections"};

  // A polygon as a caption names it: its triangle and object, and for a piece cut by
  // splits, its number in the pool.
  std::string polygonName(std::uint32_t polygon) const {
    const std::string triangle = scene_.triangleName(geometry_.triangles[pool_[polygon].screenTriangle].triangle);
    return pool_[polygon].cuts.empty() ? triangle : "piece " + std::to_string(polygon) + " of " + triangle;
  }

  // Screen space with a depth that grows away from the eye: t is 1/d under perspective
  // (so -t grows with d) and d under orthographic.
  dvec3 screenPoint(const dvec3& corner) const {
    return {corner.x, corner.y, geometry_.camera.perspective() ? -corner.z : corner.z};
  }

  bool farther(std::uint32_t a, std::uint32_t b) const { return pool_[a].maxZ > pool_[b].maxZ; }

  // Step 2: the first polygon that the candidate may hide, or none. The pending list is
  // sorted by maxZ, so the polygons whose depth range reaches past the candidate's near
  // end are a run at its back; the moved polygons are all checked.
  std::optional<std::uint32_t> firstPolygonHiddenBy(std::uint32_t candidate) {
    for (auto it = ahead_.rbegin(); it != ahead_.rend(); ++it)
      if (*it != candidate && !canPaintBefore(candidate, *it)) return *it;
    const double nearEnd = pool_[candidate].minZ;
    for (auto it = pending_.rbegin(); it != pending_.rend() && pool_[*it].maxZ > nearEnd; ++it)
      if (*it != candidate && !canPaintBefore(candidate, *it)) return *it;
    return std::nullopt;
  }

  // Tests a to e: true when P provably hides no part of Q.
  bool canPaintBefore(std::uint32_t pIndex, std::uint32_t qIndex) {
    const Polygon &p = pool_[pIndex], &q = pool_[qIndex];
    if (p.minZ >= q.maxZ) return decided(0);
    ++pairsTested_;
    if (p.maxX <= q.minX || q.maxX <= p.minX || p.maxY <= q.minY || q.maxY <= p.minY) return decided(1);
    if (isBehindOrIn(side(p, q.screenTriangle))) return decided(2);
    if (isInFrontOrIn(side(q, p.screenTriangle))) return decided(3);
    if (!projectionsOverlap(p, q)) return decided(4);
    return false;
  }

  bool decided(int test) {
    ++decidedBy_[test];
    return true;
  }

  static bool isBehindOrIn(Side s) { return s == Side::behind || s == Side::coplanar; }
  static bool isInFrontOrIn(Side s) { return s == Side::inFront || s == Side::coplanar; }

  // +1 if v is behind the screen triangle's plane (farther from the eye), -1 in front,
  // 0 on it. det[b - a, c - a, v - a] = n . (v - a), and n's z component is the
  // triangle's projected area, so sign(det) x winding = sign(v.z - plane z at v.x, v.y).
  int depthSide(std::uint32_t plane, const dvec3& v) {
    const auto& corners = planes_[plane];
    return predicates_.orient3d(corners[0], corners[1], corners[2], v) * winding_[plane];
  }

  Side side(const Polygon& polygon, std::uint32_t plane) {
    if (winding_[plane] == 0) return Side::coplanar;  // an edge-on plane hides nothing and orders nothing
    // A piece cut by this triangle's plane knows its side.
    const std::uint32_t triangle = geometry_.triangles[plane].triangle;
    for (const Cut& cut : polygon.cuts)
      if (cut.plane == triangle) return (cut.positive ? 1 : -1) == -eyeSideOf(triangle) ? Side::behind : Side::inFront;
    bool anyBehind = false, anyInFront = false;
    for (const dvec3& v : polygon.vertices) {
      const int s = depthSide(plane, v);
      anyBehind |= s > 0;
      anyInFront |= s < 0;
    }
    if (!anyBehind && !anyInFront) return Side::coplanar;
    if (scene_.liesOn(worldPlane(plane), geometry_.triangles[polygon.screenTriangle].triangle)) return Side::coplanar;
    if (anyBehind && anyInFront) return Side::straddles;
    return anyInFront ? Side::inFront : Side::behind;
  }

  // The world plane of a screen triangle's triangle, up to the placements' rounding,
  // made when first needed.
  const RoundedPlane& worldPlane(std::uint32_t plane) {
    std::optional<RoundedPlane>& rounded = worldPlanes_[plane];
    if (!rounded) rounded = scene_.planeUpToPlacement(geometry_.triangles[plane].triangle);
    return *rounded;
  }

  int eyeSideOf(std::uint32_t triangle) {
    const auto [it, inserted] = eyeSides_.try_emplace(triangle, 0);
    if (inserted) it->second = eyeSide(scene_, geometry_.camera, triangle, predicates_);
    return it->second;
  }

  // Test e: two convex polygons' interiors are disjoint exactly when some edge of one
  // has every vertex of the other on its outer side or on its line (the separating axis
  // theorem in the plane), decided exactly. An overlap narrower than kSliverPixels
  // counts as none: it is where rounded split points cross along a cut the two pieces
  // share (three triangles piercing each other leave pieces that touch along their cuts
  // and at the point where the three planes meet; their rounded outlines overlap by
  // slivers about 1e-12 of the image wide, and orders drawn from such slivers close
  // cycles no split can break). A pixel center in so thin a band is decided by the
  // pieces' exact cuts, or lies within the rasterizer's snapping of an edge.
  static constexpr double kSliverPixels = 1e-6;
  bool projectionsOverlap(const Polygon& p, const Polygon& q) {
    const int wp = winding_[p.screenTriangle], wq = winding_[q.screenTriangle];
    if (wp == 0 || wq == 0) return false;  // no area on screen
    if (separatedByAnEdgeOf(p, wp, q) || separatedByAnEdgeOf(q, wq, p)) return false;
    return overlapWidth(p, q, wq) > kSliverPixels;
  }

  // How wide the overlap of two convex projections is, as twice its area over its
  // perimeter, in pixels: p clipped by each of q's edges, in double precision.
  static double overlapWidth(const Polygon& p, const Polygon& q, int qWinding) {
    std::vector<dvec2> region, clipped;
    for (const dvec3& v : p.vertices) region.emplace_back(v.x, v.y);
    for (std::size_t i = 0; i < q.vertices.size() && !region.empty(); ++i) {
      if (!isEdge(q.vertices[i], q.vertices[(i + 1) % q.vertices.size()])) continue;
      const dvec2 a(q.vertices[i]), b(q.vertices[(i + 1) % q.vertices.size()]);
      const auto inside = [&](const dvec2& v) { return qWinding * ((b.x - a.x) * (v.y - a.y) - (b.y - a.y) * (v.x - a.x)); };
      clipped.clear();
      for (std::size_t k = 0; k < region.size(); ++k) {
        const dvec2 &u = region[k], &w = region[(k + 1) % region.size()];
        const double du = inside(u), dw = inside(w);
        if (du >= 0) clipped.push_back(u);
        if ((du >= 0) != (dw >= 0)) clipped.push_back(u + (du / (du - dw)) * (w - u));
      }
      region.swap(clipped);
    }
    // The area from the first vertex: a shoelace over the coordinates themselves would
    // cancel to rounding noise for a region far smaller than its distance from the origin.
    double twiceArea = 0, perimeter = 0;
    for (std::size_t k = 0; k < region.size(); ++k) {
      const dvec2 u = region[k] - region[0], w = region[(k + 1) % region.size()] - region[0];
      twiceArea += u.x * w.y - u.y * w.x;
      perimeter += glm::length(w - u);
    }
    return perimeter > 0 ? std::abs(twiceArea) / perimeter : 0;
  }

  // An edge shorter than kSliverPixels is no edge: split points made by repeated cuts
  // near one corner can lie a rounding apart, and the direction between them is noise
  // that could separate, or clip away, what overlaps. Leaving it out only makes both
  // tests see more overlap.
  static bool isEdge(const dvec3& a, const dvec3& b) { return glm::length(dvec2(b - a)) > kSliverPixels; }

  bool separatedByAnEdgeOf(const Polygon& p, int winding, const Polygon& q) {
    for (std::size_t i = 0; i < p.vertices.size(); ++i) {
      const dvec3 &a = p.vertices[i], &b = p.vertices[(i + 1) % p.vertices.size()];
      if (!isEdge(a, b)) continue;
      bool allOutside = true;
      for (const dvec3& v : q.vertices)
        if (predicates_.orient2d(a, b, v) * winding > 0) {
          allOutside = false;
          break;
        }
      if (allOutside) return true;
    }
    return false;
  }

  // Steps 3 and 4: split P by Q's plane if P straddles it, else Q by P's plane; in a
  // cycle, any moved polygon that straddles another moved polygon's plane. Returns false
  // when nothing straddles anything.
  bool splitSomething(std::uint32_t pIndex, std::uint32_t qIndex) {
    if (side(pool_[pIndex], pool_[qIndex].screenTriangle) == Side::straddles) return split(pIndex, qIndex), true;
    if (side(pool_[qIndex], pool_[pIndex].screenTriangle) == Side::straddles) return split(qIndex, pIndex), true;
    std::vector<std::uint32_t> cycle = ahead_;
    if (std::find(cycle.begin(), cycle.end(), pIndex) == cycle.end()) cycle.push_back(pIndex);
    for (const std::uint32_t x : cycle)
      for (const std::uint32_t y : cycle)
        if (x != y && side(pool_[x], pool_[y].screenTriangle) == Side::straddles && projectionsOverlap(pool_[x], pool_[y]))
          return split(x, y), true;
    return false;
  }

  // Replaces polygon x by its pieces behind and in front of y's plane.
  void split(std::uint32_t x, std::uint32_t y) {
    ++splits_;
    const std::uint32_t plane = pool_[y].screenTriangle;
    const std::uint32_t triangle = geometry_.triangles[plane].triangle;
    const Polygon source = pool_[x];
    std::vector<int> sides;
    std::vector<double> heights;
    const auto& corners = planes_[plane];
    for (const dvec3& v : source.vertices) {
      sides.push_back(depthSide(plane, v));
      heights.push_back(predicates_.orient3dValue(corners[0], corners[1], corners[2], v) * winding_[plane]);
    }
    SplitPolygon pieces = splitPolygon(source.vertices, sides, heights);  // positive: behind the plane
    Polygon behind, inFront;
    behind.vertices = std::move(pieces.positive);
    inFront.vertices = std::move(pieces.negative);
    const int behindSide = -eyeSideOf(triangle);
    for (Polygon* piece : {&behind, &inFront}) {
      piece->screenTriangle = source.screenTriangle;
      piece->cuts = source.cuts;
      piece->cuts.push_back({triangle, (piece == &behind ? behindSide : -behindSide) > 0});
      piece->updateBounds();
    }
    // The pieces replace x: the first in its slot, the second appended; both go back
    // into the sorted list.
    remove(x);
    pool_[x] = std::move(behind);
    pool_.push_back(std::move(inFront));
    insertSorted(x);
    insertSorted(static_cast<std::uint32_t>(pool_.size() - 1));
  }

  // A step (renderer/steps/steps.hpp): the candidate P in red and the polygon Q it may hide in
  // blue, over the outlines of every screen triangle.
  void recordConflict(std::uint32_t p, std::uint32_t q, const std::string& caption,
                      SourceLocation where = SourceLocation::current()) {
    if (!steps_ || !steps_->due(conflictsRecorded_++)) return;
    const CameraTransform& camera = geometry_.camera;
    Image picture = blankPicture(camera.width(), camera.height());
    const auto outline = [&](const std::vector<dvec3>& vertices, Rgb color, double width) {
      for (std::size_t k = 0; k < vertices.size(); ++k) {
        const dvec3 &a = vertices[k], &b = vertices[(k + 1) % vertices.size()];
        drawSegment(picture, {a.x, a.y}, {b.x, b.y}, color, width);
      }
    };
    for (const auto& corners : planes_) outline({corners.begin(), corners.end()}, {205, 205, 205}, 1.0);
    outline(pool_[q].vertices, kSecondHighlight, 2.5);
    outline(pool_[p].vertices, kHighlight, 2.5);
    steps_->record(caption, std::move(picture), where);
  }

  void moveToFront(std::uint32_t q) {
    ++reorders_;
    remove(q);
    pool_[q].moved = true;
    ahead_.push_back(q);
  }

  void paint(std::uint32_t candidate) {
    remove(candidate);
    order_.add(pool_[candidate].screenTriangle, pool_[candidate].cuts);
    for (const std::uint32_t m : ahead_) pool_[m].moved = false;
  }

  void remove(std::uint32_t index) {
    const auto inAhead = std::find(ahead_.begin(), ahead_.end(), index);
    if (inAhead != ahead_.end()) {
      ahead_.erase(inAhead);
      return;
    }
    // The pending list is sorted by maxZ: search the run of equal keys.
    const auto first = std::lower_bound(pending_.begin(), pending_.end(), index,
                                        [&](std::uint32_t a, std::uint32_t b) { return farther(b, a); });
    pending_.erase(std::find(first, pending_.end(), index));
  }

  void insertSorted(std::uint32_t index) {
    const auto at = std::upper_bound(pending_.begin(), pending_.end(), index,
                                     [&](std::uint32_t a, std::uint32_t b) { return farther(b, a); });
    pending_.insert(at, index);
  }

  const PreparedScene& scene_;
  const ScreenGeometry& geometry_;
  const Knobs& knobs_;
  Stats& stats_;
  StepRecorder* steps_;
  std::size_t conflictsRecorded_ = 0;
  ExactPredicates predicates_;
  std::vector<std::array<dvec3, 3>> planes_;  // each screen triangle's corners in (x, y, z)
  std::vector<int> winding_;                  // orient2d of those corners: 0 = no area on screen
  std::map<std::uint32_t, int> eyeSides_;     // by global triangle, computed when first needed
  std::vector<std::optional<RoundedPlane>> worldPlanes_;  // per screen triangle: worldPlane()
  std::vector<Polygon> pool_;
  std::vector<std::uint32_t> pending_;  // sorted by maxZ, farthest at the back
  std::vector<std::uint32_t> ahead_;    // moved in front of the list; the last is the candidate
  PaintOrder order_;
  std::int64_t splits_ = 0, pairsTested_ = 0, reorders_ = 0, unresolvedAtCap_ = 0, unresolvedWithoutSplit_ = 0;
  std::int64_t decidedBy_[5] = {};
};

}  // namespace

PaintOrder newellOrder(const PreparedScene& scene, const ScreenGeometry& geometry, const Knobs& knobs, Stats& stats,
                       StepRecorder* steps) {
  PhaseTimer timer(stats, "ordering");
  return Newell(scene, geometry, knobs, stats, steps).run();
}

}  // namespace hsr::painter
