// The painter's algorithm, top to bottom: screen geometry, an order, the painting.
#include "algorithms/painter/painter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>
#include <string>

#include "algorithms/painter/bsp.hpp"
#include "algorithms/painter/order.hpp"
#include "renderer/raster/pieces.hpp"
#include "renderer/raster/tiles.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/portable_math.hpp"

namespace hsr::painter {

std::string refusal(const PreparedScene& scene, const Knobs& knobs) {
  const double n = static_cast<double>(scene.triangleCount());
  char text[256];
  if (knobs.variant == Variant::newell) {
    // Newell compares every pair whose depth ranges overlap: up to n(n - 1)/2 of them.
    const double pairs = n * (n - 1) / 2;
    if (pairs <= knobs.budget) return "";
    std::snprintf(text, sizeof text,
                  "newell may test %.3g triangle pairs (%zu triangles), more than --knob budget=%.3g; raise it, or use "
                  "--variant bsp",
                  pairs, scene.triangleCount(), knobs.budget);
    return text;
  }
  if (knobs.variant == Variant::bsp) {
    // Each polygon is classified once per level of a tree about log2(n) deep, and
    // splitting multiplies the polygons by about log2(n) more on curved meshes: the
    // estimate n log2(n)^2 is within a factor of 4 of the counted classifications on the
    // shipped scenes (algorithms/painter/README.md).
    const double levels = portable::log(std::max(2.0, n)) / portable::log(2.0);
    const double work = n * levels * levels;
    if (work <= knobs.buildBudget) return "";
    std::snprintf(text, sizeof text,
                  "building the bsp tree of %zu triangles takes about %.3g plane-side tests, more than --knob "
                  "build-budget=%.3g; raise it (about 10 s per 1e8 on one core)",
                  scene.triangleCount(), work, knobs.buildBudget);
    return text;
  }
  return "";
}

PaintedPieces order(const VisibilityRequest& request, const Knobs& knobs) {
  const PreparedScene& scene = request.scene;
  // Step 1: the screen triangles, clipped at the near and far planes as the reference
  // sees the scene. Sort and Newell order them by their corners.
  PaintedPieces painted{buildScreenTriangles(scene, request.view, {.keepCorners = knobs.variant != Variant::bsp, .submitted = request.triangles},
                                             request.threads, request.stats),
                        {}};
  // Step 2: back to front.
  switch (knobs.variant) {
    case Variant::sort: painted.order = sortOrder(painted.geometry, knobs.key, request.stats); break;
    case Variant::newell: painted.order = newellOrder(scene, painted.geometry, knobs, request.stats, request.steps); break;
    case Variant::bsp: {
      const BspTree tree(scene, knobs, request.stats);
      if (request.steps) {
        constexpr int kLevelsDrawn = 5;
        request.steps->record("step 2: the BSP tree, built once for every eye (its top " + std::to_string(kLevelsDrawn) + " of " +
                                  std::to_string(tree.depth()) + " levels); the walk draws each node's far side, the node, then its near side",
                              graphvizPicture(tree.diagram(scene, request.view, kLevelsDrawn)));
      }
      painted.order = tree.backToFront(scene, painted.geometry, request.stats);
      break;
    }
  }
  return painted;
}

namespace {

// A step: the image so far, the piece just painted tinted red and its triangle outlined.
void recordPiece(const PreparedScene& scene, const PaintedPieces& painted, std::uint32_t index, const Frame& frame,
                 std::span<const std::size_t> piecePixels, StepRecorder& steps,
                 SourceLocation where = SourceLocation::current()) {
  const Piece& piece = painted.order.pieces[index];
  const std::uint32_t triangle = painted.geometry.triangles[piece.screenTriangle].triangle;
  Image picture = surfacePicture(scene, painted.geometry.camera, frame.ids, frame.width, frame.height);
  tint(picture, piecePixels, kHighlight);
  drawWireframe(picture, scene, painted.geometry.camera, std::span(&triangle, 1), kHighlight);
  std::string caption = "step 3: piece " + std::to_string(index + 1) + " of " + std::to_string(painted.order.pieces.size()) +
                        " painted over what is behind it (tinted red; outlined: its triangle, " + scene.triangleName(triangle);
  if (piece.cutCount > 0) caption += ", of which the piece is the part cut out by " + std::to_string(piece.cutCount) + (piece.cutCount == 1 ? " plane" : " planes");
  steps.record(caption + ")", std::move(picture), where);
}

// hsr why: a piece painted at a pixel asked about, over whatever the pixel showed.
void witnessPainting(const PaintedPieces& painted, const PieceFragment& fragment, PixelWitness& why) {
  std::vector<PixelEvent>* history = why.at(fragment.x, fragment.y);
  if (!history) return;
  const Piece& piece = painted.order.pieces[fragment.piece];
  const std::string cut = piece.cutCount == 0 ? "its whole triangle"
                                              : "the part of its triangle cut out by " + std::to_string(piece.cutCount) +
                                                    (piece.cutCount == 1 ? " plane" : " planes");
  history->push_back({fragment.triangle + 1, "painted over what the pixel showed",
                      "piece " + std::to_string(fragment.piece + 1) + " of " + std::to_string(painted.order.pieces.size()) +
                          " in the order, back to front (" + cut + ")",
                      fragment.depth, true, {}});
}

}  // namespace

void paint(const PreparedScene& scene, const PaintedPieces& painted, int threads, Frame& frame, Stats& stats, StepRecorder* steps,
           PixelWitness* why) {
  // With no depth test, a pixel shows whatever was drawn there last.
  PhaseTimer timer(stats, "painting");
  // Steps watch the whole image painted in order: one tile, on one thread.
  const TileGrid tiles(frame.width, frame.height, steps ? std::max(frame.width, frame.height) : TileGrid::kTileSize);
  const std::size_t pieceCount = painted.order.pieces.size();
  std::vector<std::size_t> piecePixels;  // the pixels the piece being painted wrote, for the steps
  std::vector<std::int64_t> writes(tiles.count(), 0);
  const std::int64_t cutTests = paintInOrder(
      scene, painted, tiles, threads,
      [&](std::size_t, const TileGrid::Rect& rect) {
        for (int y = rect.y0; y < rect.y1; ++y) {
          const std::size_t first = std::size_t(y) * std::size_t(frame.width) + std::size_t(rect.x0), count = std::size_t(rect.x1 - rect.x0);
          std::fill_n(frame.ids.begin() + std::ptrdiff_t(first), count, conventions::kBackgroundId);
          std::fill_n(frame.depth.begin() + std::ptrdiff_t(first), count, std::numeric_limits<float>::infinity());
        }
      },
      [&](std::size_t tile, const PieceFragment& fragment) {
        ++writes[tile];
        frame.ids[fragment.pixel] = fragment.triangle + 1;
        frame.depth[fragment.pixel] = fragment.depth;
        if (steps) piecePixels.push_back(fragment.pixel);
        if (why) witnessPainting(painted, fragment, *why);
      },
      [&](std::size_t, std::uint32_t index) {
        if (!steps) return;
        if (steps->due(index, pieceCount)) recordPiece(scene, painted, index, frame, piecePixels, *steps);
        piecePixels.clear();
      });
  std::int64_t written = 0;
  for (const std::int64_t count : writes) written += count;
  stats.add("pieces painted", static_cast<std::int64_t>(painted.order.pieces.size()));
  stats.add("fragments written", written);
  stats.add("cut tests", cutTests);
}

void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility) {
  visibility.painted = order(request, knobs);
  // Step 3: paint the pieces in order, each over what is already there.
  paint(request.scene, *visibility.painted, request.threads, visibility.frame, request.stats, request.steps, request.why);
  visibility.frame.partial = visibility.painted->order.partial;
}

AlgorithmEntry entry() {
  AlgorithmEntry entry;
  entry.name = "painter";
  entry.summary = "far to near with no depth buffer: depth sort, Newell-Newell-Sancha with splitting, or a BSP tree";
  setKnobs(entry, knobTable());
  entry.keyCounters = {"pieces painted", "fragments written", "newell pairs tested", "newell reorders", "newell splits",
                       "bsp nodes", "bsp depth", "bsp splits"};
  entry.studyConfigurations = {{}, {{"variant", "newell"}}, {{"variant", "sort"}}, {{"variant", "sort"}, {"key", "nearest"}}};
  entry.answersWhy = true;
  setRefusal(entry, refusal);
  entry.takesTriangleSubsets = true;
  setVisibility(entry, visibility);
  setOrder(entry, order);
  return entry;
}

}  // namespace hsr::painter
