// Weiler-Atherton: the nearest polygon clips the rest; what lies inside it and behind it
// is removed; a piece found in front of it clips in turn.
#include "algorithms/weiler_atherton/weiler_atherton.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <string>

#include "renderer/raster/plane_depth.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "renderer/util/conventions.hpp"

namespace hsr::weiler_atherton {
namespace {

// GCC's 128-bit integer (an extension: the __extension__ keeps -Wpedantic quiet about it).
__extension__ typedef __int128 Wide;
using conventions::kSubpixelScale;

// A boundary line f(X, Y) = a X + b Y + c, in the rasterizer's sub-pixel units, with the
// polygon on its positive side. Each is one of the rasterizer's edge functions E doubled
// and moved by one: inside an edge is 2E + 1 > 0, outside -(2E + 1) > 0. At a pixel
// center E is an integer, so f is odd there: never zero. A center is inside a polygon
// exactly when it is strictly inside each of its lines, which is the rasterizer's rule
// (E >= 0 after the top-left bias) for the edges of its triangle.
// Sizes: sub-pixel coordinates within the guard band are below 2^29 in magnitude, so
// a and b are below 2^31 and c below 2^60.
struct Line {
  std::int64_t a, b, c;
  Line flipped() const { return {-a, -b, -c}; }
};

Line insideEdge(const ScreenTriangle& tri, int k) { return {2 * tri.edgeA[k], 2 * tri.edgeB[k], 2 * tri.edgeC[k] + 1}; }

// A corner: where two lines meet, (x / w, y / w) in sub-pixel units with w > 0, exact.
// x and y stay below 2^92 and w below 2^63, so a line's value there, a x + b y + c w,
// stays below 2^125: 128-bit integers hold every product.
struct Point {
  Wide x, y, w;
};

Point meet(const Line& p, const Line& q) {
  Wide w = Wide(p.a) * q.b - Wide(q.a) * p.b;
  Wide x = Wide(p.b) * q.c - Wide(q.b) * p.c;
  Wide y = Wide(p.c) * q.a - Wide(q.c) * p.a;
  if (w < 0) w = -w, x = -x, y = -y;
  return {x, y, w};
}

// Which side of the line the point lies on: +1, 0 or -1, exactly.
int sideOf(const Line& line, const Point& p) {
  const Wide value = Wide(line.a) * p.x + Wide(line.b) * p.y + Wide(line.c) * p.w;
  return (value > 0) - (value < 0);
}

// In pixel units, rounded: for depths, boxes and drawings, never for a decision of sides.
dvec2 approximate(const Point& p) {
  const double w = static_cast<double>(p.w) * kSubpixelScale;
  return {static_cast<double>(p.x) / w, static_cast<double>(p.y) / w};
}

// Sutherland-Hodgman in double precision, for drawings: the part of a convex polygon
// where the affine function f is negative.
template <typename Affine>
std::vector<dvec2> clippedWhereNegative(const std::vector<dvec2>& polygon, Affine&& f) {
  std::vector<dvec2> part;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const dvec2 &from = polygon[i], &to = polygon[(i + 1) % polygon.size()];
    const double here = f(from), next = f(to);
    if (here < 0) part.push_back(from);
    if ((here < 0) != (next < 0)) part.push_back(from + (to - from) * (here / (here - next)));
  }
  return part;
}

// A convex outline of positive area: each corner, and the line from it to the next.
struct Corner {
  Point point;
  Line edge;
};
using Outline = std::vector<Corner>;

// Sutherland-Hodgman against one line: the part of a convex outline on one side of it,
// given each corner's side. A corner on the line belongs to both parts; a
// part with no corner strictly on its side has no area, and is not made.
// keep = +1 keeps the positive side, -1 the negative (whose boundary is the line flipped).
Outline clipped(const Outline& outline, const std::vector<int>& sides, const Line& cut, int keep) {
  const Line line = keep > 0 ? cut : cut.flipped();
  Outline part;
  part.reserve(outline.size() + 1);  // a cut adds at most one corner
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Corner& from = outline[i];
    const int here = sides[i] * keep, next = sides[(i + 1) % outline.size()] * keep;
    if (here >= 0) {
      if (next >= 0) part.push_back(from);                            // along an edge that stays on this side
      else if (here == 0) part.push_back({from.point, line});         // leaving at this corner: on along the line
      else part.push_back(from), part.push_back({meet(from.edge, line), line});  // leaving across the edge
    } else if (next > 0) {
      part.push_back({meet(from.edge, line), from.edge});  // entering across the edge
    }
  }
  return part;
}

