// Judging a line drawing against the exact line reference, stretch by stretch, and saying
// in words what is wrong where it is (Exercise 5: hidden lines).
//
// The lines a drawing must hold are those of the view: the scene's feature edges
// (contours, creases sharper than 30 degrees, boundaries: renderer/lines/feature_edges.hpp)
// and the lines where surfaces pass through each other (renderer/scene/intersections.hpp),
// each where the line reference (renderer/reference/line_reference.hpp) finds it visible.
// Worked out here from the shared core, apart from every line algorithm, so that a
// student's own Appel is never its judge.
//
// A submission hands in visible segments in pixel coordinates. They are compared with
// the reference's pieces in the image: a segment covers whatever part of a piece lies on
// its line (both ends within kOnLine pixels of it), so pieces may be split or joined any
// way. A stretch left over, drawn but not visible in the reference or visible but not
// drawn, is wrong when it is longer than kExcusedLength (the rounding of a crossing's
// position in the submission's decimals); shorter ones are excused.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "renderer/util/math.hpp"
#include "renderer/scene/prepare.hpp"

namespace hsr::grading {

inline constexpr double kOnLine = 0.01;        // pixels across a line that still lie on it
inline constexpr double kExcusedLength = 0.05;  // pixels along a line: a stretch this short is rounding

// One visible segment as a submission draws it, in pixels: x to the right and y down
// from the image's top-left corner (a pixel's center at +0.5, as the id images').
struct DrawnSegment {
  dvec2 from, to;
};
// A drawing holds at most this many segments: the judge compares each with each of the
// view's lines (100,000 random segments on the bunny: 0.6 s), and the shipped scenes'
// drawings hold a few hundred.
inline constexpr std::size_t kMostSegments = 100'000;
// Reads a drawing: a line per segment, "x0 y0 x1 y1"; blank lines and lines starting
// with '#' are skipped. Returns "" or what is wrong, naming the line.
std::string readSegments(const std::filesystem::path& file, std::vector<DrawnSegment>& segments);

// Why a stretch is wrong. In the order feedback lists them.
enum class LineCause {
  drawnThoughHidden,  // on a line of the view where the reference hides it: a QI too low
  hiddenThoughVisible,  // a visible line left out: a QI too high, or an edge not drawn
  notALine,           // on no line of the view: an edge that is not a feature edge
};
inline constexpr int kLineCauses = 3;
const char* lineCauseName(LineCause cause);
const char* lineCauseAdvice(LineCause cause);

struct LineCauseLength {
  LineCause cause;
  double pixels = 0;     // the length of its stretches
  std::string first;     // "at (120.5, 33.0), on edge 14 (a contour)"
  dvec2 at{-1, -1};      // the middle of its longest stretch
};

struct DrawingJudgement {
  double visibleLength = 0;  // the reference's visible line, in pixels
  double wrong = 0;          // the length of the wrong stretches
  double excused = 0;        // the length of stretches within kExcusedLength
  std::vector<LineCauseLength> causes;  // the causes found, longest first
  std::vector<std::uint8_t> heatMap;    // RGBA: the reference's visible lines grey, its hidden ones faint, wrong stretches red
  bool passed() const { return wrong == 0; }
};

// The scene must lie beyond the near plane (the line reference's assumption).
DrawingJudgement judgeDrawing(const PreparedScene& scene, std::span<const DrawnSegment> drawn, int threads);

}  // namespace hsr::grading
