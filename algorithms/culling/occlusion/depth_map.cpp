// The occluder depth map (depth_map.hpp has the two rasterization rules).
#include "algorithms/culling/occlusion/depth_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "algorithms/culling/occlusion/fast_path.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/simd.hpp"

namespace hsr::culling::occlusion {
namespace {

constexpr float kEmpty = std::numeric_limits<float>::infinity();
constexpr std::uint32_t kNearAndGuard = kNearPlane | kGuardLeft | kGuardRight | kGuardBottom | kGuardTop;

double cross(const dvec2& u, const dvec2& v) { return u.x * v.y - u.y * v.x; }

// Andrew's monotone chain: the convex hull of up to 8 points, counter-clockwise in
// (x, y) as the numbers go (clockwise as seen on a y-down image); returns its size.
int convexHull(std::array<dvec2, 8> points, int count, dvec2* hull) {
  std::sort(points.begin(), points.begin() + count,
            [](const dvec2& a, const dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  int size = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const int start = size;
    for (int k = 0; k < count; ++k) {
      const dvec2& p = points[std::size_t(pass == 0 ? k : count - 1 - k)];
      while (size >= start + 2 && cross(hull[size - 1] - hull[size - 2], p - hull[size - 2]) <= 0) --size;
      hull[size++] = p;
    }
    --size;  // each chain's last point starts the other
  }
  return size;
}

// The largest key of `rows` rows of `columns` texels (a multiple of the vector's lanes),
// rows `stride` apart, a vector of Lanes at a time: the compiler leaves this reduction
// scalar by itself (it would have to reorder the comparisons). Four lanes for the
// baseline; eight, a tile's whole row, inlined into an AVX2 function.
template <typename Lanes>
HSR_INLINE float largestOfWholeRows(const float* first, std::size_t stride, int rows, int columns) {
  constexpr int kLanes = int(sizeof(Lanes) / sizeof(float));
  Lanes lanes = Lanes{} - kEmpty;  // -infinity in every lane
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < columns; x += kLanes) {
      Lanes some;
      __builtin_memcpy(&some, first + std::size_t(y) * stride + std::size_t(x), sizeof some);
      lanes = some > lanes ? some : lanes;
    }
  float largest = lanes[0];
  for (int lane = 1; lane < kLanes; ++lane) largest = std::max(largest, lanes[lane]);
  return largest;
}
using Float8 = float __attribute__((vector_size(32)));
HSR_AVX2 float largestOfWholeRowsWithAvx2(const float* first, std::size_t stride, int rows, int columns) {
  return largestOfWholeRows<Float8>(first, stride, rows, columns);
}

}  // namespace

void conservativeRow(float* row, int first, int last, const RowKey* keys, int count) {
  for (int x = first; x <= last; ++x) {
    double farthest = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < count; ++k) farthest = std::max(farthest, keys[k].atZero + keys[k].slope * x);
    row[x] = std::min(row[x], roundedUp(farthest));
  }
}

void centerRow(float* row, int first, int last, const CenterRowKey* keys, int count) {
  for (int x = first; x <= last; ++x) {
    float farthest = -kEmpty;
    for (int k = 0; k < count; ++k) farthest = std::max(farthest, keys[k].atZero + keys[k].slope * static_cast<float>(x));
    row[x] = std::min(row[x], farthest);
  }
}

DepthMap::DepthMap(int w, int h) : width(w), height(h), keys(std::size_t(w) * std::size_t(h), kEmpty) {}

MapView::MapView(const CameraTransform& viewCamera, int mapWidth, int mapHeight)
    : camera(viewCamera),
      width(mapWidth),
      height(mapHeight),
      scale(double(mapWidth) / viewCamera.width(), double(mapHeight) / viewCamera.height()),
      volume(viewCamera, false) {
  // The guard band in the map's own texels, where the rasterizer's fixed point needs it.
  volume.guardX = conventions::kGuardBandPixels / (0.5 * mapWidth);
  volume.guardY = conventions::kGuardBandPixels / (0.5 * mapHeight);
}

