// What an algorithm module is, to the registry (algorithms/registry.hpp) and the
// pipeline (pipeline/pipeline.hpp) that run it: a name, its knobs, and its answer to
// the visibility question, and nothing else. Shading, transparency, fog and outlines
// are the pipeline's passes, the same for every algorithm; an algorithm never calls
// another (the build gives each folder only renderer/ and this interface to include).
//
// Each algorithm folder defines its entry as `AlgorithmEntry <namespace>::entry()`, and
// its CMakeLists.txt names the folder to hsr_algorithm(); the build lists the entries
// (algorithms/CMakeLists.txt), so adding an algorithm edits nothing outside its folder
// but that one line.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "algorithms/knobs.hpp"
#include "renderer/geometry/camera.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/image/polygon_svg.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/raster/coverage.hpp"
#include "renderer/raster/depth.hpp"
#include "renderer/raster/pieces.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/scene/visible_set.hpp"
#include "renderer/steps/steps.hpp"
#include "renderer/steps/why.hpp"
#include "renderer/util/stats.hpp"

namespace hsr {

// What an algorithm answers.
enum class AlgorithmKind {
  surface,    // which triangle each pixel shows, and at what depth
  line,       // a line drawing: the visible parts of the feature edges
  reference,  // the exact reference: exact visibility and exact effects, the whole image
};
const char* algorithmKindName(AlgorithmKind kind);  // "surface", "line", "reference"

// The visibility question: the scene seen from a view, over some of its triangles.
struct VisibilityRequest {
  const PreparedScene& scene;
  const CameraTransform& view;   // the scene's camera, or a light's for a shadow map
  const VisibleSet* triangles;   // only these (what culling kept, or the opaque ones); nullptr: all
  int threads;                   // 0 = all cores; the answer is the same bits for any count
  Stats& stats;
  StepRecorder* steps = nullptr;  // where the algorithm records its steps; null: not asked (renderer/steps/steps.hpp)
  PixelWitness* why = nullptr;    // hsr why's pixels, where it records their histories; null: not asked (renderer/steps/why.hpp)
};

// A surface algorithm's answer, written into a frame of the view's size (which a caller
// may reuse from one request to the next): frame.ids and frame.depth for every pixel
// (frame.color is left to the shading passes; the z-buffer's full frame leaves its depth
// undecoded, for frame.distances() to decode when a stage reads it), frame.partial when the algorithm knows
// its answer may be wrong somewhere, and, from an algorithm that decides by painting in
// order (the painter), the order it painted, for the transparency pass to blend in;
// from an algorithm that decides in object space (Weiler-Atherton), the visible
// polygons themselves, which hsr render can draw as SVG; from an antialiasing algorithm
// (the A-buffer), each pixel's surfaces and their shares of it, which the shading pass
// blends (renderer/raster/coverage.hpp; frame.ids then names the surface with the largest share).
struct Visibility {
  Frame frame;
  std::optional<PaintedPieces> painted;
  std::vector<VisiblePolygon> polygons = {};
  std::optional<PixelCoverage> coverage = {};
};

// A line drawing judged against the exact one: its line error, where it is wrong
// (renderer/lines/line_errors: lineErrorMap's colours), and the exact drawing it was judged by.
struct LineJudgement {
  LineError error;
  std::vector<std::uint8_t> errorMap;
  LineSet exact;
};

struct AlgorithmEntry {
  std::string name;
  AlgorithmKind kind = AlgorithmKind::surface;
  std::string summary;
  std::vector<KnobSpec> knobs;  // as `hsr list` prints them
  // The settings checked and typed by the entry's knob table (algorithms/knobs.hpp).
  std::function<KnobValues(const KnobSettings&, const std::string& where)> resolve;
  // The counters hsr compare prints for this algorithm, in this order.
  std::vector<std::string> keyCounters;
  // The configurations hsr compare's default study runs (the defaults first), chosen to
  // show what the knobs trade.
  std::vector<KnobSettings> studyConfigurations = {{}};
  // Why the algorithm cannot answer for the scene at its size with these knobs, or ""
  // when it can; the message names the knob to change when there is one.
  std::function<std::string(const PreparedScene&, const KnobValues&)> refusal = [](const PreparedScene&, const KnobValues&) {
    return std::string();
  };

  // Surface algorithms.
  std::function<void(const VisibilityRequest&, const KnobValues&, Visibility&)> visibility;
  // It answers with visible polygons too (Visibility::polygons): hsr render -o out.svg draws them.
  bool drawsPolygons = false;
  // It blends transparent surfaces itself (Visibility::coverage): it sees every triangle,
  // and no transparency pass follows it.
  bool resolvesTransparency = false;
  // It can leave triangles out (request.triangles): culling stages may run before it,
  // and the transparency pass can ask it for the opaque surfaces alone.
  bool takesTriangleSubsets = false;
  // It records the history of the pixels hsr why asks about (VisibilityRequest::why).
  bool answersWhy = false;
  // Every decision its loops can record about what is not a triangle (Warnock's windows;
  // for a line algorithm, Roberts' bodies along an edge), as an event's outcome begins,
  // before its first ": ". The browser edition's quiz offers them all when it asks what
  // the loop decided; empty: it offers those taken at the pixel.
  std::vector<std::string> whyDecisions;
  // It decides with a depth buffer: the format its knobs chose (what a tie is a tie of:
  // hsr render's note on depth ties, and its advice).
  std::function<DepthFormat(const KnobValues&)> depthFormat;
  // List-priority algorithms: the requested triangles' screen pieces, back to front.
  std::function<PaintedPieces(const VisibilityRequest&, const KnobValues&)> order;

