// A scanline z-buffer written apart from hsr: one row of float32 depth at a time (hsr's
// scanline variant keeps a row too, but this one keeps no active edge list: each row
// tests the triangles whose rows it lies in, found from a table of first rows). Depth
// is float32 z in [0, 1] as OpenGL stores it: f (d - n) / (d (f - n)) under perspective,
// decoded back to the view distance d for the depth image as each row is done.
//   scanline SCENE.tri IDS.png DEPTH.pfm
#include <algorithm>
#include <cmath>
#include <limits>

#include "../common/triangle_file.hpp"

namespace {

struct Clip {
  double x, y, d, w;
};
struct Corner {
  double x, y, d;  // pixel coordinates, and the distance along the view axis
};
struct ScreenTriangle {
  Corner v[3];
  double area;
  std::uint32_t id;
  int firstRow, lastRow;
};

Clip lerp(const Clip& a, const Clip& b, double s) { return {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), a.d + s * (b.d - a.d), a.w + s * (b.w - a.w)}; }

// Sutherland-Hodgman against near <= d (keep = +1) or d <= far (keep = -1).
std::vector<Clip> clipped(const std::vector<Clip>& polygon, double plane, double keep) {
  std::vector<Clip> out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Clip &a = polygon[i], &b = polygon[(i + 1) % polygon.size()];
    const double da = keep * (a.d - plane), db = keep * (b.d - plane);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(lerp(a, b, da / (da - db)));
  }
  return out;
}

bool topLeft(const Corner& a, const Corner& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  return (dy == 0 && dx > 0) || dy < 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: scanline SCENE.tri IDS.png DEPTH.pfm\n");
    return 2;
  }
  const variant::TriangleFile scene = variant::readTriangleFile(argv[1]);
  const int width = scene.width, height = scene.height;
  const double n = scene.near, f = scene.far;

  // Geometry: each triangle to clip space, clipped, fanned into screen triangles.
  std::vector<ScreenTriangle> triangles;
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    std::vector<Clip> polygon;
    for (const variant::Vec3& p : scene.triangles[t]) {
      double c[4];
      for (int r = 0; r < 4; ++r)
        c[r] = scene.clipFromWorld[r][0] * p[0] + scene.clipFromWorld[r][1] * p[1] + scene.clipFromWorld[r][2] * p[2] + scene.clipFromWorld[r][3];
      polygon.push_back({c[0], c[1], c[2], c[3]});
    }
    polygon = clipped(clipped(polygon, n, 1), f, -1);
    std::vector<Corner> corners;
    for (const Clip& c : polygon) corners.push_back({(c.x / c.w * 0.5 + 0.5) * width, (0.5 - c.y / c.w * 0.5) * height, c.d});
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
      ScreenTriangle tri{{corners[0], corners[k], corners[k + 1]}, 0, std::uint32_t(t + 1), 0, 0};
      tri.area = (tri.v[1].x - tri.v[0].x) * (tri.v[2].y - tri.v[0].y) - (tri.v[1].y - tri.v[0].y) * (tri.v[2].x - tri.v[0].x);
      if (tri.area == 0) continue;
      if (tri.area < 0) {  // clockwise on screen, y down
        std::swap(tri.v[1], tri.v[2]);
        tri.area = -tri.area;
      }
      const double top = std::min({tri.v[0].y, tri.v[1].y, tri.v[2].y}), bottom = std::max({tri.v[0].y, tri.v[1].y, tri.v[2].y});
      tri.firstRow = std::max(0, int(std::ceil(top - 0.5)));
      tri.lastRow = std::min(height - 1, int(std::floor(bottom - 0.5)));
      if (tri.firstRow <= tri.lastRow) triangles.push_back(tri);
    }
  }
  // The table of first rows: triangles by the row they start on, in submission order.
  std::vector<std::vector<std::size_t>> startingOn(static_cast<std::size_t>(height));
  for (std::size_t k = 0; k < triangles.size(); ++k) startingOn[std::size_t(triangles[k].firstRow)].push_back(k);

  std::vector<std::uint32_t> ids(std::size_t(width) * std::size_t(height), 0);
  std::vector<float> depth(static_cast<std::size_t>(width));
  std::vector<float> distances(std::size_t(width) * std::size_t(height), std::numeric_limits<float>::infinity());
  std::vector<std::size_t> active;
  for (int y = 0; y < height; ++y) {
    active.insert(active.end(), startingOn[std::size_t(y)].begin(), startingOn[std::size_t(y)].end());
    std::erase_if(active, [&](std::size_t k) { return triangles[k].lastRow < y; });
    std::sort(active.begin(), active.end());  // submission order: ties keep the first drawn
    std::fill(depth.begin(), depth.end(), 1.0f);
    const double cy = y + 0.5;
    for (const std::size_t k : active) {
      const ScreenTriangle& tri = triangles[k];
      const double left = std::min({tri.v[0].x, tri.v[1].x, tri.v[2].x}), right = std::max({tri.v[0].x, tri.v[1].x, tri.v[2].x});
      for (int x = std::max(0, int(std::ceil(left - 0.5))); x <= std::min(width - 1, int(std::floor(right - 0.5))); ++x) {
        const double cx = x + 0.5;
        double weight[3];
        bool inside = true;
        for (int e = 0; e < 3 && inside; ++e) {
          const Corner &a = tri.v[(e + 1) % 3], &b = tri.v[(e + 2) % 3];
          const double value = (b.x - a.x) * (cy - a.y) - (b.y - a.y) * (cx - a.x);
          inside = value > 0 || (value == 0 && topLeft(a, b));
          weight[e] = value / tri.area;
        }
        if (!inside) continue;
        const double d = scene.perspective ? 1 / (weight[0] / tri.v[0].d + weight[1] / tri.v[1].d + weight[2] / tri.v[2].d)
                                           : weight[0] * tri.v[0].d + weight[1] * tri.v[1].d + weight[2] * tri.v[2].d;
        const float z = float(scene.perspective ? f * (d - n) / (d * (f - n)) : (d - n) / (f - n));
        if (z < depth[std::size_t(x)]) {
          depth[std::size_t(x)] = z;
          ids[std::size_t(y) * std::size_t(width) + std::size_t(x)] = tri.id;
        }
      }
    }
    for (int x = 0; x < width; ++x) {
      const double z = depth[std::size_t(x)];
      if (ids[std::size_t(y) * std::size_t(width) + std::size_t(x)] != 0)
        distances[std::size_t(y) * std::size_t(width) + std::size_t(x)] = float(scene.perspective ? f * n / (f - z * (f - n)) : n + z * (f - n));
    }
  }
  variant::writeIdPng(argv[2], width, height, ids);
  variant::writeDepthPfm(argv[3], width, height, distances);
  return 0;
}