std::array<dvec3, 8> cornersOf(const Aabb& box) {
  std::array<dvec3, 8> corners;
  for (int i = 0; i < 8; ++i)
    corners[std::size_t(i)] = dvec3(i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z);
  return corners;
}

BoxFootprint footprint(const MapView& view, const Aabb& bounds) {
  BoxFootprint box;
  dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  double nearest = std::numeric_limits<double>::infinity();
  // The view transform is affine: each corner's view coordinates are the low corner's
  // moved by the box's sides, transformed once (a few ulps from transforming each
  // corner, far inside the margins below).
  const CameraTransform& camera = view.camera;
  const dvec3 low = camera.viewFromWorld(bounds.lo), size = bounds.hi - bounds.lo;
  const dvec3 sides[3] = {size.x * dvec3(camera.right().x, camera.up().x, -camera.forward().x),
                          size.y * dvec3(camera.right().y, camera.up().y, -camera.forward().y),
                          size.z * dvec3(camera.right().z, camera.up().z, -camera.forward().z)};
  for (int corner = 0; corner < 8; ++corner) {
    dvec3 inView = low;
    for (int axis = 0; axis < 3; ++axis)
      if (corner >> axis & 1) inView += sides[axis];
    const ClipVertex v = camera.clipFromView(inView);
    if (v.d < view.volume.near) {
      box.crossesNear = true;
      return box;
    }
    const dvec2 texel = view.texel(v);
    lo = glm::min(lo, texel), hi = glm::max(hi, texel);
    nearest = std::min(nearest, v.d);
  }
  // The box's projection lies within its corners' rectangle (it is their convex hull);
  // the margin, far above the rounding of a projection, keeps a pixel center on the
  // rectangle's edge inside it.
  constexpr double kMargin = 1e-6;
  const auto clampedFloor = [](double value, int limit) {
    return static_cast<int>(std::clamp(value, 0.0, double(limit)));  // clamped to [0, limit], truncation is the floor
  };
  box.x0 = clampedFloor(lo.x - kMargin, view.width), box.x1 = clampedFloor(hi.x + kMargin + 1, view.width);
  box.y0 = clampedFloor(lo.y - kMargin, view.height), box.y1 = clampedFloor(hi.y + kMargin + 1, view.height);
  box.nearest = roundedDown(view.key(nearest));
  return box;
}

bool hiddenOnMap(const DepthMap& map, const BoxFootprint& box, std::int64_t& texelsRead, MapDecision* decision) {
  if (decision) [[unlikely]]
    decision->tested = box;
  if (box.crossesNear || box.empty()) return false;
  for (int y = box.y0; y < box.y1; ++y)
    for (int x = box.x0; x < box.x1; ++x) {
      ++texelsRead;
      if (map.at(x, y) >= box.nearest) {  // something of the box may show here
        if (decision) [[unlikely]]
          decision->x = x, decision->y = y;
        return false;
      }
    }
  return true;
}

TileMaxima::TileMaxima(const DepthMap& map)
    : map_(map),
      columns_((map.width + kTile - 1) / kTile),
      rows_((map.height + kTile - 1) / kTile),
      maxima_(std::size_t(columns_) * std::size_t(rows_), kEmpty),
      stale_(maxima_.size(), 1) {}

void TileMaxima::invalidate(const BoxFootprint& box) {
  if (box.crossesNear) {
    std::fill(stale_.begin(), stale_.end(), 1);
    return;
  }
  if (box.empty()) return;
  for (int ty = box.y0 / kTile; ty <= (box.y1 - 1) / kTile; ++ty)
    for (int tx = box.x0 / kTile; tx <= (box.x1 - 1) / kTile; ++tx) stale_[std::size_t(ty) * std::size_t(columns_) + std::size_t(tx)] = 1;
}

