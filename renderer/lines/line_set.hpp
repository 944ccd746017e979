// A line drawing: the feature edges of one view, each cut into pieces with how many
// surfaces hide each piece. Every hidden-line algorithm (Roberts, Appel, the floating
// horizon) produces one; the line reference (renderer/reference/line_reference) judges it and
// renderer/lines/line_drawing draws it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "renderer/lines/feature_edges.hpp"

namespace hsr {

// Per feature edge, the parts drawn as visible, as sub-intervals of the edge's parameter
// range [0, 1], and the edge's projected length in pixels: what the line error compares
// (renderer/reference/metrics.hpp).
struct Interval {
  double begin, end;
};
struct EdgeVisibility {
  double lengthPixels = 0;
  std::vector<Interval> visible;  // sorted, disjoint
};

// One piece of an edge's projection, [begin, end] in its parameter u, with how many
// front-facing surfaces hide it: 0 is visible. An algorithm that only knows "hidden"
// (Roberts) reports kHidden.
struct LineSegment {
  static constexpr int kHidden = -1;
  std::uint32_t edge;
  double begin, end;
  int qi;
  bool visible() const { return qi == 0; }
};

// Where an edge of a drawing of curves lies: on curve `curve`, from running coordinate
// `from` to `to` (from < to; the 3D parameter s is linear in it). Two drawings of the same
// curves sampled differently are compared at equal coordinates
// (algorithms/floating_horizon/curve_comparison).
struct CurvePlace {
  std::uint32_t curve;
  double from, to;
};

struct LineSet {
  int width = 0, height = 0;
  std::vector<FeatureEdge> edges;
  // Pieces covering every edge's [0, 1] with no gap, edge by edge, in increasing u.
  std::vector<LineSegment> segments;
  // A drawing of curves (the floating horizon's): one per edge. Empty otherwise.
  std::vector<CurvePlace> curvePlaces;
  // Why the drawing may be wrong somewhere, when the algorithm knows it may be ("" when
  // it is exact wherever its method is); hsr render prints it as a warning.
  std::string partial;
};

// Per edge, its projected length and its visible sub-intervals merged (the line error's
// input).
std::vector<EdgeVisibility> edgeVisibility(const LineSet& lines);

// The drawing of `edges`' edges as `visibility` (one per edge) says: a reference's answer
// as a LineSet, to draw like any other (its hidden parts kHidden).
LineSet drawingOf(const LineSet& edges, std::span<const EdgeVisibility> visibility);

// Appends edge `edge`'s pieces covering [0, 1]: the visible parts (sorted, disjoint) with QI
// 0, the parts between them kHidden.
void appendPieces(LineSet& lines, std::uint32_t edge, std::span<const Interval> visible);

}  // namespace hsr
