// Occlusion queries: ask the GPU how many pixels of a box would pass the depth test
// against what is drawn so far, and skip what lies in the box when none would. The
// GPU is simulated (algorithms/culling/occlusion/simulated_gpu.hpp), and its answers come back late: the
// four strategies differ in what they do meanwhile. All walk a hierarchy of the objects
// (hierarchy.hpp) nearest first, and a node found hidden culls everything below it.
//
//   stop-and-wait  each node in the view volume queried, its answer waited for, and
//                  opened (a leaf: drawn) only if visible. Never wrong; but the CPU waits
//                  for every answer and the GPU for every next command.
//   delayed        no waiting: each leaf in the view volume drawn unless its newest answer
//                  in says hidden, then every such leaf queried against this frame's
//                  drawing, for a later frame. An object coming into view behind what
//                  hid it appears exactly `latency` frames late.
//   chc            Coherent Hierarchical Culling (Bittner, Wimmer, Piringer and
//                  Purgathofer 2004). Visibility changes little from frame to frame, so
//                  the leaves visible last frame are drawn at once (and queried, for the
//                  next frame), and inner nodes visible last frame are opened without a
//                  query; only nodes hidden last frame are queried before anything below
//                  them is drawn. Their answers are taken as they come in, between steps
//                  of the traversal; it waits only when it has nothing else to do. A node
//                  found visible passes its visibility up to its ancestors, so that next
//                  frame they are opened unasked.
//   chcpp          CHC++ (Mattausch, Bittner and Wimmer 2008): CHC with fewer queries and
//                  fewer waits. Nodes hidden last frame are queried in batches of `batch`;
//                  those likely to stay hidden share one query (a multiquery: if it comes
//                  back visible, each is asked again alone). A leaf visible last frame
//                  goes unqueried for `assume-visible` frames (the first wait drawn at
//                  random, so that leaves seen together are not all queried together), and
//                  its query waits in a queue for a moment when the CPU would otherwise
//                  wait. Tight bounds: a node is queried by its children's or objects'
//                  boxes where those cover less than its own.
//
// Every box is queried grown by 1/16 of a pixel (queries.cpp, kMarginPixels), so that the
// rasterizer's snapping of its outline, or a face resting on a surface already drawn,
// cannot hide an object the exact reference sees. A box that, grown, reaches in front of
// the near plane (the eye in it or at it) is visible without a query: a GPU clips the
// box open there and would count too few fragments.
//
// With threshold 0, stop-and-wait, chc and chcpp draw every object the finished depth
// buffer shows: a node is culled only when no fragment of its box passes against what is
// already drawn, and what is drawn only grows. delayed and a threshold above 0 trade that
// away for speed: the studies count the objects they show late.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "algorithms/culling/culling.hpp"
#include "algorithms/culling/occlusion/hierarchy.hpp"
#include "algorithms/culling/occlusion/occlusion.hpp"
#include "algorithms/culling/occlusion/simulated_gpu.hpp"

namespace hsr::culling::occlusion {

// What the query methods carry from frame to frame: the hierarchy, and for each node
// what the last frames decided about it.
struct QueryMemory : StageMemory {
  struct Node {
    bool visible = false;              // the node's classification after the last frame that visited it
    std::int64_t lastVisited = -2;     // that frame
    std::int64_t nextQuery = 0;        // chcpp: the frame a visible leaf is queried again
    int framesHidden = 0;              // chcpp: answers in a row that said hidden
    bool answered = false;             // delayed: some answer is in since the leaf came into view
    std::deque<PendingQuery> inFlight; // delayed: the leaf's queries, oldest first
  };
  const PreparedScene* scene = nullptr;
  std::optional<ObjectHierarchy> hierarchy;
  std::vector<Node> nodes;
  std::int64_t frame = -1;
};

// The stage's queries variant: the triangles of `in` of the objects it drew. `memory`:
// the stage's slot in a walk (null: a single frame, from nothing). `gpu`: the walk's
// simulated GPU, its frame already begun (null: one of its own, whose clocks go to stats
// as phases "queries: frame", "queries: waiting", "queries: cpu busy", "queries: gpu
// busy"). Counts "queries: nodes visited", "queries: issued" (GPU queries, a multiquery
// once), "queries: nodes queried", "queries: answered visible" (a query that spared
// nothing: wasted), "queries: stalls" (answers read before they were in), "queries:
// multiqueries", "queries: multiqueries re-asked", "queries: boxes at the eye",
// "queries: objects drawn", and the GPU's work for it: "queries: boxes queried", "box
// fragments tested", "box fragments passed", "triangles drawn", "fragments written".
// `why`: hsr why's objects, for each what was last decided on the way down to it (its
// query's count of passed fragments, a multiquery's, visible last frame, outside the view
// volume) at its leaf or at the node above it where the walk stopped; null: not asked.
VisibleSet cullWithQueries(const PreparedScene& scene, const CameraTransform& camera, const Knobs& knobs, const VisibleSet& in,
                           std::unique_ptr<StageMemory>* memory, SimulatedGpu* gpu, Stats& stats, StageWitness* why = nullptr);

}  // namespace hsr::culling::occlusion