float TileMaxima::maximum(int tileX, int tileY) {
  const std::size_t index = std::size_t(tileY) * std::size_t(columns_) + std::size_t(tileX);
  if (stale_[index]) {
    const int x0 = tileX * kTile, x1 = std::min(map_.width, x0 + kTile), y1 = std::min(map_.height, (tileY + 1) * kTile);
    float largest = -kEmpty;
    if (x1 - x0 == kTile) {
      const float* const first = &map_.keys[std::size_t(tileY * kTile) * std::size_t(map_.width) + std::size_t(x0)];
      const int rows = y1 - tileY * kTile;
      largest = cpuHasAvx2() ? largestOfWholeRowsWithAvx2(first, std::size_t(map_.width), rows, kTile)
                             : largestOfWholeRows<Float4>(first, std::size_t(map_.width), rows, kTile);
    } else {
      for (int y = tileY * kTile; y < y1; ++y)
        for (int x = x0; x < x1; ++x) largest = std::max(largest, map_.at(x, y));
    }
    maxima_[index] = largest;
    stale_[index] = 0;
  }
  return maxima_[index];
}

bool TileMaxima::hidden(const BoxFootprint& box, std::int64_t& texelsRead) {
  if (box.crossesNear || box.empty()) return false;
  for (int ty = box.y0 / kTile; ty <= (box.y1 - 1) / kTile; ++ty)
    for (int tx = box.x0 / kTile; tx <= (box.x1 - 1) / kTile; ++tx) {
      ++texelsRead;
      // The whole tile is nearer. Its maximum from before the latest draws is tried
      // first: keys only fall while the map is drawn (a texel keeps the nearer key), so
      // an old maximum still bounds the tile, and where it is enough, the 64 texels need
      // no second look.
      const float bound = maxima_[std::size_t(ty) * std::size_t(columns_) + std::size_t(tx)];
      if (bound < box.nearest || maximum(tx, ty) < box.nearest) continue;
      // The tile holds something at least as far: look at the box's own texels in it.
      const BoxFootprint part{false, std::max(box.x0, tx * kTile), std::min(box.x1, (tx + 1) * kTile),
                              std::max(box.y0, ty * kTile), std::min(box.y1, (ty + 1) * kTile), box.nearest};
      if (!hiddenOnMap(map_, part, texelsRead)) return false;
    }
  return true;
}

Pyramid::Pyramid(const DepthMap& map) {
  levels_.push_back(map);
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const DepthMap& below = levels_.back();
    DepthMap level((below.width + 1) / 2, (below.height + 1) / 2);
    for (int y = 0; y < level.height; ++y) {
      const int y0 = 2 * y, y1 = std::min(2 * y + 1, below.height - 1);
      for (int x = 0; x < level.width; ++x) {
        const int x0 = 2 * x, x1 = std::min(2 * x + 1, below.width - 1);
        level.at(x, y) = std::max({below.at(x0, y0), below.at(x1, y0), below.at(x0, y1), below.at(x1, y1)});
      }
    }
    levels_.push_back(std::move(level));
  }
}

bool Pyramid::hidden(const BoxFootprint& box, std::int64_t& texelsRead, MapDecision* decision) const {
  if (box.crossesNear || box.empty()) return hiddenOnMap(levels_.front(), box, texelsRead, decision);
  // Texel i of a level covers texels 2i and 2i + 1 below it, so level k's texel over
  // level-0 texel x is x >> k.
  int level = 0;
  while (((box.x1 - 1) >> level) - (box.x0 >> level) > 1 || ((box.y1 - 1) >> level) - (box.y0 >> level) > 1) ++level;
  const BoxFootprint coarse{false, box.x0 >> level, ((box.x1 - 1) >> level) + 1, box.y0 >> level, ((box.y1 - 1) >> level) + 1,
                            box.nearest};
  if (decision) [[unlikely]]
    decision->level = level;
  return hiddenOnMap(levels_[std::size_t(level)], coarse, texelsRead, decision);
}

void OccluderRasterizer::triangle(const dvec3& a, const dvec3& b, const dvec3& c) {
  triangleInClipSpace({view_.camera.clipFromWorld(a), view_.camera.clipFromWorld(b), view_.camera.clipFromWorld(c)});
}

