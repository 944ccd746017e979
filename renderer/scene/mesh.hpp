// Mesh: indexed triangles, and the procedural primitives scenes are built from.
// Every closed primitive is watertight (shared vertices, each edge in exactly two
// triangles) and wound counter-clockwise seen from outside (conventions.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "renderer/util/math.hpp"

namespace hsr {

struct Mesh {
  std::vector<dvec3> positions;     // #V object-space vertex positions
  std::vector<Triangle> triangles;  // #T vertex index triples, counter-clockwise = front
  // Per triangle, its corners' object-space normals as the file gave them (OBJ vn); empty
  // when the file gave none, and a zero vector for a corner it gave none for.
  std::vector<std::array<dvec3, 3>> cornerNormals;
  // How far each coordinate may lie from the one its source meant: an OBJ file's
  // decimal rounding (obj.cpp: half a unit in the last digit of numbers written with six
  // or more significant digits), in object units. 0 for the procedural primitives, which
  // are computed in double: their own rounding (an ulp or two of sin and cos) lies within
  // the placement's rounding bound (Instance::placementRounding).
  double statedRounding = 0;
};

// Axis-aligned box centered at the origin with the given edge lengths: 12 triangles.
Mesh makeBox(const dvec3& size);
// UV sphere of `segments` around the y axis and `rings` from pole to pole.
Mesh makeSphere(double radius, int segments, int rings);
// Capped cylinder along y, centered at the origin.
Mesh makeCylinder(double radius, double height, int segments);
// Capped cone along y: base at -height/2, apex at +height/2.
Mesh makeCone(double radius, double height, int segments);
// Flat grid in the xz plane at y = 0, facing +y, centered at the origin.
Mesh makeGrid(const dvec2& size, int segmentsX, int segmentsZ);

// The named height functions h(u, v) a height-field object may use (u, v in the
// object's xz plane, h along +y; "z = f(x, y)" of the textbooks with the height up).
struct HeightFunction {
  std::string name;
  double amplitude = 1.0;
  double frequency = 1.0;
  double evaluate(double u, double v) const;
};
const std::vector<std::string>& heightFunctionNames();
Mesh makeHeightField(const dvec2& size, int segmentsX, int segmentsZ, const HeightFunction& function);

// n + 1 evenly spaced coordinates across an extent centered at 0: a grid's lines.
std::vector<double> evenlySpaced(double extent, int n);

// A height field over the lattice us x vs (each ascending): lattice point (i, k) is the
// vertex (us[i], height(us[i], vs[k]), vs[k]), rows of constant v one after the other,
// and each cell is two triangles facing +y, split as the grid's. Where the height is
// undefined (NaN) there is no vertex (vertexAt holds kNoVertex), and a triangle is left
// out when it would use such a vertex or when `broken` says the surface does not continue
// along one of its sides (a jump): the surface has a hole there, not a wall to nowhere.
struct Lattice {
  static constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();
  Mesh mesh;
  std::vector<std::uint32_t> vertexAt;  // per lattice point, row by row
};
Lattice makeLattice(std::span<const double> us, std::span<const double> vs, const std::function<double(double, double)>& height,
                    const std::function<bool(dvec2, dvec2)>& broken = nullptr);

// Signed volume (positive for a closed mesh wound counter-clockwise from outside).
double signedVolume(const Mesh& mesh);

}  // namespace hsr
