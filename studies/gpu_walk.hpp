// What the walkthrough studies share (occlusion-queries, indoor): a culling method
// walking a level on a simulated GPU (algorithms/culling/occlusion/simulated_gpu.hpp), so that methods that
// cull on the CPU and methods that ask the GPU are timed on one timeline; a frame's row
// judged against the exact reference; and the spread of a column of frame times.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "algorithms/algorithm.hpp"
#include "algorithms/culling/culling.hpp"
#include "algorithms/culling/occlusion/simulated_gpu.hpp"
#include "studies/results.hpp"

namespace hsr::studies {

// A method of a study: its name in tables and plots, and its culling pipeline (--cull).
struct Method {
  std::string name, cull;
};

// One method walking one stretch of a level: what it carries from frame to frame.
struct MethodWalk {
  culling::Pipeline pipeline;
  // The variant of the pipeline's last stage: "queries" draws as it goes; "previous-frame"
  // reads the frame before.
  bool lastStageIs(const std::string& variant) const { return !pipeline.empty() && pipeline.back().variant() == variant; }
  std::vector<std::unique_ptr<culling::StageMemory>> memory;
  SimulatedGpu gpu;
  Visibility last;  // previous-frame: the frame before, drawn by the z-buffer
  Camera lastCamera;
  bool hasLast = false;
  std::vector<std::uint8_t> drawnInSpell;  // per object: drawn since it last came into view
};

// One frame of one method.
struct FrameRow {
  std::string level, method;
  int segment = 0, frame = 0;
  double ms = 0, waitingMs = 0;
  std::int64_t triangles = 0, objects = 0, queries = 0, multiqueries = 0, wasted = 0, late = 0, falseCulls = 0;
};

// One frame of `walk` at the scene's camera: its culling stages, then (unless its last
// stage drew as it went) a draw per object kept, on the walk's GPU. `seen`: per object,
// whether the exact reference shows it now; `seenBefore`: at the frame before. Counts
// objects late (seen, not drawn, and not drawn since they came into view) and false
// culls (seen, not drawn, though drawn earlier in the same spell of being seen).
FrameRow walkFrame(const PreparedScene& scene, const std::vector<std::uint8_t>& seen, const std::vector<std::uint8_t>& seenBefore,
                   MethodWalk& walk, int threads);

// One position of a walk at the scene's camera: the exact reference's verdict, then a
// frame of each method (walkFrame), taken in an order rotated by `position` so that each
// method comes in each place of the order in turn; rows labelled with the level, method
// and position. `seenBefore`: what the reference showed at the position before, updated.
std::vector<FrameRow> walkPosition(const PreparedScene& scene, const std::string& level, const std::vector<Method>& methods,
                                   std::vector<MethodWalk>& walks, std::vector<std::uint8_t>& seenBefore, int position, int threads);

// Mean, variance and the 5th and 95th percentiles of a column of values (not empty).
struct Spread {
  double mean, variance, p5, p95;
};
Spread spreadOf(std::vector<double> values);

// The frame-time plot of a walkthrough study (`study` names it in the title): a group of
// bars per level, a bar per method with its 5th to 95th percentiles. `table` is a data
// block named $table, a row per level: its name, then mean, p5 and p95 per method.
// `shown`: every frame time, for the axis.
std::string levelTimesPlot(const std::string& study, const std::string& table, const std::vector<std::string>& methods,
                           const std::vector<double>& shown);

// {"a": "x", "b": 1.5}: a row as a JSON object, its first `textFields` values quoted.
std::string jsonObjectOf(const CsvRow& row, std::size_t textFields);

}  // namespace hsr::studies
