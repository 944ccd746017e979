#include "grading/judge.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>

#include "renderer/raster/depth.hpp"
#include "renderer/reference/agreement.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::grading {
namespace {

constexpr std::array<CauseText, kCauses> kCauseTexts = {{
    {"nothing drawn",
     "every pixel is background: is the depth buffer cleared to the far end (the largest value the test can "
     "beat), and does a fragment pass when it is nearer than the stored depth?"},
    {"crack on a shared edge (fill rule)",
     "a pixel center exactly on an edge two triangles share belongs to exactly one of them: the top-left rule "
     "(conventions.hpp). A strict test on every edge leaves such centers to neither"},
    {"shared edge given to the wrong triangle (fill rule)",
     "a center on an edge belongs to the triangle for which that edge is a top or a left edge; testing >= 0 on "
     "every edge gives it to both, and the depth test then keeps whichever came first"},
    {"a tie kept by the later triangle",
     "two triangles exactly as near at a center: the one drawn first keeps it (conventions.hpp), so the depth "
     "test is strictly nearer, not nearer-or-equal"},
    {"near-plane clipping",
     "a triangle that crosses the near plane must be clipped there (d >= near) before it is projected: a corner "
     "behind the eye projects through w < 0 to the wrong side of the image"},
    {"a farther surface won",
     "the triangle shown is met farther along the pixel's ray than the nearest one: check the depth test's "
     "direction, the depth's sign, and that depth is interpolated (1/w under perspective) before it is compared"},
    {"coverage: the triangle does not hold the pixel center",
     "the triangle shown does not cover this pixel's center: check the edge functions and the bounding box"},
    {"sampled at a pixel corner, not its center",
     "pixel (i, j) is sampled at (i + 0.5, j + 0.5): the triangle shown covers the pixel's corner, not its center"},
    {"a triangle is missing",
     "nothing is shown where a triangle covers the center and is nearest: check the bounding box's clamping to "
     "the image, the edge functions' signs for both windings, and degenerate-looking slivers"},
    {"beyond the far plane", "the triangle shown is met beyond the far plane there: clip at d <= far too"},
    {"not a triangle of the scene", "the id is larger than the scene's triangle count (24-bit RGB, R the high byte)"},
    {"depth image: z, not the distance",
     "the depth image holds each pixel's view distance d (world units along the view axis), not the depth buffer's z "
     "in [0, 1]: decode z to d (under perspective z = f (d - n) / (d (f - n)), so d = f n / (f - z (f - n)); "
     "orthographic, d = n + z (f - n))"},
    {"depth image: not the shown triangle's distance",
     "where a pixel shows a triangle, the depth image holds that triangle's view distance at the pixel center: under "
     "perspective interpolate 1/d (or z), not d, across the screen; and a PFM's rows go from the image's bottom up"},
    {"depth image: background nearer than the far plane",
     "where a pixel shows the background, the depth image holds +infinity (or the far plane's distance): clear the "
     "depth buffer to its far end, and write the background as far away"},
}};

// Whether any corner of the triangle lies in front of the near plane (d < near).
bool crossesNearPlane(const PreparedScene& scene, std::uint32_t triangle) {
  const CameraTransform& camera = scene.camera();
  for (const std::uint32_t vertex : scene.triangles()[triangle])
    if (camera.clipFromWorld(scene.positions()[vertex]).d < camera.camera().near) return true;
  return false;
}

// Eight points 1/1024 pixel around a center: whether something covers all around it.
constexpr double kNear = 1.0 / 1024;
const std::array<dvec2, 8> kAround = {dvec2(kNear, 0),     dvec2(kNear, kNear),   dvec2(0, kNear),   dvec2(-kNear, kNear),
                                      dvec2(-kNear, 0),    dvec2(-kNear, -kNear), dvec2(0, -kNear),  dvec2(kNear, -kNear)};

// An edge function on the screen: twice the signed area of the triangle a, b, p.
double edgeFunction(const dvec2& a, const dvec2& b, const dvec2& p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

// A triangle's outline in pixel coordinates (projectedOutline), its corners clockwise
// on screen (y down); none where it is not a triangle there (cut by the near plane into
// four corners, behind it, or seen edge-on).
std::optional<std::array<dvec2, 3>> clockwiseOutline(const PreparedScene& scene, std::uint32_t triangle) {
  const std::vector<dvec2> outline = projectedOutline(scene, scene.camera(), triangle);
  if (outline.size() != 3) return std::nullopt;
  std::array<dvec2, 3> corners = {outline[0], outline[1], outline[2]};
  const double area = edgeFunction(corners[0], corners[1], corners[2]);
  if (area == 0) return std::nullopt;
  if (area < 0) std::swap(corners[1], corners[2]);
  return corners;
}

// Whether the fill rule gives the center to the triangle, on a scene whose vertices
// land on pixel coordinates exactly (so that these products are exact): every edge
// function positive there, or zero on a top or a left edge (conventions.hpp, and
// renderer/raster/raster.cpp, which decides it in fixed point).
bool fillRuleHolds(const std::array<dvec2, 3>& clockwise, const dvec2& center) {
  for (int k = 0; k < 3; ++k) {
    const dvec2 &a = clockwise[std::size_t(k + 1) % 3], &b = clockwise[std::size_t(k + 2) % 3];
    const double value = edgeFunction(a, b, center), dx = b.x - a.x, dy = b.y - a.y;
    if (value < 0 || (value == 0 && !((dy == 0 && dx > 0) || dy < 0))) return false;
  }
  return true;
}

// The same for a triangle projected for this center alone.
bool fillRuleGives(const PreparedScene& scene, std::uint32_t triangle, const dvec2& center) {
  const std::optional<std::array<dvec2, 3>> outline = clockwiseOutline(scene, triangle);
  return outline && fillRuleHolds(*outline, center);
}

// A triangle's corners on the screen, each with its view distance.
struct CornerDistances {
  std::array<dvec2, 3> pixel;
  std::array<double, 3> distance;
};
CornerDistances cornerDistances(const PreparedScene& scene, std::uint32_t triangle) {
  const CameraTransform& camera = scene.camera();
  CornerDistances corners;
  for (std::size_t k = 0; k < 3; ++k) {
    const ClipVertex v = camera.clipFromWorld(scene.positions()[scene.triangles()[triangle][k]]);
    corners.pixel[k] = camera.pixelFromClip(v);
    corners.distance[k] = v.d;
  }
  return corners;
}

// The view distance of a triangle at a center, from its corners' distances weighted by
// the center's barycentric coordinates on the screen (depth is affine there under an
// orthographic camera, which a pixel-exact scene has); a triangle of one distance has
// exactly it.
double distanceAt(const CornerDistances& corners, const dvec2& center) {
  const auto& [pixel, distance] = corners;
  if (distance[0] == distance[1] && distance[1] == distance[2]) return distance[0];
  const double area = edgeFunction(pixel[0], pixel[1], pixel[2]);
  return (edgeFunction(pixel[1], pixel[2], center) * distance[0] + edgeFunction(pixel[2], pixel[0], center) * distance[1] +
          edgeFunction(pixel[0], pixel[1], center) * distance[2]) /
         area;
}

std::string distanceText(double distance) {
  char text[48];
  std::snprintf(text, sizeof text, "%.9g", distance);
  return text;
}

// A depth image's verdict at a pixel whose id is right (see judge() in judge.hpp).
struct DepthVerdict {
  std::optional<Cause> cause;  // none when right
  double expected = INFINITY;  // the shown triangle's distance at the center
  double z = 1;                // and the float32 z-buffer's z there, before rounding
};
DepthVerdict checkDepth(const PreparedScene& scene, std::uint32_t shown, const dvec2& center, double kept) {
  const CameraTransform& camera = scene.camera();
  const DepthEncoding encoding = depthEncoding(DepthFormat::float32, camera);
  const auto zOf = [&](double distance) { return encoding.z(camera.screenAffineDepth(distance)); };
  const auto float32Step = [](double z) { return double(std::nextafter(float(z), 2.0f)) - double(float(z)); };
  DepthVerdict verdict;
  // A distance is positive: in front of the eye (under perspective a negative one's z
  // would pass for one beyond the far plane).
  if (shown == 0) {
    const double far = camera.camera().far, farZ = zOf(far);
    if (!(kept >= far || (kept > 0 && zOf(kept) >= farZ - 2 * float32Step(farZ)))) verdict.cause = Cause::backgroundDepth;
    return verdict;
  }
  // z is affine across the screen, so its change over a pixel, right and down, bounds
  // what moving the triangle's vertices by 1/256 pixel changes it by at the center.
  const auto zAt = [&](double x, double y) { return zOf(planeHit(scene, camera, shown - 1, camera.rayThroughPixel(x, y)).distance); };
  verdict.expected = planeHit(scene, camera, shown - 1, camera.rayThroughPixel(center.x, center.y)).distance;
  verdict.z = zAt(center.x, center.y);
  const double slope = std::abs(zAt(center.x + 1, center.y) - verdict.z) + std::abs(zAt(center.x, center.y + 1) - verdict.z);
  // A plane seen edge-on has no distance to judge at the center.
  if (!std::isfinite(verdict.z) || !std::isfinite(slope)) return verdict;
  const double allowed = 2 * float32Step(verdict.z) + slope * kSnapDistance + std::abs(zOf(verdict.expected * (1 + 0x1p-23)) - verdict.z);
  if (kept > 0 && std::abs(zOf(kept) - verdict.z) <= allowed) return verdict;
  verdict.cause = std::abs(kept - verdict.z) <= allowed ? Cause::depthIsZ : Cause::depthWrong;
  return verdict;
}

}  // namespace

std::vector<std::uint32_t> conventionsAnswer(const PreparedScene& scene) {
  const int width = scene.width(), height = scene.height();
  const double near = scene.camera().camera().near, far = scene.camera().camera().far;
  std::vector<std::uint32_t> ids(std::size_t(width) * std::size_t(height), 0);
  std::vector<double> nearest(ids.size(), std::numeric_limits<double>::infinity());
  // In submission order: a triangle keeps a center it holds by the fill rule where it is
  // strictly nearer than what the center holds, so the first drawn keeps a tie.
  for (std::uint32_t t = 0; t < scene.triangleCount(); ++t) {
    // Behind the near plane, cut by it (no pixel-exact scene has one) or edge-on: no center.
    const std::optional<std::array<dvec2, 3>> outline = clockwiseOutline(scene, t);
    if (!outline) continue;
    const CornerDistances corners = cornerDistances(scene, t);
    double left = width, right = 0, top = height, bottom = 0;
    for (const dvec2& corner : *outline) {
      left = std::min(left, corner.x), right = std::max(right, corner.x);
      top = std::min(top, corner.y), bottom = std::max(bottom, corner.y);
    }
    for (int y = std::max(0, int(std::floor(top))); y < std::min(height, int(std::ceil(bottom)) + 1); ++y)
      for (int x = std::max(0, int(std::floor(left))); x < std::min(width, int(std::ceil(right)) + 1); ++x) {
        const dvec2 center(x + 0.5, y + 0.5);
        if (!fillRuleHolds(*outline, center)) continue;
        const std::size_t p = std::size_t(y) * std::size_t(width) + std::size_t(x);
        const double distance = distanceAt(corners, center);
        if (distance < near || distance > far || !(distance < nearest[p])) continue;
        nearest[p] = distance;
        ids[p] = t + 1;
      }
  }
  return ids;
}

const char* causeName(Cause cause) { return kCauseTexts[std::size_t(cause)].name; }
const char* causeAdvice(Cause cause) { return kCauseTexts[std::size_t(cause)].advice; }

Judgement judge(const PreparedScene& scene, const ReferenceImage& reference, std::span<const std::uint32_t> shown,
                std::span<const std::uint32_t> conventions, bool tieRule, std::span<const float> depth) {
  const CameraTransform& camera = scene.camera();
  const int width = scene.width();
  const std::uint32_t triangles = std::uint32_t(scene.triangleCount());
  const DepthTie depthTie = float32DepthTie(camera);
  Stats stats;
  const SurfaceReference rays(scene, stats);

  Judgement result;
  result.pixels = std::int64_t(shown.size());
  result.heatMap.resize(shown.size() * 4);
  std::array<CauseCount, kCauses> found;
  for (int c = 0; c < kCauses; ++c) found[std::size_t(c)].cause = Cause(c);
  bool anythingShown = false;

  for (std::size_t p = 0; p < shown.size(); ++p) {
    const int x = int(p % std::size_t(width)), y = int(p / std::size_t(width));
    const std::uint32_t mine = shown[p], exact = reference.frame.ids[p];
    anythingShown |= mine != 0;
    const Ray ray = camera.rayThroughPixel(x + 0.5, y + 0.5);
    const auto metAt = [&](std::uint32_t id) { return id == 0 ? NAN : hitDistance(scene, camera, id - 1, ray); };
    // The verdict: right, excused, or wrong with a cause.
    enum class Verdict { right, tie, excused, wrong } verdict = Verdict::right;
    Cause cause = Cause::missing;
    const dvec2 center(x + 0.5, y + 0.5);
    const double near = camera.camera().near, far = camera.camera().far;
    // The cause of a wrong pixel, from what its ray meets.
    const auto causeOf = [&](bool onAnEdge) {
      const double mineAt = metAt(mine), exactAt = metAt(exact);
      if (onAnEdge) return mine == 0 ? Cause::crack : Cause::doubleCovered;
      if (mine == 0) return exact != 0 && crossesNearPlane(scene, exact - 1) ? Cause::nearPlane : Cause::missing;
      if (crossesNearPlane(scene, mine - 1) && !(mineAt >= near)) return Cause::nearPlane;
      if (std::isnan(mineAt))
        return std::isfinite(hitDistance(scene, camera, mine - 1, camera.rayThroughPixel(x, y))) ? Cause::cornerSampled
                                                                                               : Cause::notCovering;
      if (mineAt > far) return Cause::beyondFar;
      if (exact != 0 && mineAt > exactAt) return Cause::fartherWon;
      return Cause::notCovering;
    };
    if (reference.ambiguous[p]) ++result.ties;
    if (mine > triangles) {
      verdict = Verdict::wrong;
      cause = Cause::unknownId;
    } else if (!conventions.empty()) {
      // A fill-rule scene: the rasterizer places every vertex exactly, so every pixel,
      // a center on an edge too, has one right answer: the conventions'.
      // The triangle shown must hold the center by the fill rule and be among the
      // nearest; of several, the first drawn, where the exercise's algorithm keeps ties
      // so (a painter draws coplanar faces in an order of its own).
      const auto amongTied = [&] {
        std::vector<std::uint32_t> tied;
        SurfaceReference::Counters counters;
        rays.trace(camera, ray, counters, &tied);
        return std::find(tied.begin(), tied.end(), mine) != tied.end();
      };
      if (mine == conventions[p]) {
        verdict = reference.ambiguous[p] ? Verdict::tie : Verdict::right;
      } else if (mine != 0 && (mine == exact || (reference.ambiguous[p] && amongTied())) && fillRuleGives(scene, mine - 1, center)) {
        verdict = tieRule ? Verdict::wrong : Verdict::tie;
        cause = Cause::laterTie;
      } else {
        verdict = Verdict::wrong;
        cause = causeOf(nearestProjectedEdge(scene, camera, {mine, conventions[p], exact}, center) < kSnapDistance);
      }
    } else if (reference.ambiguous[p]) {
      std::vector<std::uint32_t> tied;
      SurfaceReference::Counters counters;
      rays.trace(camera, ray, counters, &tied);
      const double tiedAt = metAt(tied.front()), mineAt = metAt(mine);
      if (std::find(tied.begin(), tied.end(), mine) != tied.end()) {
        verdict = Verdict::tie;
      } else if (mine == 0) {
        // Background at a tie. On the scene's outline (a vertex or edge on the
        // silhouette), the fill rule may give the center to none of the tied triangles.
        // Inside it, the center lies on an edge the tied triangles share, which snaps
        // alike in both: background there is a crack, or coplanar faces both dropped.
        const bool enclosed = std::all_of(kAround.begin(), kAround.end(), [&](const dvec2& offset) {
          return rays.trace(camera, camera.rayThroughPixel(center.x + offset.x, center.y + offset.y), counters).id != 0;
        });
        if (!enclosed) {
          verdict = Verdict::excused;
        } else {
          verdict = Verdict::wrong;
          cause = nearestProjectedEdge(scene, camera, {tied.front()}, center) < kSnapDistance ? Cause::crack : Cause::missing;
        }
      } else if (std::any_of(tied.begin(), tied.end(),
                             [&](std::uint32_t id) { return nearestProjectedEdge(scene, camera, {mine, id}, center) < kSnapDistance; }) ||
                 (std::isfinite(mineAt) && depthTie(mineAt, tiedAt))) {
        verdict = Verdict::excused;
      } else {
        verdict = Verdict::wrong;
        cause = causeOf(false);
      }
    } else if (mine != exact) {
      const double mineAt = metAt(mine), exactAt = metAt(exact);
      if (nearestProjectedEdge(scene, camera, {mine, exact}, center) < kSnapDistance ||
          (std::isfinite(mineAt) && std::isfinite(exactAt) && depthTie(mineAt, exactAt))) {
        verdict = Verdict::excused;
      } else {
        verdict = Verdict::wrong;
        cause = causeOf(false);
      }
    }

    // The depth image, where the id is right (a wrong id is the first thing to mend).
    std::optional<DepthVerdict> depthVerdict;
    if (!depth.empty() && verdict != Verdict::wrong) {
      depthVerdict = checkDepth(scene, mine, center, depth[p]);
      if (depthVerdict->cause) {
        verdict = Verdict::wrong;
        cause = *depthVerdict->cause;
      }
    }

    std::uint8_t* heat = &result.heatMap[4 * p];
    const auto grey = std::uint8_t(exact == 0 ? 24 : 70 + (exact * 37) % 90);
    heat[0] = heat[1] = heat[2] = grey;
    heat[3] = 255;
    if (verdict == Verdict::tie) {
      heat[2] = 220;
    } else if (verdict == Verdict::excused) {
      ++result.excused;
      heat[0] = heat[1] = 200;
      heat[2] = 40;
    } else if (verdict == Verdict::wrong) {
      ++result.wrong;
      heat[0] = 255;
      heat[1] = heat[2] = 0;
      CauseCount& count = found[std::size_t(cause)];
      const bool firstOfItsCause = count.pixels++ == 0;
      if (firstOfItsCause && depthVerdict) {
        count.x = x;
        count.y = y;
        count.first = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "): shows " +
                      (mine == 0 ? std::string("background")
                                 : "triangle " + std::to_string(mine) + ", at distance " + distanceText(depthVerdict->expected) +
                                       " there (z " + distanceText(depthVerdict->z) + ")") +
                      "; the depth image holds " + distanceText(depth[p]);
      } else if (firstOfItsCause) {
        count.x = x;
        count.y = y;
        const double mineAt = metAt(mine <= triangles ? mine : 0), exactAt = metAt(exact);
        count.first = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "): shows " +
                      (mine == 0 ? std::string("background") : "triangle " + std::to_string(mine)) +
                      (mine != 0 && mine <= triangles
                           ? (std::isfinite(mineAt) ? " (met at distance " + distanceText(mineAt) + ")" : " (not met by the pixel's ray)")
                           : "") +
                      "; exactly, " +
                      (exact == 0 ? std::string("background") : "triangle " + std::to_string(exact) + " at distance " + distanceText(exactAt)) +
                      (reference.ambiguous[p] ? " (a certified tie)" : "");
      }
    }
  }
  const bool referenceShowsSomething =
      std::any_of(reference.frame.ids.begin(), reference.frame.ids.end(), [](std::uint32_t id) { return id != 0; });
  if (!anythingShown && referenceShowsSomething) {
    found = {};
    found[std::size_t(Cause::nothingDrawn)] = {Cause::nothingDrawn, result.wrong, "every pixel is background", -1, -1};
  }
  for (const CauseCount& count : found)
    if (count.pixels > 0) result.causes.push_back(count);
  std::stable_sort(result.causes.begin(), result.causes.end(),
                   [](const CauseCount& a, const CauseCount& b) { return a.pixels > b.pixels; });
  return result;
}

}  // namespace hsr::grading
