// The occluder depth map: a small depth buffer that holds, for each of its texels, a
// depth no object behind it can be nearer than: the occluders' depth (rasterized into
// it) or the previous frame's (read back from it). An occludee is hidden when its box,
// projected, lies behind every texel its screen rectangle touches.
//
// Depths are stored as keys that are affine in screen space and grow with distance
// (-1/d under perspective, d under orthographic), so one plane interpolates a triangle's
// depth exactly and "nearer" is always "smaller". Empty texels hold +infinity.
//
// The two rasterization rules of the published methods:
//   center        a texel takes an occluder's depth at its center whenever the occluder
//                 covers that center. Fast; but the texel then claims its whole area
//                 for the occluder, so an object seen through a gap narrower than a
//                 texel can be culled.
//   conservative  a texel is written only where one occluder covers it entirely, with
//                 the farthest depth the occluder has over it (rounded away from the
//                 occludee's side). Never culls a visible object.
// Both draw a convex polygon at a time (a triangle, or a solid box's whole outline) by
// the same scan: they differ only in the point of a texel they look at and the depth
// they write there.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/geometry/clip.hpp"
#include "renderer/rays/bvh.hpp"
#include "renderer/util/memory.hpp"

namespace hsr::culling::occlusion {

enum class Rule { conservative, center };

struct DepthMap {
  int width = 0, height = 0;
  std::vector<float> keys;  // row-major, row 0 at the top