struct Box {
  double x0, y0, x1, y1;
  bool meets(const Box& other) const { return x0 <= other.x1 && other.x0 <= x1 && y0 <= other.y1 && other.y0 <= y1; }
};

// A box around the outline, a sub-pixel unit wider each way than its rounded corners
// (whose rounding is a few units in their last place, far less): sure to hold it.
Box boxOf(const Outline& outline) {
  Box box{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const Corner& corner : outline) {
    const dvec2 p = approximate(corner.point);
    box = {std::min(box.x0, p.x), std::min(box.y0, p.y), std::max(box.x1, p.x), std::max(box.y1, p.y)};
  }
  constexpr double kMargin = 1.0 / kSubpixelScale;
  return {box.x0 - kMargin, box.y0 - kMargin, box.x1 + kMargin, box.y1 + kMargin};
}

// The area of an outline in square pixels, from its rounded corners (shoelace formula).
double areaOf(const Outline& outline) {
  double twiceArea = 0;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const dvec2 a = approximate(outline[i].point), b = approximate(outline[(i + 1) % outline.size()].point);
    twiceArea += a.x * b.y - b.x * a.y;
  }
  return std::abs(twiceArea) / 2;
}

// Below this area (in square pixels) a part inside a clip polygon that holds no pixel
// center is a sliver: the piece is left whole rather than cut around it. Only the
// drawing sees the choice (the piece drawn over the clip polygon's outline in the
// sliver), so it is kept far below a pixel.
constexpr double kSliverArea = 1.0 / 64;

// A piece of a polygon: the part of screen triangle `polygon` within its outline, and
// where it passes through other polygons, only where it is nearer than each of
// `nearerThan` (decided per pixel center).
struct Piece {
  std::uint32_t polygon;
  Outline outline;
  std::vector<std::uint32_t> nearerThan;
  Box box;  // boxOf(outline)

  Piece(std::uint32_t polygon_, Outline outline_, std::vector<std::uint32_t> nearerThan_)
      : polygon(polygon_), outline(std::move(outline_)), nearerThan(std::move(nearerThan_)), box(boxOf(outline)) {}
};

// Whether the center of pixel (x, y) lies strictly inside every line of the outline:
// step 5's test (Clipper::show) at one pixel, for hsr why.
bool holdsCenter(const Outline& outline, int x, int y) {
  const std::int64_t px = x * kSubpixelScale + kSubpixelScale / 2, py = y * kSubpixelScale + kSubpixelScale / 2;
  return std::all_of(outline.begin(), outline.end(), [&](const Corner& corner) {
    return corner.edge.a * px + corner.edge.b * py + corner.edge.c > 0;
  });
}

// Step 5's solve on one row: of pixels first..last of row y, those whose centers lie
// strictly inside every line of the outline are first + lo .. first + hi (none when
// lo > hi), found exactly, as renderer/raster/raster's coveredRun does for a triangle.
struct RowRun {
  std::int64_t lo, hi;
};

RowRun centersInside(const Outline& outline, int y, int first, int last) {
  const std::int64_t py = y * kSubpixelScale + kSubpixelScale / 2, px = first * kSubpixelScale + kSubpixelScale / 2;
  RowRun run{0, last - first};
  for (const Corner& corner : outline) {
    const Line& line = corner.edge;
    const std::int64_t value = line.a * px + line.b * py + line.c, step = line.a * kSubpixelScale;
    // value + step i > 0 bounds the i-th pixel from below (step > 0) or above (step < 0).
    if (step > 0) {
      if (value <= 0) run.lo = std::max(run.lo, -value / step + 1);
    } else if (step < 0) {
      if (value <= 0) run.hi = -1;
      else run.hi = std::min(run.hi, (value - 1) / -step);
    } else if (value <= 0) {
      run.hi = -1;
    }
  }
  return run;
}

// A polygon's whole outline: its triangle's three edges.
Outline outlineOf(const ScreenTriangle& tri) {
  Outline outline;
  for (int k = 0; k < 3; ++k) outline.push_back({meet(insideEdge(tri, (k + 2) % 3), insideEdge(tri, k)), insideEdge(tri, k)});
  return outline;
}

// The parts of a piece inside a clip polygon's outline and outside it. Outside is not
// convex, so it comes in up to three convex pieces: outside the first edge; inside the
// first and outside the second; inside both and outside the third. No parts at all when
// the outline does not cut the piece: when no part of it is inside.
struct Split {
  std::optional<Piece> inside;
  std::vector<Piece> outside;
};