  // Line algorithms: the drawing, and how it is judged.
  // steps: where it records its steps, or null (renderer/steps/steps.hpp).
  std::function<LineSet(const PreparedScene&, const KnobValues&, int threads, Stats&, StepRecorder* steps)> drawLines;
  std::function<LineJudgement(const PreparedScene&, const KnobValues&, const LineSet&, int threads, Stats&)> judgeLines;
  // Line algorithms that answer hsr why --edge: the same drawing, with what the walk met
  // along edge witness.edge recorded (renderer/steps/why.hpp); null for the others.
  std::function<LineSet(const PreparedScene&, const KnobValues&, Stats&, EdgeWitness&)> drawLinesWatchingEdge;
  // Where the exact drawing (LineJudgement::exact) shows edge `edge` of the drawing, in
  // its u, for an algorithm whose exact drawing has other edges (the floating horizon's
  // curves, sampled finer); null: the exact drawing's edges are the drawing's own.
  std::function<EdgeVisibility(const LineSet& drawing, std::uint32_t edge, const LineSet& exact)> exactAlongEdge;

  // The reference: its whole image, visibility and effects both exact.
  std::function<Frame(const PreparedScene&, int threads, Stats&)> renderExactly;
};

// The help of the knob every mesh line algorithm has: which edges are drawn besides
// contours and boundaries.
inline constexpr const char* kCreaseKnobHelp =
    "feature edges: draw the edges whose two faces' normals differ by more than this many degrees";

// A line drawing judged by the exact line reference of its own edges
// (renderer/reference/line_reference): what Roberts and Appel are judged by (judgeLines).
LineJudgement judgedByLineReference(const PreparedScene& scene, const KnobValues& knobs, const LineSet& lines, int threads,
                                    Stats& stats);

// An entry's knob table hooked up: its specs for listing, and resolve.
template <typename Knobs>
void setKnobs(AlgorithmEntry& entry, const KnobTable<Knobs>& table) {
  entry.knobs = table.specs();
  entry.resolve = [table, owner = entry.name](const KnobSettings& settings, const std::string& where) {
    return table.resolve(owner, settings, where);
  };
}

// An entry's functions given as the algorithm's own, which take its Knobs struct: the
// entry hands each the struct its knob table made.
template <typename Knobs>
void setVisibility(AlgorithmEntry& entry, void (*visibility)(const VisibilityRequest&, const Knobs&, Visibility&)) {
  entry.visibility = [visibility](const VisibilityRequest& request, const KnobValues& knobs, Visibility& answer) {
    answer.frame.leaveUndecoded({});  // a reused frame's depth left undecoded by an earlier pass is not this one's
    visibility(request, knobs.as<Knobs>(), answer);
  };
}
template <typename Knobs>
void setOrder(AlgorithmEntry& entry, PaintedPieces (*order)(const VisibilityRequest&, const Knobs&)) {
  entry.order = [order](const VisibilityRequest& request, const KnobValues& knobs) { return order(request, knobs.as<Knobs>()); };
}
// A line algorithm's drawing: drawLines, and drawLinesWatchingEdge the same run with
// hsr why --edge's witness handed in.
template <typename Knobs>
void setDrawing(AlgorithmEntry& entry, LineSet (*draw)(const PreparedScene&, const Knobs&, Stats&, StepRecorder*, EdgeWitness*)) {
  entry.drawLines = [draw](const PreparedScene& scene, const KnobValues& knobs, int, Stats& stats, StepRecorder* steps) {
    return draw(scene, knobs.as<Knobs>(), stats, steps, nullptr);
  };
  entry.drawLinesWatchingEdge = [draw](const PreparedScene& scene, const KnobValues& knobs, Stats& stats, EdgeWitness& edge) {
    return draw(scene, knobs.as<Knobs>(), stats, nullptr, &edge);
  };
}
template <typename Knobs>
void setRefusal(AlgorithmEntry& entry, std::string (*refusal)(const PreparedScene&, const Knobs&)) {
  entry.refusal = [refusal](const PreparedScene& scene, const KnobValues& knobs) { return refusal(scene, knobs.as<Knobs>()); };
}
// A refusal that depends on the scene alone.
void setRefusal(AlgorithmEntry& entry, std::string (*refusal)(const PreparedScene&));

}  // namespace hsr
