// Judging one id image against the exact reference, pixel by pixel, and saying in words
// what is wrong where it is.
//
// A pixel is right when it shows the reference's triangle; where the reference certifies
// a tie (two or more triangles exactly nearest: coplanar faces, a center on a shared
// edge), when it shows any of the tied triangles. Two more differences are excused, the
// tolerances every shipped algorithm is held to (renderer/reference/agreement.hpp): a
// center within 1/256 pixel of either triangle's outline (where rounding the vertices
// may decide), and two surfaces whose depths there lie within two float32 steps.
// Everything else is wrong, and each wrong pixel gets its cause, a broken convention
// named where one explains it (Cause).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "renderer/reference/reference.hpp"
#include "renderer/scene/prepare.hpp"

namespace hsr::grading {

// Why a pixel is wrong, from what the submission shows there and what the pixel's ray
// meets. In the order feedback lists them.
enum class Cause {
  nothingDrawn,      // the whole image is background: nothing passed the depth test
  crack,             // background at a center on an edge two triangles share: the fill rule
  doubleCovered,     // a shared edge's center shows the triangle the fill rule gives away
  laterTie,          // two triangles exactly as near: the later one kept, where the first keeps it
  nearPlane,         // shows or misses a triangle that crosses the near plane
  fartherWon,        // shows a triangle the ray meets farther than the nearest
  notCovering,       // shows a triangle whose outline does not hold the pixel's center
  cornerSampled,     // ...that would, sampled at the pixel's corner: not its center
  missing,           // background where a triangle is nearest
  beyondFar,         // shows a triangle met beyond the far plane
  unknownId,         // an id that names no triangle of the scene
  // Exercise 1's depth image, at a pixel whose id is right:
  depthIsZ,          // holds the depth buffer's z, not the view distance
  depthWrong,        // holds another distance than the shown triangle's at the center
  backgroundDepth,   // a background pixel holds a distance nearer than the far plane
};
inline constexpr int kCauses = 14;
// A cause's name in feedback, and what a student should check for it (also the line
// judge's causes, grading/line_judge.cpp).
struct CauseText {
  const char* name;
  const char* advice;
};
const char* causeName(Cause cause);
// What a student should check for it, in a sentence.
const char* causeAdvice(Cause cause);

struct CauseCount {
  Cause cause;
  std::int64_t pixels = 0;
  std::string first;  // "pixel (x, y): shows triangle 12 at distance 3.2; the nearest is triangle 9 at 3.1"
  int x = -1, y = -1;  // that first pixel; -1 for nothing drawn, which has none
};

struct Judgement {
  std::int64_t pixels = 0, wrong = 0;
  std::int64_t ties = 0;         // pixels the reference certifies tied
  std::int64_t excused = 0;      // differences within snapping or depth resolution
  std::vector<CauseCount> causes;  // the causes found, most pixels first
  std::vector<std::uint8_t> heatMap;  // RGBA: the reference grey, wrong red, excused yellow, ties blue
  bool passed() const { return wrong == 0; }
};

// `shown`: the submission's ids (triangle id, 0 background), width x height of the
// scene. `conventions`: the answer the suite's rasterization conventions give (the
// z-buffer's ids) on a scene whose vertices the rasterizer places exactly (the fill-rule
// tests), empty on other scenes: there a pixel may show only a triangle the fill rule
// gives its center and that is among the nearest, and with `tieRule`, of several equally
// near the first drawn (the z-buffer's rule; a painter orders coplanar faces its own way).
// The conventions' answer on a scene whose vertices the rasterizer places exactly (an
// orthographic camera with dyadic pixel coordinates, as the fill-rule generator makes):
// at every pixel center, of the triangles the top-left rule gives it, the nearest, and of
// equally near ones the first in the file. Worked out here, apart from every algorithm,
// so that a student edition's own z-buffer is never its judge.
std::vector<std::uint32_t> conventionsAnswer(const PreparedScene& scene);

// `depth`, when not empty (Exercise 1), is the submission's depth image: each pixel's
// view distance, +infinity for the background. Where its id is right, a pixel's distance
// must be the shown triangle's at the center, to within two float32 steps of the
// z-buffer's z, what rounding a vertex to 1/256 pixel moves the triangle's plane by
// there, and a float32 distance's rounding; a background pixel's, the far plane or beyond.
Judgement judge(const PreparedScene& scene, const ReferenceImage& reference, std::span<const std::uint32_t> shown,
                std::span<const std::uint32_t> conventions, bool tieRule = true, std::span<const float> depth = {});

}  // namespace hsr::grading