Split splitByOutline(const Piece& piece, const ScreenTriangle& clip) {
  // A piece wholly outside one edge (touching it at most) is outside the outline whole:
  // the trivial case, and the common one, tested first so that a piece merely near the
  // clip polygon is not cut along its edges' lines for nothing.
  for (int k = 0; k < 3; ++k) {
    const Line edge = insideEdge(clip, k);
    if (std::none_of(piece.outline.begin(), piece.outline.end(), [&](const Corner& corner) { return sideOf(edge, corner.point) > 0; }))
      return {};
  }
  // Otherwise it is cut edge by edge, the part outside each edge set aside.
  // BEGIN SOLUTION
  Split split;
  Outline remaining = piece.outline;
  std::vector<int> side;  // sideOf(edge, corner.point) for each corner of what remains
  side.reserve(remaining.size() + 3);
  for (int k = 0; k < 3; ++k) {
    const Line edge = insideEdge(clip, k);
    side.clear();
    for (const Corner& corner : remaining) side.push_back(sideOf(edge, corner.point));
    if (std::none_of(side.begin(), side.end(), [](int s) { return s < 0; })) continue;
    if (std::none_of(side.begin(), side.end(), [](int s) { return s > 0; })) return {};  // what is left is outside this edge
    split.outside.emplace_back(piece.polygon, clipped(remaining, side, edge, -1), piece.nearerThan);
    remaining = clipped(remaining, side, edge, +1);
  }
  split.inside.emplace(piece.polygon, std::move(remaining), piece.nearerThan);
  return split;
  // SKELETON
  // // Exercise 16: the piece meets the clip polygon's outline. Cut it by the outline's
  // // edges in turn, k = 0, 1, 2 (insideEdge(clip, k)): the part outside edge k is one
  // // outside piece, clipped(outline, side, edge, -1), and the part inside,
  // // clipped(outline, side, edge, +1), goes on to the next edge; what is inside all
  // // three is the inside piece. `side` holds sideOf(edge, corner.point) for each corner
  // // of the outline being cut. An outline wholly inside an edge needs no cut there; one
  // // wholly outside it is outside the whole outline: return no parts. Each piece keeps
  // // its polygon and nearerThan (Piece(polygon, outline, nearerThan)). How many outside
  // // pieces can there be, and when are there fewer?
  // (void)clipped, (void)piece;
  // return {};
  // END SOLUTION
}

// How a piece lies against a clip polygon it is inside of.
enum class Relation { behind, inFront, crossing };

struct Counts {
  std::int64_t clipPolygons = 0, recursions = 0, piecesClipped = 0, piecesMade = 0, hidden = 0, cutByDepth = 0, visible = 0;
  std::int64_t mostInside = 0, deepest = 0, claimedTwice = 0, noPixel = 0, cutsUndone = 0, dropped = 0;
};

class Clipper {
 public:
  // why: hsr why's pixels, or null (renderer/steps/why.hpp).
  Clipper(const ScreenGeometry& geometry, Frame& frame, Counts& counts, std::vector<VisiblePolygon>& polygons, PixelWitness* why)
      : triangles_(geometry.triangles), camera_(geometry.camera), order_(geometry.camera), frame_(frame), counts_(counts),
        polygons_(polygons), why_(why) {}

