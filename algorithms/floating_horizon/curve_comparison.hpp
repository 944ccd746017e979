// How the floating horizon is judged: a drawing of curves against the exact drawing of
// the same curves (reference.cpp), compared along the curves rather than edge by edge,
// since the two sample the curves differently.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "renderer/lines/line_set.hpp"
#include "renderer/reference/metrics.hpp"

namespace hsr {

// Two drawings of the same curves (both with curvePlaces), sampled differently: the drawn
// one (an algorithm's) against the exact one. They are compared at equal running
// coordinates along each curve, every quarter pixel: a point drawn visible is right when
// the exact drawing shows the curve there within kCurveTolerancePixels of it; a point the
// exact drawing shows is missed unless the drawn one shows it so. A curve drawn through
// the wrong place (a spike cut off by coarse sampling) is then wrongly drawn where it is
// and wrongly hidden where it should be. Lengths in pixels; the picture as lineErrorMap's.
inline constexpr double kCurveTolerancePixels = 0.5;
struct CurveComparison {
  LineError error;
  std::vector<std::uint8_t> errorMap;
};
CurveComparison compareCurveDrawings(const LineSet& drawn, const LineSet& exact, std::span<const EdgeVisibility> exactVisibility);

// Where the exact drawing shows edge `edge` of the drawn one, by the same measure (every
// quarter pixel, the curve within kCurveTolerancePixels at the same coordinate), as
// intervals of the drawn edge's u: what hsr why --edge sets beside the floating horizon's pieces.
EdgeVisibility exactAlongDrawnEdge(const LineSet& drawn, std::uint32_t edge, const LineSet& exact,
                                   std::span<const EdgeVisibility> exactVisibility);

}  // namespace hsr
