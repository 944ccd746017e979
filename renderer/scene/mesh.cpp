#include "renderer/scene/mesh.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "renderer/util/error.hpp"
#include "renderer/util/portable_math.hpp"

namespace hsr {
namespace {

constexpr double kPi = std::numbers::pi;

std::uint32_t addVertex(Mesh& mesh, const dvec3& position) {
  mesh.positions.push_back(position);
  return static_cast<std::uint32_t>(mesh.positions.size() - 1);
}

// Quad a-b-c-d counter-clockwise from the front, split along a-c.
void addQuad(Mesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  mesh.triangles.push_back({a, b, c});
  mesh.triangles.push_back({a, c, d});
}

// A ring of `segments` vertices around the y axis at height y. Angle 0 is +z and the
// angle grows toward +x, so consecutive ring vertices run counter-clockwise seen from +y.
std::uint32_t addRing(Mesh& mesh, double radius, double y, int segments) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  for (int s = 0; s < segments; ++s) {
    const double angle = 2 * kPi * s / segments;
    addVertex(mesh, {radius * portable::sin(angle), y, radius * portable::cos(angle)});
  }
  return first;
}

// A fan from `center` to a ring. Seen from +y the ring runs counter-clockwise, so
// a cap facing +y uses the ring's order and a cap facing -y reverses it.
void addCap(Mesh& mesh, std::uint32_t center, std::uint32_t ring, int segments, bool facesUp) {
  for (int s = 0; s < segments; ++s) {
    const std::uint32_t a = ring + s;
    const std::uint32_t b = ring + (s + 1) % segments;
    if (facesUp)
      mesh.triangles.push_back({center, a, b});
    else
      mesh.triangles.push_back({center, b, a});
  }
}

// The side wall between two rings (lower first), facing outward.
void addWall(Mesh& mesh, std::uint32_t lower, std::uint32_t upper, int segments) {
  for (int s = 0; s < segments; ++s) {
    const std::uint32_t next = (s + 1) % segments;
    addQuad(mesh, lower + s, lower + next, upper + next, upper + s);
  }
}


}  // namespace

Mesh makeBox(const dvec3& size) {
  Mesh mesh;
  const dvec3 h = size * 0.5;
  for (int corner = 0; corner < 8; ++corner)
    addVertex(mesh, {corner & 1 ? h.x : -h.x, corner & 2 ? h.y : -h.y, corner & 4 ? h.z : -h.z});
  // Corner index bits: 1 = +x, 2 = +y, 4 = +z. Each face counter-clockwise from outside.
  addQuad(mesh, 0, 4, 6, 2);  // -x
  addQuad(mesh, 1, 3, 7, 5);  // +x
  addQuad(mesh, 0, 1, 5, 4);  // -y
  addQuad(mesh, 2, 6, 7, 3);  // +y
  addQuad(mesh, 0, 2, 3, 1);  // -z
  addQuad(mesh, 4, 5, 7, 6);  // +z
  return mesh;
}

Mesh makeSphere(double radius, int segments, int rings) {
  HSR_CHECK(segments >= 3 && rings >= 2);
  Mesh mesh;
  const std::uint32_t south = addVertex(mesh, {0, -radius, 0});
  std::uint32_t previous = 0;
  for (int r = 1; r < rings; ++r) {
    const double polar = kPi * (1.0 - double(r) / rings);  // from the south pole up
    const std::uint32_t ring = addRing(mesh, radius * portable::sin(polar), radius * portable::cos(polar), segments);
    if (r == 1)
      addCap(mesh, south, ring, segments, false);
    else
      addWall(mesh, previous, ring, segments);
    previous = ring;
  }
  const std::uint32_t north = addVertex(mesh, {0, radius, 0});
  addCap(mesh, north, previous, segments, true);
  return mesh;
}

namespace {

// A capped frustum along y, centered at the origin: a cylinder when the radii are
// equal, a cone when the top radius is 0 (its side is then a fan from the apex).
Mesh makeFrustum(double bottomRadius, double topRadius, double height, int segments) {
  HSR_CHECK(segments >= 3);
  Mesh mesh;
  const std::uint32_t bottomCenter = addVertex(mesh, {0, -height / 2, 0});
  const std::uint32_t topCenter = addVertex(mesh, {0, height / 2, 0});
  const std::uint32_t bottom = addRing(mesh, bottomRadius, -height / 2, segments);
  addCap(mesh, bottomCenter, bottom, segments, false);
  if (topRadius > 0) {
    const std::uint32_t top = addRing(mesh, topRadius, height / 2, segments);
    addWall(mesh, bottom, top, segments);
    addCap(mesh, topCenter, top, segments, true);
  } else {
    addCap(mesh, topCenter, bottom, segments, true);
  }
  return mesh;
}

}  // namespace

Mesh makeCylinder(double radius, double height, int segments) { return makeFrustum(radius, radius, height, segments); }

Mesh makeCone(double radius, double height, int segments) { return makeFrustum(radius, 0, height, segments); }