  // Textbook step 1: the preliminary sort, by each polygon's nearest depth.
  std::vector<std::uint32_t> sortedByNearestDepth() const {
    std::vector<double> nearest(triangles_.size());
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      nearest[i] = std::numeric_limits<double>::infinity();
      for (const Corner& corner : outlineOf(triangles_[i])) nearest[i] = std::min(nearest[i], keyAt(triangles_[i], approximate(corner.point)));
    }
    std::vector<std::uint32_t> order(triangles_.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) { return nearest[p] < nearest[q]; });
    return order;
  }

  // Steps 3 and 4, for the pieces inside `clip`'s outline (its own among them): remove
  // those behind it, and if any is in front of it somewhere, process the list again
  // with that one's polygon clipping. `stack`: the clip polygons this list lies inside.
  void resolveInside(std::vector<Piece> inside, std::uint32_t clip, std::vector<std::uint32_t>& stack) {
    ++counts_.clipPolygons;
    counts_.mostInside = std::max(counts_.mostInside, static_cast<std::int64_t>(inside.size()));
    std::vector<Piece> kept;
    kept.reserve(inside.size());
    bool anyInFront = false;
    for (Piece& piece : inside) {
      // The clip polygon's own piece is not judged against itself.
      const std::optional<Relation> relation = piece.polygon != clip ? std::optional(relationOf(piece, clip)) : std::nullopt;
      if (why_) [[unlikely]] witnessInside(piece, clip, relation, stack.size());
      if (relation) {
        if (relation == Relation::behind) {
          ++counts_.hidden;
          continue;
        }
        // Where the planes cross inside the piece, it is kept where it is nearer, pixel
        // by pixel; the clip polygon's pieces will be cut the same way against it when
        // its polygon clips them, by the same comparison, so each center goes to one.
        if (relation == Relation::crossing) {
          piece.nearerThan.push_back(clip);
          ++counts_.cutByDepth;
        }
        anyInFront = true;
      }
      kept.push_back(std::move(piece));
    }
    if (!anyInFront) {
      for (Piece& piece : kept) show(std::move(piece));
      return;
    }
    // Step 4: something inside is in front: its polygon clips the inside list.
    ++counts_.recursions;
    stack.push_back(clip);
    counts_.deepest = std::max(counts_.deepest, static_cast<std::int64_t>(stack.size()));
    resolveList(std::move(kept), stack);
    stack.pop_back();
  }

  // Steps 2 to 4 on a list (in the sorted order): its first polygon not already on the
  // stack clips it; the inside pieces are resolved; the outside ones go on. A polygon on
  // the stack does not clip again: the list lies inside it, and its pieces and the
  // others here have been compared with it, each way, when it clipped.
  void resolveList(std::vector<Piece> list, std::vector<std::uint32_t>& stack) {
    while (!list.empty()) {
      const auto first = std::find_if(list.begin(), list.end(), [&](const Piece& piece) {
        return std::find(stack.begin(), stack.end(), piece.polygon) == stack.end();
      });
      if (first == list.end()) {
        for (Piece& piece : list) show(std::move(piece));
        return;
      }
      const std::uint32_t clip = first->polygon;
      const Box clipBox = boxOf(outlineOf(triangles_[clip]));
      std::vector<Piece> inside, outside;
      outside.reserve(list.size());
      for (Piece& piece : list) {
        if (!clipBox.meets(piece.box)) {
          outside.push_back(std::move(piece));
          continue;
        }
        std::optional<Split> split = splitAgainst(piece, clip);
        if (!split) {  // not cut
          outside.push_back(std::move(piece));
          continue;
        }
        for (Piece& part : split->outside) outside.push_back(std::move(part));
        if (split->inside) inside.push_back(std::move(*split->inside));
      }
      resolveInside(std::move(inside), clip, stack);
      list = std::move(outside);
    }
  }

  // Step 2 for one piece: its parts inside and outside the clip polygon's outline, of
  // those that hold a pixel; nothing when the piece stays as it is. The image is its
  // pixel centers, and no center lies on a line: a part that holds none changes no pixel,
  // and neither does the clip polygon there. So such a part is dropped, inside or
  // outside; and when the part inside holds none and is a sliver, the piece is not cut at
  // all: it stays whole. A mesh's triangles that meet at a corner overlap so (their
  // outlines lie half a sub-pixel unit outside them): cut, each would leave up to three
  // slivers outside the other. Every piece in a list holds a pixel, so the clip
  // polygon's own piece, all inside, always goes to the inside list.
  std::optional<Split> splitAgainst(const Piece& piece, std::uint32_t clip) {
    Split split = splitByOutline(piece, triangles_[clip]);
    if (!split.inside) return std::nullopt;
    const bool insideHoldsAPixel = piece.polygon == clip || holdsAPixel(*split.inside);
    if (!insideHoldsAPixel && areaOf(split.inside->outline) < kSliverArea) {
      ++counts_.cutsUndone;
      return std::nullopt;
    }
    const std::size_t parts = split.outside.size() + 1;
    counts_.dropped += static_cast<std::int64_t>(std::erase_if(split.outside, [&](const Piece& part) { return !holdsAPixel(part); }));
    if (!insideHoldsAPixel) split.inside.reset(), ++counts_.dropped;
    if (parts > 1) {
      ++counts_.piecesClipped;
      counts_.piecesMade += static_cast<std::int64_t>(split.outside.size() + (split.inside ? 1 : 0));
    }
    return split;
  }

  // Whether the piece holds the center of a pixel its triangle may cover (and so of a
  // pixel of the image): the rows and columns whose centers its box holds, each row
  // solved exactly.
  bool holdsAPixel(const Piece& piece) const {
    const ScreenTriangle& tri = triangles_[piece.polygon];
    const Box& box = piece.box;
    const int top = std::max(tri.minY, static_cast<int>(std::ceil(std::max(box.y0 - 0.5, -1.0))));
    const int bottom = std::min(tri.maxY, static_cast<int>(std::floor(std::min(box.y1 - 0.5, double(tri.maxY)))));
    const int first = std::max(tri.minX, static_cast<int>(std::ceil(std::max(box.x0 - 0.5, -1.0))));
    const int last = std::min(tri.maxX, static_cast<int>(std::floor(std::min(box.x1 - 0.5, double(tri.maxX)))));
    for (int y = top; y <= bottom && first <= last; ++y) {
      const RowRun run = centersInside(piece.outline, y, first, last);
      if (run.lo <= run.hi) return true;
    }
    return false;
  }

  const ScreenTriangle& triangle(std::uint32_t polygon) const { return triangles_[polygon]; }

 private:
  double keyAt(const ScreenTriangle& tri, const dvec2& p) const { return order_.sign * tri.depthAt(p.x, p.y); }

  // A bound on the error of keyAt at a rounded corner and of DepthOrder::key at any
  // pixel center in the outline: each is within DepthOrder's rounding bound there, and
  // the corner's own rounding moves x and y by a few units in their last place, hence the
  // terms in x and y themselves.
  static double keyBound(const ScreenTriangle& tri, const dvec2& p) {
    return 2 * DepthOrder::roundingBoundAt(tri, p.x, p.y) +
           8 * std::numeric_limits<double>::epsilon() * (std::abs(tri.tdx * p.x) + std::abs(tri.tdy * p.y));
  }

  // Step 3's depth test: planes are linear, so a piece is behind the clip polygon
  // everywhere in its outline if it is behind at every corner, by more than the
  // rounding of both; and in front everywhere likewise. Otherwise they cross, or come
  // too close to call from the corners (coplanar ones among them).
  Relation relationOf(const Piece& piece, std::uint32_t clip) const {
    const ScreenTriangle& own = triangles_[piece.polygon];
    const ScreenTriangle& clipping = triangles_[clip];
    bool allBehind = true, allInFront = true;
    for (const Corner& corner : piece.outline) {
      const dvec2 p = approximate(corner.point);
      const double gap = keyAt(own, p) - keyAt(clipping, p), bound = keyBound(own, p) + keyBound(clipping, p);
      allBehind = allBehind && gap > bound;
      allInFront = allInFront && gap < -bound;
    }
    return allBehind ? Relation::behind : allInFront ? Relation::inFront : Relation::crossing;
  }

  // Whether the piece's polygon is nearer than `other` at the center of pixel (x, y):
  // the comparison every image-space algorithm makes, a tie going to the earlier polygon.
  bool nearerAt(std::uint32_t polygon, std::uint32_t other, int x, int y) const {
    return DepthOrder::inFront(order_.key(triangles_[polygon], x, y), polygon, order_.key(triangles_[other], x, y), other);
  }

  // hsr why: a piece inside clip polygon `clip`'s outline, at each pixel asked about whose
  // center it holds: how step 3 judged it against the clip polygon (`depth` clip polygons
  // deep in step 4's recursion).
  void witnessInside(const Piece& piece, std::uint32_t clip, std::optional<Relation> relation, std::size_t depth) const {
    const ScreenTriangle& tri = triangles_[piece.polygon];
    why_->forEachPixel([&](int x, int y, std::vector<PixelEvent>& history) {
      if (!holdsCenter(piece.outline, x, y)) return;
      const std::string outcome =
          !relation                         ? "the clip polygon's own piece, inside its outline"
          : relation == Relation::behind    ? "removed: inside the clip polygon's outline and behind it at every corner"
          : relation == Relation::crossing  ? "kept where nearer: its plane crosses the clip polygon's (or comes within rounding)"
                                            : "in front of the clip polygon at every corner: it clips the inside list in turn";
      history.push_back({tri.triangle + 1, outcome,
                         "clip polygon: triangle " + std::to_string(triangles_[clip].triangle) + "; a piece of " +
                             std::to_string(piece.outline.size()) + " corners" +
                             (depth ? ", " + std::to_string(depth) + (depth == 1 ? " recursion" : " recursions") + " deep" : ""),
                         DepthOrder::distanceAt(camera_, tri, x, y), false, {}});
    });
  }

  // hsr why: a visible piece scan-converted, at each pixel asked about whose center it
  // holds: drawn there, or not where a polygon it passes through is nearer.
  void witnessShown(const Piece& piece, int top, int bottom) const {
    const ScreenTriangle& tri = triangles_[piece.polygon];
    why_->forEachPixel([&](int x, int y, std::vector<PixelEvent>& history) {
      if (y < top || y > bottom || x < tri.minX || x > tri.maxX || !holdsCenter(piece.outline, x, y)) return;
      const auto nearer = std::find_if(piece.nearerThan.begin(), piece.nearerThan.end(),
                                       [&](std::uint32_t other) { return !nearerAt(piece.polygon, other, x, y); });
      const bool drawn = nearer == piece.nearerThan.end();
      std::string through;  // the polygons it passes through, where it is drawn only if nearer
      for (const std::uint32_t other : piece.nearerThan) through += (through.empty() ? "" : ", ") + std::to_string(triangles_[other].triangle);
      history.push_back({tri.triangle + 1, drawn ? "drawn: a visible piece, scan-converted" : "not drawn here: a polygon it passes through is nearer",
                         drawn ? "a piece of " + std::to_string(piece.outline.size()) + " corners" +
                                     (through.empty() ? "" : ", nearer here than the triangles it passes through (" + through + ")")
                               : "triangle " + std::to_string(triangles_[*nearer].triangle) + " is nearer at this pixel's center",
                         DepthOrder::distanceAt(camera_, tri, x, y), drawn, {}});
    });
  }

  // Step 5: a visible piece is scan-converted: on each row, the centers strictly inside
  // every line of its outline (solved exactly, as renderer/raster/raster's coveredRun does for a
  // triangle), and of those the ones where it is nearer than each polygon it passes through.
  void show(Piece piece) {
    ++counts_.visible;
    const ScreenTriangle& tri = triangles_[piece.polygon];
    const Box& box = piece.box;
    std::int64_t pixels = 0;
    const int top = std::max(tri.minY, static_cast<int>(std::floor(box.y0))), bottom = std::min(tri.maxY, static_cast<int>(std::ceil(box.y1)));
    if (why_) [[unlikely]] witnessShown(piece, top, bottom);
    for (int y = top; y <= bottom; ++y) {
      const RowRun run = centersInside(piece.outline, y, tri.minX, tri.maxX);
      for (std::int64_t i = run.lo; i <= run.hi; ++i) {
        const int x = tri.minX + static_cast<int>(i);
        if (!std::all_of(piece.nearerThan.begin(), piece.nearerThan.end(),
                         [&](std::uint32_t other) { return nearerAt(piece.polygon, other, x, y); }))
          continue;
        const std::size_t pixel = std::size_t(y) * std::size_t(frame_.width) + std::size_t(x);
        ++pixels;
        counts_.claimedTwice += frame_.ids[pixel] != conventions::kBackgroundId;
        frame_.ids[pixel] = tri.triangle + 1;
        frame_.depth[pixel] = DepthOrder::distanceAt(camera_, tri, x, y);
      }
    }
    // The polygons drawn are those that show in the image. A piece with no pixel center
    // is left out: a sub-pixel piece the convex cutting made, or one that only touches a
    // polygon it lies behind (a back face at the silhouette), kept where nearer, nowhere.
    if (pixels == 0) {
      ++counts_.noPixel;
      return;
    }
    VisiblePolygon drawn{tri.triangle, {}};
    for (const Corner& corner : piece.outline) drawn.corners.push_back(approximate(corner.point));
    // For the drawing, a piece kept only where it is nearer than another polygon is cut
    // where their planes cross, in double precision (its pixels were decided exactly).
    for (const std::uint32_t other : piece.nearerThan)
      drawn.corners = clippedWhereNegative(drawn.corners, [&](const dvec2& p) { return keyAt(tri, p) - keyAt(triangles_[other], p); });
    polygons_.push_back(std::move(drawn));
  }

  const ScreenTriangles& triangles_;
  const CameraTransform& camera_;
  DepthOrder order_;
  Frame& frame_;
  Counts& counts_;
  std::vector<VisiblePolygon>& polygons_;
  PixelWitness* why_;
};