  DepthMap() = default;
  DepthMap(int w, int h);
  float at(int x, int y) const { return keys[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
  float& at(int x, int y) { return keys[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

// The next float above f: std::nextafter(f, +infinity) for a finite f (-0 and +0 alike
// go to the smallest positive float), by its bits, without a call into the maths
// library (the conservative rule takes two per texel it writes).
inline float nextUp(float f) {
  if (f == 0) return std::numeric_limits<float>::denorm_min();
  const auto bits = bitCast<std::uint32_t>(f);
  return bitCast<float>(f > 0 ? bits + 1 : bits - 1);  // a positive's magnitude grows, a negative's shrinks
}

// A double rounded to float in a chosen direction, and one ulp further: a key computed in
// double within a few of its ulps of the truth still lands on the safe side.
inline float roundedUp(double value) {
  if (std::isinf(value)) return static_cast<float>(value);
  const float nearest = static_cast<float>(value);
  const float above = static_cast<double>(nearest) < value ? nextUp(nearest) : nearest;  // a select, not a branch it would mispredict
  return nextUp(above);
}
inline float roundedDown(double value) { return -roundedUp(-value); }

// The view's camera, seen at the map's resolution: the same view volume, its pixels scaled.
struct MapView {
  MapView(const CameraTransform& camera, int mapWidth, int mapHeight);
  const CameraTransform& camera;
  int width, height;
  dvec2 scale;        // map texels per view pixel
  ClipVolume volume;  // near plane and the guard band, in map texels
  double key(double distance) const { return camera.perspective() ? -1.0 / distance : distance; }
  dvec2 texel(const ClipVertex& v) const { return camera.pixelFromClip(v) * scale; }
};

// Where an occludee's box lands on the map: the texels [x0, x1) x [y0, y1) its screen
// rectangle touches, and its nearest key rounded down. `crossesNear`: some corner is
// nearer than the near plane, so its projection is unbounded: never hidden.
struct BoxFootprint {
  bool crossesNear = false;
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  float nearest = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
};
BoxFootprint footprint(const MapView& view, const Aabb& box);
std::array<dvec3, 8> cornersOf(const Aabb& box);

// What decided a box's test, for hsr why: the footprint tested (at pyramid level
// `level`, 0: the map itself) and the first texel that proved it may show, or none
// (x = -1: every texel hid it, or the footprint was empty or unbounded).
struct MapDecision {
  BoxFootprint tested;
  int level = 0;
  int x = -1, y = -1;
};

// Hidden when every texel of the footprint holds a key nearer than the box's nearest;
// stops at the first texel that proves it visible. Counts the texels read. `decision`:
// hsr why's, or null.
bool hiddenOnMap(const DepthMap& map, const BoxFootprint& box, std::int64_t& texelsRead, MapDecision* decision = nullptr);

// The largest key of each 8x8 tile of a map that is still being drawn, recomputed only
// where it was drawn since, and only when its old value, still a bound, is not enough:
// the test of an occluder before it is drawn (most are hidden by nearer ones, and a
// near one covers many texels) reads a tile where it can instead of its 64 texels.
// Decides exactly as hiddenOnMap does.
class TileMaxima {
 public:
  explicit TileMaxima(const DepthMap& map);
  // The texels of `box` (all of them if it crosses the near plane) may have changed.
  void invalidate(const BoxFootprint& box);
  bool hidden(const BoxFootprint& box, std::int64_t& texelsRead);

 private:
  static constexpr int kTile = 8;
  float maximum(int tileX, int tileY);
  const DepthMap& map_;
  int columns_, rows_;
  std::vector<float> maxima_;
  std::vector<std::uint8_t> stale_;
};

// The hierarchical-Z pyramid: level 0 is the map, each next level the max of 2x2 texels
// of the one below. At an odd size the last texel of a row or column covers the one
// child left (ceil(n / 2) texels), so every level stays a bound on everything below it.
class Pyramid {
 public:
  explicit Pyramid(const DepthMap& map);
  // The box tested at the finest level where its footprint spans at most 2x2 texels.
  bool hidden(const BoxFootprint& box, std::int64_t& texelsRead, MapDecision* decision = nullptr) const;
  const std::vector<DepthMap>& levels() const { return levels_; }

 private:
  std::vector<DepthMap> levels_;
};

// An occluder face's key as a plane over the map: key(x, y) = k0 + kx x + ky y, in texels.
struct KeyPlane {
  double k0, kx, ky;
};

// A face's key along one row of the map: key(x) = atZero + slope x.
struct RowKey {
  double atZero, slope;
};

// The conservative rule's texels first .. last of a row, the textbook loop: each keeps
// the nearer of what it holds and the farthest of the faces' keys there, rounded up
// (`keys` give each face's key at the corner of the texel where it is largest).
void conservativeRow(float* row, int first, int last, const RowKey* keys, int count);

// A face's key along one row in float, for the center rule: key(x) = atZero + slope x,
// atZero the key at the center of the row's texel 0.
struct CenterRowKey {
  float atZero, slope;
};

// The center rule's texels first .. last of a row, the textbook loop: each keeps the
// nearer of what it holds and the farthest of the faces' keys at its center, in float
// (the rule is approximate anyway, and float is what makes it fast).
void centerRow(float* row, int first, int last, const CenterRowKey* keys, int count);

// Rasterizes occluders into a map, by one rule. Occluders are given in world space.
class OccluderRasterizer {
 public:
  OccluderRasterizer(const MapView& view, Rule rule, DepthMap& map) : view_(view), rule_(rule), map_(map) {}
  // A triangle of an occluder's surface: either side of it hides what lies behind.
  void triangle(const dvec3& a, const dvec3& b, const dvec3& c);
  // A solid box (corner i at bit 0: +x side, bit 1: +y, bit 2: +z of its own axes, as
  // cornersOf gives them or any affine image of those): only its front is drawn.
  void box(const std::array<dvec3, 8>& corners);

  std::int64_t trianglesRasterized = 0, texelsWritten = 0;

 private:
  void triangleInClipSpace(const std::array<ClipVertex, 3>& clip);
  // The texels of a convex polygon (map texels, either winding) by the rule: those whose
  // center it covers, or those wholly inside it; each written with the largest of the
  // planes' keys there (at its center, or over the whole texel).
  void polygon(const dvec2* corners, int count, const KeyPlane* planes, int planeCount);
  bool facesEye(const std::array<dvec3, 8>& corners, int axis, int side) const;

  const MapView& view_;
  Rule rule_;
  DepthMap& map_;
};

}  // namespace hsr::culling::occlusion