void OccluderRasterizer::triangleInClipSpace(const std::array<ClipVertex, 3>& clip) {
  ++trianglesRasterized;
  // Clipped only where it crosses the near plane or the guard band: most do not.
  ClipPolygon clipped;
  if ((view_.volume.outside(clip[0]) | view_.volume.outside(clip[1]) | view_.volume.outside(clip[2])) & kNearAndGuard) {
    clipped = clipTriangle(clip, view_.volume, kNearAndGuard);
    if (clipped.count < 3) return;
  } else {
    clipped.count = 3;
    std::copy(clip.begin(), clip.end(), clipped.vertices.begin());
  }
  dvec2 texel[9];
  double key[9];
  for (int i = 0; i < clipped.count; ++i) {
    texel[i] = view_.texel(clipped.vertices[std::size_t(i)]);
    key[i] = view_.key(clipped.vertices[std::size_t(i)].d);
  }
  // The plane through the polygon's best-conditioned fan triangle (all lie in one plane).
  int best = 1;
  double bestArea = 0;
  for (int i = 1; i + 1 < clipped.count; ++i) {
    const double area = std::abs(cross(texel[i] - texel[0], texel[i + 1] - texel[0]));
    if (area > bestArea) best = i, bestArea = area;
  }
  if (bestArea == 0) return;
  const dvec2 e1 = texel[best] - texel[0], e2 = texel[best + 1] - texel[0];
  const double area = cross(e1, e2), dk1 = key[best] - key[0], dk2 = key[best + 1] - key[0];
  const double kx = (dk1 * e2.y - dk2 * e1.y) / area, ky = (e1.x * dk2 - e2.x * dk1) / area;
  const KeyPlane plane{key[0] - kx * texel[0].x - ky * texel[0].y, kx, ky};
  polygon(texel, clipped.count, &plane, 1);
}

// A face of the box faces the eye when the eye is outside its plane. Decided in double
// with a tolerance that leans towards "faces the eye": an extra face only raises the
// depth written (farther: safe), a missing one could lower it.
bool OccluderRasterizer::facesEye(const std::array<dvec3, 8>& corners, int axis, int side) const {
  const int u = 1 << ((axis + 1) % 3), v = 1 << ((axis + 2) % 3), base = side << axis;
  const dvec3& origin = corners[std::size_t(base)];
  dvec3 normal = glm::cross(corners[std::size_t(base | u)] - origin, corners[std::size_t(base | v)] - origin);
  const dvec3 inward = corners[std::size_t(base ^ (1 << axis))] - origin;
  if (glm::dot(normal, inward) > 0) normal = -normal;
  const dvec3 towardsEye = view_.camera.perspective() ? view_.camera.camera().eye - origin : -view_.camera.forward();
  // dot(n, e) >= -1e-9 |n| |e|, squared where it is negative (no square roots).
  const double alongEye = glm::dot(normal, towardsEye);
  return alongEye >= 0 || alongEye * alongEye <= 1e-18 * glm::dot(normal, normal) * glm::dot(towardsEye, towardsEye);
}