// The whole list, held in tiles: a clip polygon meets only the pieces in the tiles its
// outline touches, where a plain list would have it look at every piece of the scene.
// Pieces taken out leave their slot free for the next one made, so the memory held is
// the pieces in the list, not every piece the clipping ever made; a tile names a piece
// by slot and the slot's generation, so that it forgets a piece taken out.
class TiledList {
 public:
  static constexpr int kTileSide = 8;

  // rankOf: each polygon's place in the sorted list.
  TiledList(int width, int height, std::vector<std::size_t> rankOf)
      : columns_((width + kTileSide - 1) / kTileSide), rows_((height + kTileSide - 1) / kTileSide),
        tiles_(std::size_t(columns_) * std::size_t(rows_)), rankOf_(std::move(rankOf)), remaining_(rankOf_.size(), 0) {}

  void add(Piece piece) {
    std::uint32_t slot;
    if (freeSlots_.empty()) {
      slot = static_cast<std::uint32_t>(slots_.size());
      slots_.emplace_back(std::move(piece));
      generation_.push_back(0);
      seen_.push_back(0);
    } else {
      slot = freeSlots_.back();
      freeSlots_.pop_back();
      slots_[slot].emplace(std::move(piece));
    }
    forEachTile(slots_[slot]->box, [&](std::vector<Entry>& tile) { tile.push_back({slot, generation_[slot]}); });
    ++remaining_[slots_[slot]->polygon];
  }

