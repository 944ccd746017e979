// What the walkthrough studies share (occlusion-queries, indoor): a culling method
// walking a level on a simulated GPU (renderer/simulated_gpu.hpp), so that methods that
// cull on the CPU and methods that ask the GPU are timed on one timeline; a frame's row
// judged against the exact reference; and the spread of a column of frame times.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "algorithms/algorithm.hpp"
#include "algorithms/culling/culling.hpp"
#include "renderer/simulated_gpu.hpp"
#include "studies/results.hpp"

namespace hsr::studies {

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
  std::int64_t triangles = 0, objects = 0, queries = 0, wasted = 0, late = 0, falseCulls = 0;
};

// One frame of `walk` at the scene's camera: its culling stages, then (unless its last
// stage drew as it went) a draw per object kept, on the walk's GPU. `seen`: per object,
// whether the exact reference shows it now; `seenBefore`: at the frame before. Counts
// objects late (seen, not drawn, and not drawn since they came into view) and false
// culls (seen, not drawn, though drawn earlier in the same spell of being seen).
FrameRow walkFrame(const PreparedScene& scene, const std::vector<std::uint8_t>& seen, const std::vector<std::uint8_t>& seenBefore,
                   MethodWalk& walk, int threads);

// Mean, variance and the 5th and 95th percentiles of a column of values (not empty).
struct Spread {
  double mean, variance, p5, p95;
};
Spread spreadOf(std::vector<double> values);

// {"a": "x", "b": 1.5}: a row as a JSON object, its first `textFields` values quoted.
std::string jsonObjectOf(const CsvRow& row, std::size_t textFields);

}  // namespace hsr::studies
