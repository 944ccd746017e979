// Warnock's area subdivision, level by level: every window of one size is examined,
// the simple ones are drawn, the rest are cut into four for the next level.
#include "algorithms/warnock/warnock.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <optional>

#include "renderer/raster/plane_depth.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr::warnock {
namespace {

// Pixels [x0, x1) x [y0, y1) of the image.
struct Window {
  int x0, y0, x1, y1;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

// The four relations of a polygon to a window (header). The rules below treat
// contained and intersecting alike; they are told apart for the counters, which show
// how the mix changes as windows shrink.
enum class Relation { disjoint, contained, intersecting, surrounding };
constexpr std::array<const char*, 4> kRelationCounters = {"polygons disjoint", "polygons contained", "polygons intersecting",
                                                          "polygons surrounding"};

// How a window was decided, or that it was not.
enum class Rule { empty, onePolygon, surrounded, smallest, subdivided };
constexpr std::array<const char*, 5> kRuleCounters = {"windows empty", "windows with one polygon", "windows surrounded",
                                                      "windows at smallest size", "windows subdivided"};

// A triangle's edge function k at the center of pixel (x, y): non-negative inside, the
// top-left rule folded in (renderer/raster/raster.hpp). Exact integers.
std::int64_t edgeAtCenter(const ScreenTriangle& tri, int k, int x, int y) {
  using conventions::kSubpixelScale;
  return tri.edgeA[k] * (x * kSubpixelScale + kSubpixelScale / 2) + tri.edgeB[k] * (y * kSubpixelScale + kSubpixelScale / 2) +
         tri.edgeC[k];
}

bool coversCenter(const ScreenTriangle& tri, int x, int y) {
  return edgeAtCenter(tri, 0, x, y) >= 0 && edgeAtCenter(tri, 1, x, y) >= 0 && edgeAtCenter(tri, 2, x, y) >= 0;
}

// The relation, decided on the pixel centers the window holds. An edge function is
// linear, so its values at the window's four corner centers bound it over every center
// between them: all four outside one edge, and no center of the window is inside; all
// four inside every edge, and every center is (a triangle is convex). Anything else
// meets the window, or may: a smaller window will tell.
Relation relationTo(const ScreenTriangle& tri, const Window& window) {
  // BEGIN SOLUTION
  if (tri.maxX < window.x0 || tri.minX >= window.x1 || tri.maxY < window.y0 || tri.minY >= window.y1) return Relation::disjoint;
  const int xs[2] = {window.x0, window.x1 - 1}, ys[2] = {window.y0, window.y1 - 1};
  bool surrounds = true;
  for (int k = 0; k < 3; ++k) {
    int inside = 0;
    for (const int x : xs)
      for (const int y : ys) inside += edgeAtCenter(tri, k, x, y) >= 0;
    if (inside == 0) return Relation::disjoint;
    surrounds = surrounds && inside == 4;
  }
  if (surrounds) return Relation::surrounding;
  const bool insideWindow = tri.minX >= window.x0 && tri.maxX < window.x1 && tri.minY >= window.y0 && tri.maxY < window.y1;
  return insideWindow ? Relation::contained : Relation::intersecting;
  // SKELETON
  // // Exercise 14: classify the triangle against the window (pixels window.x0 to x1 - 1,
  // // window.y0 to y1 - 1). Its pixel box (tri.minX to tri.maxX, tri.minY to tri.maxY)
  // // apart from the window's: disjoint. Then edgeAtCenter(tri, k, x, y) >= 0 says the
  // // center of pixel (x, y) is inside edge k: at the window's four corner centers, all
  // // outside one edge means disjoint, all inside every edge means surrounding. Otherwise
  // // contained (the pixel box lies in the window) or intersecting. Why do the corners
  // // suffice?
  // (void)tri, (void)window;
  // return Relation::disjoint;
  // END SOLUTION
}

// The range of a triangle's plane over a window's pixel centers, nearest to farthest
// (renderer/raster/plane_depth.hpp: smaller is nearer). The plane is affine, so its extremes lie
// at the corner centers. Each value computed at a corner is within a rounding bound of
// the exact one, and so is each value computed at any center inside (the bound is
// largest at a corner), so the range widened by twice the largest corner bound holds
// every value computed at any center of the window.
struct DepthRange {
  double nearest, farthest;
};
DepthRange depthRange(const ScreenTriangle& tri, const Window& window, const DepthOrder& order) {
  DepthRange range{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  double bound = 0;
  for (const int x : {window.x0, window.x1 - 1})
    for (const int y : {window.y0, window.y1 - 1}) {
      const double key = order.key(tri, x, y);
      range.nearest = std::min(range.nearest, key);
      range.farthest = std::max(range.farthest, key);
      bound = std::max(bound, DepthOrder::roundingBound(tri, x, y));
    }
  return {range.nearest - 2 * bound, range.farthest + 2 * bound};
}

// One level's windows still to examine, each with the polygons that met its parent
// (an index into `lists`): a polygon disjoint from a window is disjoint from its parts.
struct Level {
  std::vector<Window> windows;
  std::vector<std::uint32_t> listOf;
  std::vector<std::vector<std::uint32_t>> lists;
};

// What examining one window found: its rule, and for a subdivided window the polygons
// that meet it, for its four parts.
struct Examined {
  Rule rule;
  std::vector<std::uint32_t> meeting;
};

// A worker's counts, on cache lines of their own: two threads counting polygon-window
// tests on one line would wait for each other at every test.
struct alignas(64) Counts {
  std::array<std::int64_t, 5> windows{};    // by Rule
  std::array<std::int64_t, 4> relations{};  // by Relation
  Counts& operator+=(const Counts& other) {
    for (std::size_t k = 0; k < windows.size(); ++k) windows[k] += other.windows[k];
    for (std::size_t k = 0; k < relations.size(); ++k) relations[k] += other.relations[k];
    return *this;
  }
};

class Subdivision {
 public:
  Subdivision(const ScreenGeometry& geometry, const Knobs& knobs, Frame& frame, PixelWitness* why)
      : triangles_(geometry.triangles), camera_(geometry.camera), knobs_(knobs), frame_(frame),
        order_(geometry.camera), why_(why) {}

  // Examines a window: step 1 classifies every polygon that met its parent, step 2
  // applies the rules in order, drawing the window when one decides it.
  Examined examine(const Window& window, std::span<const std::uint32_t> candidates, Counts& counts) const {
    // Step 1: the relation of each polygon to the window; the disjoint ones are dropped.
    Examined examined{Rule::subdivided, {}};
    examined.meeting.reserve(candidates.size());  // one allocation, where growing by doubling took several
    const std::array<std::int64_t, 4> relationsBefore = why_ ? counts.relations : std::array<std::int64_t, 4>{};
    std::optional<std::uint32_t> nearestSurrounding;
    double nearestSurroundingFarthest = std::numeric_limits<double>::infinity();
    for (const std::uint32_t i : candidates) {
      const Relation relation = relationTo(triangles_[i], window);
      ++counts.relations[std::size_t(relation)];
      if (relation == Relation::disjoint) continue;
      examined.meeting.push_back(i);
      if (relation != Relation::surrounding) continue;
      const double farthest = depthRange(triangles_[i], window, order_).farthest;
      if (farthest < nearestSurroundingFarthest) nearestSurrounding = i, nearestSurroundingFarthest = farthest;
    }
    const auto& meeting = examined.meeting;

    // Step 2, rule 1: nothing meets the window.
    if (meeting.empty()) {
      fillWith(window, std::nullopt);
      examined.rule = Rule::empty;
    }
    // Rule 2: one polygon meets it and does not cover it: scan-convert it within the window.
    else if (meeting.size() == 1 && !nearestSurrounding) {
      fillWith(window, std::nullopt);
      drawWithin(window, meeting[0]);
      examined.rule = Rule::onePolygon;
    }
    // Rule 3: a surrounding polygon is nearer than every other polygon at every center:
    // its farthest point in the window is nearer than each other's nearest. Strictly:
    // a tie is left to smaller windows, where the earlier polygon wins it.
    else if (nearestSurrounding && std::all_of(meeting.begin(), meeting.end(), [&](std::uint32_t i) {
               return i == *nearestSurrounding || nearestSurroundingFarthest < depthRange(triangles_[i], window, order_).nearest;
             })) {
      fillWith(window, *nearestSurrounding);
      examined.rule = Rule::surrounded;
    }
    // The stop: a window no larger than the knob is decided by its central pixel.
    else if (window.width() <= knobs_.smallestWindow && window.height() <= knobs_.smallestWindow) {
      fillWith(window, nearestAtCenter(window, meeting));
      examined.rule = Rule::smallest;
    }
    // Otherwise subdivide (the caller cuts the window; the polygons meeting it go along).
    ++counts.windows[std::size_t(examined.rule)];
    if (why_) {
      std::array<std::int64_t, 4> related{};
      for (std::size_t k = 0; k < related.size(); ++k) related[k] = counts.relations[k] - relationsBefore[k];
      witnessWindow(window, examined, related, nearestSurrounding);
    }
    if (examined.rule != Rule::subdivided) std::vector<std::uint32_t>().swap(examined.meeting);  // its memory too: reserved at the parent's size
    return examined;
  }

 private:
  // The central pixel of a window, which decides a window at the smallest size.
  static std::pair<int, int> centralPixel(const Window& window) {
    return {window.x0 + (window.width() - 1) / 2, window.y0 + (window.height() - 1) / 2};
  }

  // The polygon nearest at the center of the window's central pixel, of those covering
  // it; a tie goes to the earlier polygon, as in the z-buffer.
  std::optional<std::uint32_t> nearestAtCenter(const Window& window, std::span<const std::uint32_t> meeting) const {
    const auto [x, y] = centralPixel(window);
    std::optional<std::uint32_t> nearest;
    double nearestKey = std::numeric_limits<double>::infinity();
    for (const std::uint32_t i : meeting) {
      if (!coversCenter(triangles_[i], x, y)) continue;
      const double key = order_.key(triangles_[i], x, y);
      if (key < nearestKey) nearest = i, nearestKey = key;
    }
    return nearest;
  }

  void setPixel(int x, int y, const std::optional<std::uint32_t>& triangle) const {
    const std::size_t pixel = std::size_t(y) * std::size_t(frame_.width) + std::size_t(x);
    if (!triangle) {
      frame_.ids[pixel] = conventions::kBackgroundId;
      frame_.depth[pixel] = std::numeric_limits<float>::infinity();
      return;
    }
    const ScreenTriangle& tri = triangles_[*triangle];
    frame_.ids[pixel] = tri.triangle + 1;
    frame_.depth[pixel] = DepthOrder::distanceAt(camera_, tri, x, y);
  }

  // Every pixel of the window shows the polygon (its plane's depth at each center), or
  // the background.
  void fillWith(const Window& window, const std::optional<std::uint32_t>& triangle) const {
    for (int y = window.y0; y < window.y1; ++y)
      for (int x = window.x0; x < window.x1; ++x) setPixel(x, y, triangle);
  }

  // Scan conversion of one polygon, clipped to the window.
  void drawWithin(const Window& window, std::uint32_t triangle) const {
    const ScreenTriangle& tri = triangles_[triangle];
    const int x0 = std::max(window.x0, tri.minX), x1 = std::min(window.x1, tri.maxX + 1);
    for (int y = std::max(window.y0, tri.minY); y < std::min(window.y1, tri.maxY + 1); ++y)
      rasterizeSpan(tri, y, x0, x1, [&](int x) { setPixel(x, y, triangle); });
  }

  // hsr why: a window examined that holds a pixel asked about, and the rule that decided
  // it or that none did; for a decided window, what each polygon meeting it came to at
  // the pixel. The window is examined once at each level, and only it draws its pixels,
  // so a pixel's history is written by one thread at a time.
  void witnessWindow(const Window& window, const Examined& examined, const std::array<std::int64_t, 4>& related,
                     std::optional<std::uint32_t> surrounding) const {
    for (std::size_t asked = 0; asked < why_->count(); ++asked) {
      const auto [x, y] = why_->pixel(asked);
      if (x < window.x0 || x >= window.x1 || y < window.y0 || y >= window.y1) continue;
      std::vector<PixelEvent>& history = *why_->at(x, y);
      const std::int64_t meeting = related[1] + related[2] + related[3];
      PixelEvent event;
      event.subject = "window " + std::to_string(window.width()) + " x " + std::to_string(window.height()) + " at (" +
                      std::to_string(window.x0) + ", " + std::to_string(window.y0) + ")";
      event.detail = std::to_string(meeting) + (meeting == 1 ? " polygon meets it" : " polygons meet it") + " (" +
                     std::to_string(related[3]) + " surrounding, " + std::to_string(related[2]) + " intersecting, " +
                     std::to_string(related[1]) + " contained)";
      switch (examined.rule) {
        case Rule::empty:
          event.outcome = "rule 1, empty: no polygon meets it, so the window shows the background";
          break;
        case Rule::onePolygon:
          event.outcome = "rule 2, one polygon: it is scan-converted within the window";
          break;
        case Rule::surrounded:
          event.outcome = "rule 3, surrounded: the surrounding polygon is nearer than every other over the whole window";
          break;
        case Rule::smallest: {
          const auto [cx, cy] = centralPixel(window);
          event.outcome = "the smallest window: decided by the polygon nearest at its central pixel (" + std::to_string(cx) + ", " +
                          std::to_string(cy) + ") (--knob smallest-window=" + std::to_string(knobs_.smallestWindow) + ")";
          break;
        }
        case Rule::subdivided:
          event.outcome = "subdivided into four: no rule decides it";
          event.detail += surrounding ? "; the nearest surrounding polygon is not nearer than every other over all of it"
                                      : "; more than one meets it and none surrounds it";
          break;
      }
      history.push_back(std::move(event));
      if (examined.rule != Rule::subdivided) witnessDecision(window, examined, surrounding, x, y, history);
    }
  }

  // What each polygon meeting a decided window came to at pixel (x, y): the one the rule
  // gave the pixel, and why each other one is not shown there. Which one is shown follows
  // from the rule, as the drawing above decided it (the property test checks it against
  // the image); a distance only where the polygon covers the pixel's center.
  void witnessDecision(const Window& window, const Examined& examined, std::optional<std::uint32_t> surrounding, int x, int y,
                       std::vector<PixelEvent>& history) const {
    const Rule rule = examined.rule;
    const std::vector<std::uint32_t>& meeting = examined.meeting;
    const auto [cx, cy] = centralPixel(window);
    const std::optional<std::uint32_t> nearest = rule == Rule::smallest ? nearestAtCenter(window, meeting) : std::nullopt;
    for (const std::uint32_t i : meeting) {
      const ScreenTriangle& tri = triangles_[i];
      PixelEvent event;
      event.id = tri.triangle + 1;
      const bool coversPixel = coversCenter(tri, x, y);
      if (coversPixel) event.distance = DepthOrder::distanceAt(camera_, tri, x, y);
      const bool isSurrounding = surrounding.has_value() && *surrounding == i, isNearest = nearest.has_value() && *nearest == i;
      event.shown = rule == Rule::onePolygon ? coversPixel : rule == Rule::surrounded ? isSurrounding : isNearest;
      const std::string central = "(" + std::to_string(cx) + ", " + std::to_string(cy) + ")";
      if (rule == Rule::onePolygon) {
        event.outcome = event.shown ? "drawn: it covers the pixel's center" : "not drawn here: it does not cover the pixel's center";
        event.detail = "the one polygon meeting the window";
      } else if (rule == Rule::surrounded) {
        event.outcome = isSurrounding ? "fills the window: it surrounds it and is nearer than every other there"
                                         : "hidden: the surrounding polygon is nearer over the whole window";
        event.detail = isSurrounding ? "its farthest depth in the window is before every other polygon's nearest"
                                        : "its nearest depth in the window is beyond the surrounding polygon's farthest";
      } else if (!coversCenter(tri, cx, cy)) {
        event.outcome = "does not cover the window's central pixel " + central;
        event.detail = "at the smallest size only the central pixel's center is tested, for every pixel of the window";
      } else {
        event.outcome = isNearest ? "fills the window: the nearest at its central pixel " + central
                                     : "farther than another polygon at the window's central pixel " + central;
        event.detail = "its plane's distance there " + std::to_string(DepthOrder::distanceAt(camera_, tri, cx, cy));
      }
      history.push_back(std::move(event));
    }
  }

  const ScreenTriangles& triangles_;
  const CameraTransform& camera_;
  const Knobs& knobs_;
  Frame& frame_;
  DepthOrder order_;
  PixelWitness* why_;
};

// The window's four quadrants (two halves, or itself, where it is one pixel thin).
void subdivideInto(const Window& window, std::uint32_t list, Level& next) {
  const int xm = window.x0 + (window.width() + 1) / 2, ym = window.y0 + (window.height() + 1) / 2;
  for (const Window part : {Window{window.x0, window.y0, xm, ym}, Window{xm, window.y0, window.x1, ym},
                            Window{window.x0, ym, xm, window.y1}, Window{xm, ym, window.x1, window.y1}})
    if (part.width() > 0 && part.height() > 0) {
      next.windows.push_back(part);
      next.listOf.push_back(list);
    }
}

// A step's picture: the image decided so far, and beside it the same with each decided
// window outlined in its rule's colour and the windows left for the next level in red.
Image subdivisionPicture(const PreparedScene& scene, const CameraTransform& view, const Frame& frame,
                         const std::vector<std::pair<Window, Rule>>& decided, const std::vector<Window>& undecided) {
  static constexpr std::array<Rgb, 4> kRuleColours = {Rgb{150, 150, 150}, kThirdHighlight, kSecondHighlight, Rgb{40, 160, 60}};
  const Image surfaces = surfacePicture(scene, view, frame.ids, frame.width, frame.height);
  Image picture = surfaces;
  const auto outline = [&](const Window& w, Rgb colour) {
    const dvec2 a(w.x0, w.y0), b(w.x1, w.y0), c(w.x1, w.y1), d(w.x0, w.y1);
    drawSegment(picture, a, b, colour, 1.0), drawSegment(picture, b, c, colour, 1.0);
    drawSegment(picture, c, d, colour, 1.0), drawSegment(picture, d, a, colour, 1.0);
  };
  for (const auto& [window, rule] : decided) outline(window, kRuleColours[std::size_t(rule)]);
  for (const Window& window : undecided) outline(window, kHighlight);
  drawLegend(picture, {{kRuleColours[0], "empty"}, {kRuleColours[1], "one polygon"}, {kRuleColours[2], "surrounded"},
                       {kRuleColours[3], "smallest size"}, {kHighlight, "to subdivide"}});
  return besideEachOther({surfaces, picture});
}

// A window whose subdivision goes on by itself, with the polygons that met its parent.
struct HandedOff {
  Window window;
  std::vector<std::uint32_t> polygons;
};

// Windows at most this many pixels on a side are handed off by the levels over the
// whole image and subdivided each by itself, on one thread: the same windows and the
// same counts, but a level's lists never hold more than one such window's share, where
// a whole image of windows at one pixel (coplanar faces over all of a 16384-pixel-square
// image) would take gigabytes.
constexpr int kHandOffSide = 64;

// Examines `level` and the levels below it until every window is decided, adding to
// `total`. With `handedOff`, windows no larger than kHandOffSide are put there instead of
// being examined; with `request.steps`, each level is recorded.
void subdivideLevels(const Subdivision& subdivision, Level level, const VisibilityRequest& request, int threads, Counts& total,
                     std::vector<HandedOff>* handedOff, const Frame& frame) {
  std::vector<std::pair<Window, Rule>> decided;  // kept for the steps' pictures only
  for (int levelNumber = 0; !level.windows.empty(); ++levelNumber) {
    // Each window of the level is examined on its own (any thread; it draws only its
    // own pixels), then the subdivided ones are cut, in the level's order, so the next
    // level is the same for any thread count.
    std::vector<Examined> examined(level.windows.size());
    std::vector<Counts> counts(static_cast<std::size_t>(resolveThreadCount(threads)));
    parallelFor(level.windows.size(), threads, [&](std::size_t w, int worker) {
      examined[w] = subdivision.examine(level.windows[w], level.lists[level.listOf[w]], counts[std::size_t(worker)]);
    });
    Counts atThisLevel;
    for (const Counts& c : counts) atThisLevel += c;
    total += atThisLevel;

    Level next;
    for (std::size_t w = 0; w < level.windows.size(); ++w) {
      if (examined[w].rule != Rule::subdivided) {
        if (request.steps) decided.emplace_back(level.windows[w], examined[w].rule);
        continue;
      }
      const std::size_t firstPart = next.windows.size();
      subdivideInto(level.windows[w], std::uint32_t(next.lists.size()), next);
      if (handedOff && level.windows[w].width() <= 2 * kHandOffSide && level.windows[w].height() <= 2 * kHandOffSide) {
        for (std::size_t part = firstPart; part < next.windows.size(); ++part) handedOff->push_back({next.windows[part], examined[w].meeting});
        next.windows.resize(firstPart);
        next.listOf.resize(firstPart);
        continue;
      }
      next.lists.push_back(std::move(examined[w].meeting));
    }
    if (request.steps) {
      int widest = 0, highest = 0;
      for (const Window& window : level.windows) widest = std::max(widest, window.width()), highest = std::max(highest, window.height());
      request.steps->record(
          "level " + std::to_string(levelNumber) + ", windows up to " + std::to_string(widest) + " x " + std::to_string(highest) + " px: " + std::to_string(atThisLevel.windows[0]) + " empty, " +
              std::to_string(atThisLevel.windows[1]) + " with one polygon, " + std::to_string(atThisLevel.windows[2]) +
              " surrounded, " + std::to_string(atThisLevel.windows[3]) + " at the smallest size, " +
              std::to_string(atThisLevel.windows[4]) + " subdivided",
          subdivisionPicture(request.scene, request.view, frame, decided, next.windows));
    }
    level = std::move(next);
  }
}

// A level of one window and its polygons.
Level levelOf(const Window& window, std::vector<std::uint32_t> polygons) {
  Level level;
  level.windows.push_back(window);
  level.listOf.push_back(0);
  level.lists.push_back(std::move(polygons));
  return level;
}

}  // namespace

void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility) {
  const ScreenGeometry geometry =
      buildScreenTriangles(request.scene, request.view, {.submitted = request.triangles}, request.threads, request.stats);
  PhaseTimer timer(request.stats, "subdivision");
  Frame& frame = visibility.frame;
  const Subdivision subdivision(geometry, knobs, frame, request.why);

  // The first window is the whole image, and every polygon may meet it. Level by level
  // over the whole image while windows are large; a recording watches every level so.
  std::vector<std::uint32_t> everyPolygon(geometry.triangles.size());
  std::iota(everyPolygon.begin(), everyPolygon.end(), 0u);
  Counts total;
  std::vector<HandedOff> handedOff;
  subdivideLevels(subdivision, levelOf({0, 0, frame.width, frame.height}, std::move(everyPolygon)), request, request.threads, total,
                  request.steps ? nullptr : &handedOff, frame);
  // Then each window handed off, by itself, on one thread.
  std::vector<Counts> counts(static_cast<std::size_t>(resolveThreadCount(request.threads)));
  parallelFor(handedOff.size(), request.threads, [&](std::size_t h, int worker) {
    subdivideLevels(subdivision, levelOf(handedOff[h].window, std::move(handedOff[h].polygons)), request, 1, counts[std::size_t(worker)],
                    nullptr, frame);
  });
  for (const Counts& c : counts) total += c;

  std::int64_t examinedWindows = 0, tests = 0;
  for (std::size_t k = 0; k < total.windows.size(); ++k) {
    request.stats.add(kRuleCounters[k], total.windows[k]);
    examinedWindows += total.windows[k];
  }
  for (std::size_t k = 0; k < total.relations.size(); ++k) {
    request.stats.add(kRelationCounters[k], total.relations[k]);
    tests += total.relations[k];
  }
  request.stats.add("windows examined", examinedWindows);
  request.stats.add("polygon-window tests", tests);
}

AlgorithmEntry entry() {
  AlgorithmEntry entry;
  entry.name = "warnock";
  entry.summary = "area subdivision (Warnock 1969): windows drawn when simple, else cut in four";
  setKnobs(entry, knobTable());
  entry.keyCounters = {"windows examined", "windows subdivided", "polygon-window tests"};
  entry.studyConfigurations = {{}, {{"smallest-window", "4"}}, {{"smallest-window", "16"}}};
  entry.takesTriangleSubsets = true;
  entry.answersWhy = true;
  entry.whyDecisions = {"rule 1, empty", "rule 2, one polygon", "rule 3, surrounded", "the smallest window", "subdivided into four"};
  setVisibility(entry, visibility);
  return entry;
}

}  // namespace hsr::warnock