  bool holdsPiecesOf(std::uint32_t polygon) const { return remaining_[polygon] > 0; }

  // The pieces whose boxes meet the box, by slot, in the list's order: by their
  // polygons' ranks (and, between pieces of one polygon, by slot).
  std::vector<std::uint32_t> meeting(const Box& box) {
    ++visit_;
    std::vector<std::uint32_t> found;
    forEachTile(box, [&](std::vector<Entry>& tile) {
      std::erase_if(tile, [&](const Entry& entry) { return generation_[entry.slot] != entry.generation; });
      for (const Entry& entry : tile)
        if (seen_[entry.slot] != visit_ && box.meets(slots_[entry.slot]->box)) seen_[entry.slot] = visit_, found.push_back(entry.slot);
    });
    std::sort(found.begin(), found.end(), [&](std::uint32_t p, std::uint32_t q) {
      return std::pair(rankOf_[slots_[p]->polygon], p) < std::pair(rankOf_[slots_[q]->polygon], q);
    });
    return found;
  }

  const Piece& operator[](std::uint32_t slot) const { return *slots_[slot]; }

  // Takes the piece out of the list; its slot is free for the next piece added.
  void remove(std::uint32_t slot) {
    --remaining_[slots_[slot]->polygon];
    slots_[slot].reset();
    ++generation_[slot];
    freeSlots_.push_back(slot);
  }