void OccluderRasterizer::box(const std::array<dvec3, 8>& corners) {
  std::array<ClipVertex, 8> clip;
  bool crossesNear = false;
  for (std::size_t i = 0; i < 8; ++i) {
    clip[i] = view_.camera.clipFromWorld(corners[i]);
    crossesNear = crossesNear || clip[i].d < view_.volume.near;
  }
  const auto eachFrontFace = [&](auto&& face) {
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side)
        if (facesEye(corners, axis, side)) {
          const int u = 1 << ((axis + 1) % 3), v = 1 << ((axis + 2) % 3), base = side << axis;
          face(std::array<int, 4>{base, base | u, base | u | v, base | v});
        }
  };
  if (crossesNear) {
    // The front faces as triangles, clipped where they cross the near plane.
    eachFrontFace([&](const std::array<int, 4>& quad) {
      triangleInClipSpace({clip[std::size_t(quad[0])], clip[std::size_t(quad[1])], clip[std::size_t(quad[2])]});
      triangleInClipSpace({clip[std::size_t(quad[0])], clip[std::size_t(quad[2])], clip[std::size_t(quad[3])]});
    });
    return;
  }
  // The box wholly in front of the near plane: its projection is the hull of its
  // corners, and over it the front surface is the largest of the front faces' planes
  // (the box is convex: a sight line enters it through the last front plane it
  // crosses). So one polygon instead of up to six triangles: one scan of each row it
  // covers, and no texel lost along the edges between faces.
  std::array<dvec2, 8> texels;
  std::array<double, 8> keys;
  for (std::size_t i = 0; i < 8; ++i) texels[i] = view_.texel(clip[i]), keys[i] = view_.key(clip[i].d);
  KeyPlane planes[6];
  int planeCount = 0;
  eachFrontFace([&](const std::array<int, 4>& quad) {
    const std::size_t i0 = std::size_t(quad[0]), i1 = std::size_t(quad[1]), i2 = std::size_t(quad[3]);
    const dvec2 e1 = texels[i1] - texels[i0], e2 = texels[i2] - texels[i0];
    const double area = cross(e1, e2);
    if (area == 0) return;  // seen exactly edge-on: it shows nowhere
    const double dk1 = keys[i1] - keys[i0], dk2 = keys[i2] - keys[i0];
    const double kx = (dk1 * e2.y - dk2 * e1.y) / area, ky = (e1.x * dk2 - e2.x * dk1) / area;
    planes[planeCount++] = {keys[i0] - kx * texels[i0].x - ky * texels[i0].y, kx, ky};
  });
  dvec2 hull[16];
  const int hullSize = convexHull(texels, 8, hull);
  ++trianglesRasterized;
  if (planeCount > 0 && hullSize >= 3) polygon(hull, hullSize, planes, planeCount);
}

