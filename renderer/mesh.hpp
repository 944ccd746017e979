// Mesh: indexed triangles, and the procedural primitives scenes are built from.
// Every closed primitive is watertight (shared vertices, each edge in exactly two
// triangles) and wound counter-clockwise seen from outside (conventions.hpp).
#pragma once

#include <string>
#include <vector>

#include "renderer/math.hpp"

namespace hsr {

struct Mesh {
  std::vector<dvec3> positions;     // #V object-space vertex positions
  std::vector<Triangle> triangles;  // #T vertex index triples, counter-clockwise = front
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

// Signed volume (positive for a closed mesh wound counter-clockwise from outside).
double signedVolume(const Mesh& mesh);

}  // namespace hsr