 private:
  template <typename Visit>
  void forEachTile(const Box& box, Visit&& visit) {
    const auto column = [&](double x) { return std::clamp(static_cast<int>(std::floor(x / kTileSide)), 0, columns_ - 1); };
    const auto row = [&](double y) { return std::clamp(static_cast<int>(std::floor(y / kTileSide)), 0, rows_ - 1); };
    for (int r = row(box.y0); r <= row(box.y1); ++r)
      for (int c = column(box.x0); c <= column(box.x1); ++c) visit(tiles_[std::size_t(r) * std::size_t(columns_) + std::size_t(c)]);
  }

  struct Entry {
    std::uint32_t slot, generation;
  };
  int columns_, rows_;
  std::vector<std::vector<Entry>> tiles_;
  std::vector<std::size_t> rankOf_;
  std::vector<std::optional<Piece>> slots_;
  std::vector<std::uint32_t> freeSlots_;
  std::vector<std::uint32_t> generation_;  // by slot: how many pieces it has held and let go
  std::vector<std::uint64_t> seen_;
  std::uint64_t visit_ = 0;
  std::vector<std::int64_t> remaining_;  // pieces in the list, by polygon
};

// A step's picture: the pixels decided so far, every visible polygon so far outlined in
// grey, those from `newFrom` on in blue, and the clip polygon in red.
Image clippingPicture(const VisibilityRequest& request, const Frame& frame, const std::vector<VisiblePolygon>& polygons,
                      std::size_t newFrom, const std::vector<dvec2>& clip) {
  Image picture = surfacePicture(request.scene, request.view, frame.ids, frame.width, frame.height);
  const auto outline = [&](const std::vector<dvec2>& corners, Rgb colour, double width) {
    for (std::size_t k = 0; k < corners.size(); ++k) drawSegment(picture, corners[k], corners[(k + 1) % corners.size()], colour, width);
  };
  for (std::size_t p = 0; p < polygons.size(); ++p)
    outline(polygons[p].corners, p < newFrom ? Rgb{90, 90, 90} : kSecondHighlight, p < newFrom ? 0.6 : 1.2);
  if (clip.empty()) {
    drawLegend(picture, {{Rgb{90, 90, 90}, "visible polygons"}});
  } else {
    outline(clip, kHighlight, 2.0);
    drawLegend(picture, {{kHighlight, "clip polygon"}, {kSecondHighlight, "visible pieces it left"}, {Rgb{90, 90, 90}, "visible before"}});
  }
  return picture;
}

}  // namespace