void OccluderRasterizer::polygon(const dvec2* corners, int count, const KeyPlane* planes, int planeCount) {
  // Each edge as E(x, y) = A x + B y + C, positive inside whichever way the polygon runs.
  double orientation = 0, reach = 1, left = corners[0].x, right = corners[0].x;
  for (int i = 0; i < count; ++i) {
    orientation += cross(corners[i], corners[(i + 1) % count]);
    reach = std::max({reach, std::abs(corners[i].x), std::abs(corners[i].y)});
    left = std::min(left, corners[i].x), right = std::max(right, corners[i].x);
  }
  // Wholly left or right of the map (many occluders are, when none were culled by the
  // frustum first): no row of it would hold a texel, so none is scanned.
  if (orientation == 0 || right <= 0 || left >= map_.width) return;
  const double sign = orientation > 0 ? 1.0 : -1.0;
  // Texel (x, y) spans [x, x + 1] x [y, y + 1]. The rule looks at one point of it, and
  // the texel is written when every edge function is at least a margin there:
  //   center        its center, margin 0: A x + B y + C + (A + B) / 2 >= 0;
  //   conservative  each edge's worst corner of it, so that the whole texel is inside:
  //                 A x + min(A, 0) + B y + min(B, 0) + C >= margin.
  // Either way A x >= rest(y) = margin - (B y + offset + C). An edge with A > 0 bounds x
  // from below by rest / A, one with A < 0 from above, and one with A = 0 holds for the
  // whole row or for none of it. Each is kept as rest(y) = fromRow - B y and the factor
  // 1 / A that turns it into a bound.
  struct Bound {
    double fromRow, b, inverseA;
  };
  Bound lower[16], upper[16], level[16];
  int lowerCount = 0, upperCount = 0, levelCount = 0;
  double top = corners[0].y, bottom = corners[0].y;
  for (int i = 0; i < count; ++i) {
    const dvec2 &p = corners[i], &q = corners[(i + 1) % count];
    const double a = -sign * (q.y - p.y), b = sign * (q.x - p.x);
    const double c = -(a * p.x + b * p.y);
    double offset = 0.5 * (a + b), margin = 0;
    if (rule_ == Rule::conservative) {
      offset = std::min(a, 0.0) + std::min(b, 0.0);
      // Far above the rounding of E at any corner in play (and of the bound's own
      // arithmetic): a texel that only touches the edge, to within rounding, counts as
      // not covered.
      margin = 1e-12 * ((std::abs(a) + std::abs(b)) * reach + std::abs(c)) + 1e-9 * (std::abs(a) + std::abs(b));
    }
    const Bound bound{margin - (offset + c), b, a != 0 ? 1 / a : 0};
    if (a > 0) lower[lowerCount++] = bound;
    else if (a < 0) upper[upperCount++] = bound;
    else level[levelCount++] = bound;
    top = std::min(top, p.y), bottom = std::max(bottom, p.y);
  }
  // Bounds are clamped while still doubles: a corner far out in the guard band does not
  // fit an int.
  const double firstRow = std::max(0.0, std::floor(top)), lastRow = std::min(double(map_.height - 1), std::ceil(bottom) - 1);
  // A bound on x as an integer within [-1, width]: clamped first (a corner far out in the
  // guard band gives bounds far outside the map), then ceiling and floor by conversion
  // (the baseline x86-64 has no rounding instruction, and std::ceil is a call).
  const auto clamped = [&](double x) { return std::clamp(x, -1.0, double(map_.width)); };
  const auto ceiling = [&](double x) {
    const auto whole = static_cast<int>(clamped(x));
    return whole < clamped(x) ? whole + 1 : whole;
  };
  const auto floored = [&](double x) {
    const auto whole = static_cast<int>(clamped(x));
    return whole > clamped(x) ? whole - 1 : whole;
  };
  for (int y = static_cast<int>(firstRow); y <= lastRow; ++y) {
    int first = 0, last = map_.width - 1;
    for (int i = 0; i < lowerCount; ++i) first = std::max(first, ceiling((lower[i].fromRow - lower[i].b * y) * lower[i].inverseA));
    for (int i = 0; i < upperCount; ++i) last = std::min(last, floored((upper[i].fromRow - upper[i].b * y) * upper[i].inverseA));
    for (int i = 0; i < levelCount; ++i)
      if (level[i].fromRow - level[i].b * y > 0) last = -1;
    if (first > last) continue;  // no texel of this row
    float* row = &map_.at(0, y);
    // The map is far larger than the cache and a run is a few cache lines of it: ask for
    // the run two rows down now, so it is there when its turn comes.
    if (y + 2 <= lastRow)
      for (int x = first; x <= last + 16; x += 16) __builtin_prefetch(row + 2 * map_.width + x, 1);
    // Along the row each plane's key is affine in x: its value at x = 0, and kx. Eight
    // texels at a time where the CPU has AVX2 (fast_path.hpp: the same bits).
    if (rule_ == Rule::center) {
      CenterRowKey keys[6];
      for (int k = 0; k < planeCount; ++k)
        keys[k] = {static_cast<float>(planes[k].k0 + planes[k].kx * 0.5 + planes[k].ky * (y + 0.5)), static_cast<float>(planes[k].kx)};
      if (cpuHasAvx2()) centerRowEightAtATime(row, first, last, keys, planeCount);
      else centerRow(row, first, last, keys, planeCount);
    } else {
      // An affine key is largest over the texel at the corner its slopes point to: at
      // x + 1 along the row where kx > 0 (else x), and y + 1 where ky > 0.
      RowKey keys[6];
      for (int k = 0; k < planeCount; ++k)
        keys[k] = {planes[k].k0 + planes[k].kx * (planes[k].kx > 0) + planes[k].ky * (y + (planes[k].ky > 0)), planes[k].kx};
      if (!(cpuHasAvx2() && conservativeRowEightAtATime(row, first, last, keys, planeCount))) conservativeRow(row, first, last, keys, planeCount);
    }
    texelsWritten += last - first + 1;
  }
}

}  // namespace hsr::culling::occlusion
