// The floating-horizon algorithm (Williamson 1972; Wright 1973; Rogers, Procedural
// Elements for Computer Graphics, 4-2): hidden lines of a surface y = f(x, z), drawn as
// curves of constant z (and, as a mesh, of constant x too).
//
// Drawn front to back, a curve can only be hidden by curves already drawn, and in one
// screen column the parts already drawn cover everything between the highest and the
// lowest point drawn there. So:
//   1. Order: the curves facing the viewer (the rows) from front to back; with the mesh
//      option, before each row the cross curves' pieces between it and the row in front.
//   2. Sample each curve at `samples` points along it and project them.
//   3. Test: a point is visible when it lies above the upper horizon (the highest point
//      drawn so far in its screen column) or below the lower horizon (the lowest).
//   4. Draw the visible parts: between two samples where visibility changes, the crossing
//      with the horizon is computed (interpolate=on) or the segment is dropped (off: the
//      classic ragged ends).
//   5. Raise the horizons to take in the curve, column by column.
// The horizons are arrays over `columns` screen columns, straight between their centers.
//
// Exact in the limit (fine columns and samples, orthographic view): each screen column
// is then a vertical plane, the surface it cuts is one connected curve, and everything
// in front of a point in that plane has been drawn. What the method does not know: the
// surface between curves (a bump between two curves hides nothing), features narrower
// than the sample spacing (a spike between samples is cut off), and under perspective
// with the camera tilted, the columns are not vertical planes: the error, measured
// against the exact drawing of the same curves (reference.cpp), shows how much.
//
// Input: one height-field object (scenes/README.md), one copy, seen with no roll; under
// perspective the eye must lie outside the footprint, beyond its first curve, so that a
// front-to-back order exists. Undefined heights (NaN) and jumps break curves: nothing
// is drawn across them, and they raise no horizon.
#pragma once

#include <string>
#include <vector>

#include "algorithms/algorithm.hpp"
#include "algorithms/knobs.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::floating_horizon {

struct Knobs {
  // Horizon resolution: screen columns the horizons are kept for; and points sampled
  // along each curve (at least 2). Each a count, or a percentage of the image width.
  KnobNumber columns{100, true};
  KnobNumber samples{100, true};
  bool interpolate = true;   // compute where a segment crosses a horizon (off: drop the segment)
  bool lowerHorizon = true;  // keep the lower horizon too (off: only points above the upper one are seen)
  bool mesh = false;         // draw the curves of constant x as well
};

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table =
      KnobTable<Knobs>()
          .number("columns", &Knobs::columns, {1, 65536, true, true}, {"25%", "50%", "200%"},
                  "horizon resolution: screen columns the horizons are kept for (P%: of the image width)")
          .number("samples", &Knobs::samples, {2, 1048576, true, true}, {"5%", "25%", "200%"},
                  "points sampled along each curve (P%: of the image width)")
          .onOff("interpolate", &Knobs::interpolate, "on: compute where a segment crosses a horizon; off: drop segments whose samples disagree")
          .onOff("lower", &Knobs::lowerHorizon, "on: keep the lower horizon too, so curves seen below everything drawn are visible; off: upper only")
          .onOff("mesh", &Knobs::mesh, "on: draw the curves of constant x as well as of constant z");
  return table;
}

// Why the floating horizon cannot draw this scene, or "" when it can.
std::string refusal(const PreparedScene& scene);

// The drawing: every piece of every curve, visible (QI 0) or hidden (kHidden), with each
// edge's place on its curve (LineSet::curvePlaces). Stats: "curves", "samples",
// "undefined samples", "breaks" (segments not drawn: a jump or a hole between their
// samples), "horizon columns", "horizon crossings", "segments dropped" (interpolate=off).
// `edge`: hsr why --edge's, where what step 3 and 4 met along that segment is recorded
// (where it lies against the horizons at each column center, each horizon it crosses), or null.
LineSet run(const PreparedScene& scene, const Knobs& knobs, Stats& stats, StepRecorder* steps = nullptr, EdgeWitness* edge = nullptr);

// The exact drawing of the same curves (reference.cpp): each curve sampled every
// kReferenceSpacingPixels or finer, on a lattice of the same function whose lines include
// every curve, judged by the exact line reference (renderer/reference/line_reference).
inline constexpr double kReferenceSpacingPixels = 1.0;
struct ExactDrawing {
  LineSet lines;
  std::vector<EdgeVisibility> visibility;  // per edge of lines
};
ExactDrawing exactDrawing(const PreparedScene& scene, bool mesh, int threads, Stats& stats);

// The registry's entry (algorithms/algorithm.hpp): judged against the exact drawing of
// the same curves (curve_comparison.hpp).
AlgorithmEntry entry();

}  // namespace hsr::floating_horizon
