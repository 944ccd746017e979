#include <algorithm>
#include <cmath>
#include <vector>

#include "renderer/reference/reference.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr {
namespace {

constexpr int kSurvey = 4;                  // the survey's points per pixel side
constexpr std::uint32_t kMixed = ~0u;       // a pixel that may show more than one thing
// How far past its sides a pixel counts as touched: rounding only (the clip coordinates'
// few ulps); its nearest samples are 1/64 pixel inside its sides.
constexpr double kPixelMargin = 1.0 / 256;

// A triangle in view space (eye at the origin, looking down -z), and the part of it
// between the near and far planes, the only part a ray can meet: its corners in view
// space, in clip coordinates, and on the screen in pixel coordinates.
struct ViewTriangle {
  dvec3 corner[3];
  int seenCorners = 0;
  dvec3 seen[5];  // a convex polygon: a triangle clipped by two planes has up to five corners
  ClipVertex clip[5];
  dvec2 pixel[5];
};

// The polygon's part on the inside of a plane, by Sutherland and Hodgman's step, given
// each corner's value of the plane's linear function (inside: >= 0); the clip
// coordinates, linear in the view-space position, are cut at the same fractions.
int clippedPolygon(const dvec3* in, const ClipVertex* inClip, const double* value, int count, dvec3* out, ClipVertex* outClip) {
  int kept = 0;
  for (int k = 0; k < count; ++k) {
    const int next = (k + 1) % count;
    if (value[k] >= 0) out[kept] = in[k], outClip[kept++] = inClip[k];
    if ((value[k] >= 0) != (value[next] >= 0)) {
      const double t = value[k] / (value[k] - value[next]);
      out[kept] = in[k] + t * (in[next] - in[k]);
      const ClipVertex &a = inClip[k], &b = inClip[next];
      outClip[kept++] = {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.d + t * (b.d - a.d), a.w + t * (b.w - a.w)};
    }
  }
  return kept;
}

ViewTriangle viewTriangle(const PreparedScene& scene, const CameraTransform& camera, std::uint32_t t) {
  const Camera& lens = camera.camera();
  ViewTriangle view;
  ClipVertex clip[3];
  for (int k = 0; k < 3; ++k) {
    view.corner[k] = camera.viewFromWorld(scene.positions()[scene.triangles()[t][std::size_t(k)]]);
    clip[k] = camera.clipFromView(view.corner[k]);
  }
  double value[4];
  dvec3 nearClipped[4];
  ClipVertex nearClip[4];
  for (int k = 0; k < 3; ++k) value[k] = clip[k].d - lens.near;
  const int nearCount = clippedPolygon(view.corner, clip, value, 3, nearClipped, nearClip);
  for (int k = 0; k < nearCount; ++k) value[k] = lens.far - nearClip[k].d;
  view.seenCorners = clippedPolygon(nearClipped, nearClip, value, nearCount, view.seen, view.clip);
  for (int k = 0; k < view.seenCorners; ++k) view.pixel[k] = camera.pixelFromClip(view.clip[k]);
  return view;
}

// The seen part's piece that the rays through pixel (x, y) can meet, its sides grown by
// kPixelMargin: clipped by the pixel's four sides, planes in clip coordinates (a point is
// right of the pixel's left side when its pixel x, (x_c / w + 1) width / 2, is).
int seenThroughPixel(const ViewTriangle& view, int width, int height, int x, int y, dvec3* piece) {
  dvec3 corners[2][8];
  ClipVertex clips[2][8];
  std::copy_n(view.seen, view.seenCorners, corners[0]);
  std::copy_n(view.clip, view.seenCorners, clips[0]);
  int count = view.seenCorners;
  const double left = x - kPixelMargin, right = x + 1 + kPixelMargin, top = y - kPixelMargin, bottom = y + 1 + kPixelMargin;
  for (int side = 0; side < 4 && count > 0; ++side) {
    double value[8];
    for (int k = 0; k < count; ++k) {
      const ClipVertex& c = clips[side % 2][k];
      const double pixelX = 0.5 * width * (c.x + c.w), pixelY = 0.5 * height * (c.w - c.y);  // times w
      value[k] = side == 0 ? pixelX - left * c.w : side == 1 ? right * c.w - pixelX : side == 2 ? pixelY - top * c.w : bottom * c.w - pixelY;
    }
    count = clippedPolygon(corners[side % 2], clips[side % 2], value, count, corners[(side + 1) % 2], clips[(side + 1) % 2]);
  }
  std::copy_n(corners[0], count, piece);
  return count;
}

// Whether some corner of a piece may lie nearer than the plane of `shown` along the rays:
// on the side of that plane the rays come from (the eye's, under perspective; +z, toward
// the camera, under orthographic), or on it to within rounding. The piece is convex, and
// the plane's side is decided at its corners.
bool mayBeInFront(const dvec3* piece, int corners, const ViewTriangle& shown, bool perspective) {
  const dvec3 a = shown.corner[0];
  const dvec3 normal = glm::cross(shown.corner[1] - a, shown.corner[2] - a);
  const double eyeSide = perspective ? -glm::dot(normal, a) : normal.z;
  if (eyeSide == 0) return true;  // seen edge-on: it covers no pixel whole
  const double scale = glm::length(normal);
  for (int k = 0; k < corners; ++k) {
    const double tolerance = 1e-9 * scale * (glm::length(piece[k]) + glm::length(a) + 1);
    if ((eyeSide > 0 ? 1 : -1) * glm::dot(normal, piece[k] - a) > -tolerance) return true;
  }
  return false;
}

}  // namespace