void visibility(const VisibilityRequest& request, const Knobs&, Visibility& visibility) {
  const ScreenGeometry geometry =
      buildScreenTriangles(request.scene, request.view, {.submitted = request.triangles}, request.threads, request.stats);
  PhaseTimer timer(request.stats, "clipping");
  Frame& frame = visibility.frame;
  std::fill(frame.ids.begin(), frame.ids.end(), conventions::kBackgroundId);
  std::fill(frame.depth.begin(), frame.depth.end(), std::numeric_limits<float>::infinity());
  visibility.polygons.clear();
  Counts counts;
  Clipper clipper(geometry, frame, counts, visibility.polygons, request.why);

  // Step 1: the list, sorted by nearest depth; each polygon whole, one piece.
  const std::vector<std::uint32_t> sorted = clipper.sortedByNearestDepth();
  std::vector<std::size_t> rankOf(sorted.size());
  for (std::size_t rank = 0; rank < sorted.size(); ++rank) rankOf[sorted[rank]] = rank;
  TiledList list(frame.width, frame.height, std::move(rankOf));
  for (const std::uint32_t polygon : sorted) {
    Piece whole(polygon, outlineOf(clipper.triangle(polygon)), {});
    if (clipper.holdsAPixel(whole)) list.add(std::move(whole));
    else ++counts.dropped;
  }

  // Step 2, down the list: the nearest polygon still in it clips every piece its outline
  // meets; the parts outside go back into the list in their polygon's place.
  std::vector<std::uint32_t> stack;
  std::size_t clipsSoFar = 0;
  for (const std::uint32_t clip : sorted) {
    if (!list.holdsPiecesOf(clip)) continue;
    std::vector<Piece> inside;
    const std::size_t polygonsShown = visibility.polygons.size();
    const std::int64_t hiddenBefore = counts.hidden, recursionsBefore = counts.recursions;
    for (const std::uint32_t slot : list.meeting(boxOf(outlineOf(clipper.triangle(clip))))) {
      std::optional<Split> split = clipper.splitAgainst(list[slot], clip);
      if (!split) continue;  // not cut: it stays in its place
      list.remove(slot);
      for (Piece& part : split->outside) list.add(std::move(part));
      if (split->inside) inside.push_back(std::move(*split->inside));
    }
    clipper.resolveInside(std::move(inside), clip, stack);
    if (request.steps && request.steps->due(clipsSoFar++)) {
      std::vector<dvec2> clipCorners;
      for (const Corner& corner : outlineOf(clipper.triangle(clip))) clipCorners.push_back(approximate(corner.point));
      request.steps->record("clip polygon " + std::to_string(clipsSoFar) + " of the sorted list (triangle " +
                                std::to_string(clipper.triangle(clip).triangle) + "): " + std::to_string(counts.hidden - hiddenBefore) +
                                " pieces inside it hidden, " + std::to_string(counts.recursions - recursionsBefore) + " recursions, " +
                                std::to_string(visibility.polygons.size() - polygonsShown) + " visible pieces left inside it (blue)",
                            clippingPicture(request, frame, visibility.polygons, polygonsShown, clipCorners));
    }
  }
  if (request.steps)
    request.steps->record("every clip polygon done: " + std::to_string(visibility.polygons.size()) + " visible polygons, outlined",
                          clippingPicture(request, frame, visibility.polygons, visibility.polygons.size(), {}));

  request.stats.add("clip polygons", counts.clipPolygons);
  request.stats.add("recursions", counts.recursions);
  request.stats.add("pieces clipped", counts.piecesClipped);
  request.stats.add("pieces made", counts.piecesMade);
  request.stats.add("pieces hidden", counts.hidden);
  request.stats.add("pieces cut by depth", counts.cutByDepth);
  request.stats.add("cuts undone", counts.cutsUndone);
  request.stats.add("pieces with no pixel dropped", counts.dropped);
  request.stats.add("visible pieces", counts.visible);
  request.stats.add("visible pieces with no pixel", counts.noPixel);
  request.stats.add("most pieces in an inside list", counts.mostInside);
  request.stats.add("deepest recursion", counts.deepest);
  request.stats.add("pixels claimed twice", counts.claimedTwice);
}

namespace {
std::string refusal(const PreparedScene& scene, const Knobs& knobs) {
  if (static_cast<double>(scene.triangleCount()) <= knobs.budget) return "";
  char text[256];
  std::snprintf(text, sizeof text, "weiler_atherton clips %zu triangles against each other, more than --knob budget=%.6g; raise it",
                scene.triangleCount(), knobs.budget);
  return text;
}
}  // namespace

AlgorithmEntry entry() {
  AlgorithmEntry entry;
  entry.name = "weiler_atherton";
  entry.summary = "polygon clipping in object space (Weiler-Atherton 1977): the nearest polygon clips the rest, hidden pieces removed";
  setKnobs(entry, knobTable());
  entry.keyCounters = {"clip polygons", "pieces made", "visible pieces"};
  entry.takesTriangleSubsets = true;
  entry.drawsPolygons = true;
  entry.answersWhy = true;
  setRefusal(entry, refusal);
  setVisibility(entry, visibility);
  return entry;
}

}  // namespace hsr::weiler_atherton