std::vector<double> evenlySpaced(double extent, int n) {
  std::vector<double> coordinates(std::size_t(n) + 1);
  for (int i = 0; i <= n; ++i) coordinates[std::size_t(i)] = extent * (double(i) / n - 0.5);
  return coordinates;
}

Lattice makeLattice(std::span<const double> us, std::span<const double> vs, const std::function<double(double, double)>& height,
                    const std::function<bool(dvec2, dvec2)>& broken) {
  Lattice lattice;
  Mesh& mesh = lattice.mesh;
  lattice.vertexAt.reserve(us.size() * vs.size());
  for (const double v : vs)
    for (const double u : us) {
      const double h = height(u, v);
      lattice.vertexAt.push_back(std::isnan(h) ? Lattice::kNoVertex : addVertex(mesh, {u, h, v}));
    }
  const auto at = [&](std::size_t i, std::size_t k) { return lattice.vertexAt[k * us.size() + i]; };
  const auto point = [&](std::size_t i, std::size_t k) { return dvec2(us[i], vs[k]); };
  const auto continues = [&](std::size_t i0, std::size_t k0, std::size_t i1, std::size_t k1) {
    return !broken || !broken(point(i0, k0), point(i1, k1));
  };
  // Quads face +y: seen from above, (i, k) -> (i, k+1) -> (i+1, k+1) runs counter-clockwise.
  // Each is split along its (i, k)-(i+1, k+1) diagonal, as addQuad splits.
  for (std::size_t k = 0; k + 1 < vs.size(); ++k)
    for (std::size_t i = 0; i + 1 < us.size(); ++i) {
      const std::uint32_t a = at(i, k), b = at(i, k + 1), c = at(i + 1, k + 1), d = at(i + 1, k);
      const bool diagonal = continues(i, k, i + 1, k + 1);
      if (a != Lattice::kNoVertex && b != Lattice::kNoVertex && c != Lattice::kNoVertex && diagonal &&
          continues(i, k, i, k + 1) && continues(i, k + 1, i + 1, k + 1))
        mesh.triangles.push_back({a, b, c});
      if (a != Lattice::kNoVertex && c != Lattice::kNoVertex && d != Lattice::kNoVertex && diagonal &&
          continues(i + 1, k + 1, i + 1, k) && continues(i, k, i + 1, k))
        mesh.triangles.push_back({a, c, d});
    }
  return lattice;
}

Mesh makeGrid(const dvec2& size, int segmentsX, int segmentsZ) {
  return makeLattice(evenlySpaced(size.x, segmentsX), evenlySpaced(size.y, segmentsZ), [](double, double) { return 0.0; }).mesh;
}

const std::vector<std::string>& heightFunctionNames() {
  static const std::vector<std::string> names = {"ripple", "saddle", "gauss", "bumps", "waves",
                                                 "spike",  "step",   "cliff", "dome",  "holes"};
  return names;
}

double HeightFunction::evaluate(double u, double v) const {
  constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();
  const double r = portable::hypot(u, v) * frequency;
  if (name == "ripple") return amplitude * (r < 1e-9 ? 1.0 : portable::sin(r) / r);  // sinc
  if (name == "saddle") return amplitude * (u * u - v * v) * frequency * frequency;
  if (name == "gauss") return amplitude * portable::exp(-r * r);
  if (name == "bumps") {  // three Gaussian bumps of different heights
    const dvec2 q = frequency * dvec2(u, v);
    const auto bump = [&](dvec2 center, double height) { return height * portable::exp(-glm::dot(q - center, q - center)); };
    return amplitude * (bump({-1.5, -1.0}, 1.0) + bump({1.5, -0.5}, 0.6) + bump({0.0, 1.5}, 0.8));
  }
  if (name == "waves") return amplitude * portable::sin(u * frequency) * portable::cos(v * frequency);
  if (name == "spike") return amplitude / (1.0 + 100.0 * r * r);
  if (name == "step") return u * frequency >= 0 ? amplitude : 0.0;                 // a jump at u = 0
  if (name == "cliff") return amplitude * portable::tanh(u * frequency);          // steep but continuous
  if (name == "dome") return r <= 1 ? amplitude * std::sqrt(1 - r * r) : kUndefined;  // undefined outside r = 1
  if (name == "holes")  // waves, undefined in patches
    return portable::sin(u * frequency) * portable::sin(v * frequency) > 0.5 ? kUndefined
                                                                    : amplitude * portable::sin(u * frequency) * portable::cos(v * frequency);
  HSR_CHECK(false && "height function names are validated when the scene is loaded");
  return 0.0;
}

Mesh makeHeightField(const dvec2& size, int segmentsX, int segmentsZ, const HeightFunction& function) {
  return makeLattice(evenlySpaced(size.x, segmentsX), evenlySpaced(size.y, segmentsZ),
                     [&](double u, double v) { return function.evaluate(u, v); })
      .mesh;
}

double signedVolume(const Mesh& mesh) {
  double volume = 0;
  for (const Triangle& t : mesh.triangles)
    volume += glm::dot(mesh.positions[t[0]], glm::cross(mesh.positions[t[1]], mesh.positions[t[2]]));
  return volume / 6.0;
}

}  // namespace hsr