PixelShares traceExactShares(const PreparedScene& scene, int samples, int threads, Stats& stats) {
  HSR_CHECK(samples >= 1);
  const SurfaceReference reference(scene, stats, ReferenceTraversal::packets, threads);
  PhaseTimer timer(stats, "coverage reference");
  const int width = scene.width(), height = scene.height();
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  const CameraTransform camera = scene.camera();
  // The two images whose pixel centers are the points traced: the survey's, a quarter
  // pixel apart, and the shares', `samples` to a pixel side.
  const CameraTransform survey(scene.scene().camera, width * kSurvey, height * kSurvey);
  const CameraTransform fine(scene.scene().camera, width * samples, height * samples);
  const auto rows = static_cast<std::size_t>(height);
  std::vector<std::int64_t> rowRays(rows, 0);

  // 1. The survey: what each pixel's 4 x 4 points and its neighbours' nearest ones (6 x 6
  //    points, out to 1/8 of a pixel past its sides, beyond the image's sides too) show.
  //    Where they all show one triangle, at none of them a tie, the triangle covers the
  //    whole pixel (their hull holds the pixel, and the part of a triangle between the
  //    near and far planes is convex); where they all show nothing, nothing covers any of
  //    those points. Survey column c is point column c - 1: one more on each side.
  std::vector<std::uint32_t> shown(pixels, kMixed);
  parallelFor(rows, threads, [&](std::size_t row, int) {
    const int y = int(row);
    const int firstRow = y * kSurvey - 1, endRow = (y + 1) * kSurvey + 1;
    const std::size_t surveyWidth = std::size_t(width) * kSurvey + 2;
    SurfaceReference::Counters work;  // the traversal's counts, which the exact shares do not report
    std::vector<std::uint32_t> surveyed(std::size_t(endRow - firstRow) * surveyWidth);
    std::vector<ReferenceHit> hits(surveyWidth);
    for (int r = firstRow; r < endRow; ++r) {
      reference.traceRun(survey, r, -1, int(surveyWidth), hits.data(), work);
      for (std::size_t c = 0; c < surveyWidth; ++c) surveyed[std::size_t(r - firstRow) * surveyWidth + c] = hits[c].ambiguous ? kMixed : hits[c].id;
    }
    rowRays[row] += std::int64_t(endRow - firstRow) * std::int64_t(surveyWidth);
    for (int x = 0; x < width; ++x) {
      const std::size_t firstColumn = std::size_t(x) * kSurvey, endColumn = firstColumn + kSurvey + 2;
      const std::uint32_t first = surveyed[firstColumn];
      bool uniform = true;
      for (int r = 0; uniform && r < endRow - firstRow; ++r)
        for (std::size_t c = firstColumn; uniform && c < endColumn; ++c) uniform = surveyed[std::size_t(r) * surveyWidth + c] == first;
      if (uniform) shown[row * std::size_t(width) + std::size_t(x)] = first;
    }
  });

  // 2. The proof: a pixel stays whole only if no other triangle's piece that the pixel's
  //    rays can meet lies nearer than the one it shows (every corner of the piece behind
  //    that one's plane), or, for a pixel showing nothing, if no rays of it can meet a
  //    triangle between the near and far planes. What falls between the survey's points
  //    (a sliver, a strip narrower than a quarter pixel) is caught here.
  std::vector<ViewTriangle> view(scene.triangleCount());
  parallelForEach(view.size(), 4096, threads, [&](std::size_t t) { view[t] = viewTriangle(scene, camera, std::uint32_t(t)); });
  // A flag per pixel that threads set (claimFlag) and read while others set them, both atomically.
  std::vector<std::uint32_t> tracedInFull(pixels);
  std::transform(shown.begin(), shown.end(), tracedInFull.begin(), [](std::uint32_t id) { return id == kMixed; });
  const auto claimed = [&](std::size_t pixel) { return __atomic_load_n(&tracedInFull[pixel], __ATOMIC_RELAXED) != 0; };
  const bool perspective = scene.scene().camera.projection == Projection::perspective;
  parallelForEach(view.size(), 1024, threads, [&](std::size_t t) {
    const ViewTriangle& other = view[t];
    if (other.seenCorners == 0) return;  // wholly nearer than the near plane or beyond the far one
    double lowX = other.pixel[0].x, highX = lowX, lowY = other.pixel[0].y, highY = lowY;
    for (int k = 1; k < other.seenCorners; ++k) {
      lowX = std::min(lowX, other.pixel[k].x), highX = std::max(highX, other.pixel[k].x);
      lowY = std::min(lowY, other.pixel[k].y), highY = std::max(highY, other.pixel[k].y);
    }
    // Clamped as doubles first: a corner far off the screen is no int.
    const auto pixelAt = [](double at, int last) { return int(std::floor(std::clamp(at, -1.0, double(last) + 1))); };
    const int x0 = std::max(0, pixelAt(lowX - kPixelMargin, width)), x1 = std::min(width - 1, pixelAt(highX + kPixelMargin, width));
    const int y0 = std::max(0, pixelAt(lowY - kPixelMargin, height)), y1 = std::min(height - 1, pixelAt(highY + kPixelMargin, height));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const std::size_t pixel = std::size_t(y) * std::size_t(width) + std::size_t(x);
        const std::uint32_t id = shown[pixel];
        if (id == kMixed || id == t + 1 || claimed(pixel)) continue;
        dvec3 piece[8];
        const int corners = seenThroughPixel(other, width, height, x, y, piece);
        if (corners > 0 && (id == 0 || mayBeInFront(piece, corners, view[id - 1], perspective))) claimFlag(tracedInFull[pixel]);
      }
  });

  // 3. Each pixel's shares: a whole pixel's one surface, anywhere else its samples x
  //    samples points traced, each a sample's share (appendSharesOfSamples, as
  //    sharesOfSamples counts them), and the pixel marked tied where a point met a tie.
  std::vector<std::vector<std::pair<std::uint32_t, double>>> rowShares(rows);
  std::vector<std::vector<std::uint32_t>> rowEnds(rows);
  std::vector<std::int64_t> rowFull(rows, 0);
  std::vector<std::uint8_t> tied(pixels, 0);
  parallelFor(rows, threads, [&](std::size_t row, int) {
    std::vector<ReferenceHit> hits(static_cast<std::size_t>(samples));
    SurfaceReference::Counters work;  // the traversal's counts, which the exact shares do not report
    std::vector<std::uint32_t> ids(std::size_t(samples) * std::size_t(samples));
    for (int x = 0; x < width; ++x) {
      const std::size_t pixel = row * std::size_t(width) + std::size_t(x);
      if (!tracedInFull[pixel]) {
        rowShares[row].emplace_back(shown[pixel], 1.0);
      } else {
        ++rowFull[row];
        for (int sy = 0; sy < samples; ++sy) {
          reference.traceRun(fine, int(row) * samples + sy, x * samples, samples, hits.data(), work);
          for (int sx = 0; sx < samples; ++sx) {
            ids[std::size_t(sy) * std::size_t(samples) + std::size_t(sx)] = hits[std::size_t(sx)].id;
            tied[pixel] |= hits[std::size_t(sx)].ambiguous;
          }
        }
        rowRays[row] += std::int64_t(samples) * samples;
        appendSharesOfSamples(ids, rowShares[row]);
      }
      rowEnds[row].push_back(std::uint32_t(rowShares[row].size()));
    }
  });

  PixelShares shares;
  shares.first.reserve(pixels + 1);
  shares.first.push_back(0);
  std::int64_t rays = 0, full = 0;
  for (std::size_t row = 0; row < rows; ++row) {
    const auto offset = std::uint32_t(shares.shares.size());
    for (const std::uint32_t end : rowEnds[row]) shares.first.push_back(offset + end);
    shares.shares.insert(shares.shares.end(), rowShares[row].begin(), rowShares[row].end());
    rays += rowRays[row];
    full += rowFull[row];
  }
  if (std::find(tied.begin(), tied.end(), 1) != tied.end()) shares.tied = std::move(tied);
  stats.add("coverage reference rays", rays);
  stats.add("coverage reference pixels traced in full", full);
  return shares;
}

}  // namespace hsr
