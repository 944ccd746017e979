// A ray caster written apart from hsr: a ray through every pixel center, the nearest
// triangle it meets between the near and far planes found through a BVH of its own.
//   raycast SCENE.tri IDS.png [--bvh median|sah] [--ties lowest|highest]
// median: each node split at the median centroid on its longest axis; sah: the surface
// area heuristic over 12 bins. At an exact tie (two triangles at one distance, as on a
// shared edge) the lowest or the highest id wins: the reference certifies either.
// Moller-Trumbore in double, its barycentric bounds widened by 1e-9 so that a ray
// through an edge two triangles share meets at least one of them (rounding could let
// it slip between).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

#include "../common/triangle_file.hpp"

namespace {

using variant::Vec3;
Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 operator*(double s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
Vec3 normalized(const Vec3& a) { return (1 / std::sqrt(dot(a, a))) * a; }

struct Box {
  Vec3 low{HUGE_VAL, HUGE_VAL, HUGE_VAL}, high{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  void grow(const Vec3& p) {
    for (int k = 0; k < 3; ++k) low[k] = std::min(low[k], p[k]), high[k] = std::max(high[k], p[k]);
  }
  void grow(const Box& b) { grow(b.low), grow(b.high); }
  double area() const {
    const Vec3 e = high - low;
    return e[0] < 0 ? 0 : 2 * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
  }
};

struct Node {
  Box box;
  int left = -1, right = -1;  // children, or -1 for a leaf
  std::size_t first = 0, count = 0;
};

class Bvh {
 public:
  Bvh(const std::vector<std::array<Vec3, 3>>& triangles, bool sah) : triangles_(triangles), sah_(sah) {
    order_.resize(triangles.size());
    std::iota(order_.begin(), order_.end(), 0);
    for (const auto& t : triangles) {
      Box b;
      for (const Vec3& p : t) b.grow(p);
      boxes_.push_back(b);
      centers_.push_back(0.5 * (b.low + b.high));
    }
    if (!triangles.empty()) build(0, triangles.size());
  }
  const std::vector<Node>& nodes() const { return nodes_; }
  std::size_t triangle(std::size_t k) const { return order_[k]; }

 private:
  int build(std::size_t first, std::size_t count) {
    const int index = int(nodes_.size());
    nodes_.push_back({});
    Box box, centers;
    for (std::size_t k = first; k < first + count; ++k) box.grow(boxes_[order_[k]]), centers.grow(centers_[order_[k]]);
    nodes_[std::size_t(index)].box = box;
    const Vec3 extent = centers.high - centers.low;
    const int axis = extent[0] >= extent[1] && extent[0] >= extent[2] ? 0 : extent[1] >= extent[2] ? 1 : 2;
    std::size_t split = count / 2;
    if (count <= 4 || extent[std::size_t(axis)] <= 0) {
      nodes_[std::size_t(index)].first = first;
      nodes_[std::size_t(index)].count = count;
      return index;
    }
    const auto by = [&](std::size_t a, std::size_t b) { return centers_[a][std::size_t(axis)] < centers_[b][std::size_t(axis)]; };
    std::sort(order_.begin() + long(first), order_.begin() + long(first + count), by);
    if (sah_) split = sahSplit(first, count);
    const int left = build(first, split), right = build(first + split, count - split);
    nodes_[std::size_t(index)].left = left;
    nodes_[std::size_t(index)].right = right;
    return index;
  }
  // The cheapest of 12 cuts along the sorted order, by area times count on each side.
  std::size_t sahSplit(std::size_t first, std::size_t count) const {
    std::size_t best = count / 2;
    double bestCost = HUGE_VAL;
    for (int bin = 1; bin < 12; ++bin) {
      const std::size_t cut = std::max<std::size_t>(1, std::min(count - 1, count * std::size_t(bin) / 12));
      Box left, right;
      for (std::size_t k = first; k < first + cut; ++k) left.grow(boxes_[order_[k]]);
      for (std::size_t k = first + cut; k < first + count; ++k) right.grow(boxes_[order_[k]]);
      const double cost = left.area() * double(cut) + right.area() * double(count - cut);
      if (cost < bestCost) bestCost = cost, best = cut;
    }
    return best;
  }
  const std::vector<std::array<Vec3, 3>>& triangles_;
  bool sah_;
  std::vector<std::size_t> order_;
  std::vector<Box> boxes_;
  std::vector<Vec3> centers_;
  std::vector<Node> nodes_;
};

// Where the ray enters the box (slab test), or +infinity when it misses it before `beyond`.
double entry(const Box& box, const Vec3& origin, const Vec3& inverse, double beyond) {
  double near = 0, far = beyond;
  for (int k = 0; k < 3; ++k) {
    double a = (box.low[std::size_t(k)] - origin[std::size_t(k)]) * inverse[std::size_t(k)];
    double b = (box.high[std::size_t(k)] - origin[std::size_t(k)]) * inverse[std::size_t(k)];
    if (std::isnan(a) || std::isnan(b)) a = -HUGE_VAL, b = HUGE_VAL;  // a zero direction inside the slab
    if (a > b) std::swap(a, b);
    near = std::max(near, a), far = std::min(far, b * (1 + 4e-16));
  }
  return near <= far ? near : HUGE_VAL;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: raycast SCENE.tri IDS.png [--bvh median|sah] [--ties lowest|highest]\n");
    return 2;
  }
  bool sah = false, highest = false;
  for (int k = 3; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--bvh")) sah = !std::strcmp(argv[k + 1], "sah");
    if (!std::strcmp(argv[k], "--ties")) highest = !std::strcmp(argv[k + 1], "highest");
  }
  const variant::TriangleFile scene = variant::readTriangleFile(argv[1]);
  const Bvh bvh(scene.triangles, sah);
  const Vec3 forward = normalized(scene.target - scene.eye), right = normalized(cross(forward, scene.up)), up = cross(right, forward);
  const double aspect = double(scene.width) / scene.height;
  const double halfHeight = scene.perspective ? std::tan(scene.fovY * M_PI / 360) : scene.orthoHeight / 2;

  std::vector<std::uint32_t> ids(std::size_t(scene.width) * std::size_t(scene.height), 0);
  std::vector<int> stack;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      const double across = (2 * (x + 0.5) / scene.width - 1) * halfHeight * aspect, upward = (1 - 2 * (y + 0.5) / scene.height) * halfHeight;
      const Vec3 offset = across * right + upward * up;
      const Vec3 origin = scene.perspective ? scene.eye : scene.eye + offset;
      const Vec3 direction = scene.perspective ? forward + offset : forward;
      const Vec3 inverse = {1 / direction[0], 1 / direction[1], 1 / direction[2]};
      // t along this direction is the distance along the view axis divided by dot(direction, forward).
      const double scale = dot(direction, forward);
      double best = scene.far / scale * (1 + 1e-12);
      std::uint32_t id = 0;
      stack.assign(1, 0);
      while (!bvh.nodes().empty() && !stack.empty()) {
        const Node& node = bvh.nodes()[std::size_t(stack.back())];
        stack.pop_back();
        if (entry(node.box, origin, inverse, best) == HUGE_VAL) continue;
        if (node.left >= 0) {
          stack.push_back(node.left);
          stack.push_back(node.right);
          continue;
        }
        for (std::size_t k = node.first; k < node.first + node.count; ++k) {
          const std::size_t t = bvh.triangle(k);
          const auto& [a, b, c] = scene.triangles[t];
          const Vec3 e1 = b - a, e2 = c - a, p = cross(direction, e2);
          const double det = dot(e1, p);
          if (det == 0) continue;
          const Vec3 s = origin - a, q = cross(s, e1);
          const double u = dot(s, p) / det, v = dot(direction, q) / det, along = dot(e2, q) / det;
          constexpr double kWiden = 1e-9;
          if (u < -kWiden || v < -kWiden || u + v > 1 + kWiden) continue;
          const double distance = along * scale;
          if (distance < scene.near || distance > scene.far) continue;
          const std::uint32_t candidate = std::uint32_t(t + 1);
          if (along < best || (along == best && (highest ? candidate > id : candidate < id))) {
            best = along;
            id = candidate;
          }
        }
      }
      ids[std::size_t(y) * std::size_t(scene.width) + std::size_t(x)] = id;
    }
  variant::writeIdPng(argv[2], scene.width, scene.height, ids);
  return 0;
}
