// The painter's algorithm: draw surfaces from far to near, each over what is already
// there, with no depth buffer. Whether the image is right depends only on the order.
//
// Three ways to find the order, from wrong to always right:
//   sort    one depth key per triangle (sort.cpp): wrong wherever triangles overlap in
//           depth and the key orders them the wrong way at some pixel, and wherever
//           they interpenetrate.
//   newell  Newell, Newell and Sancha (1972) (newell.cpp): sort by the farthest depth,
//           then prove or repair the order of every pair that overlaps in depth with five
//           tests of increasing cost, and split a polygon by the other's plane when no
//           order exists (cycles, interpenetration).
//   bsp     Fuchs, Kedem and Naylor (1980) (bsp.cpp): a binary space partitioning tree
//           of the triangles' planes, built once for the scene in world space; for any
//           eye, visiting it far side first gives a correct order.
//
// Every variant produces a back-to-front list of pieces of screen triangles
// (renderer/raster/pieces), which the last step paints. The pipeline's transparency pass blends
// the scene's transparent surfaces in that same order.
//
// Inputs: a PreparedScene, a view, the knobs. Output: per pixel, the id of the last
// piece painted there (0 = background) and that triangle's distance at the pixel center;
// and the order itself.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "algorithms/algorithm.hpp"
#include "algorithms/knobs.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/scene/visible_set.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::painter {

enum class Variant { bsp, newell, sort };
enum class SortKey { centroid, nearest, farthest };
enum class Splitter { leastSplits, first, random };

struct Knobs {
  Variant variant = Variant::bsp;
  SortKey key = SortKey::centroid;  // sort: which depth of a triangle orders it
  double splitCap = 100000;         // newell: no more splits than this (the image is then labelled partial)
  double splitLimit = 1e7;          // bsp: no more splits than this (the build then stops with an error)
  double budget = 1e9;              // newell: refuses scenes with more triangle pairs than this
  double buildBudget = 1e8;         // bsp: refuses scenes whose build is estimated above this many plane-side tests
  Splitter splitter = Splitter::leastSplits;  // bsp: how each node's plane is chosen
  std::uint64_t seed = 1;           // bsp: the random choices of `random` and `least-splits`
  int candidates = 8;               // bsp least-splits: planes tried per node
};

// Why the painter cannot render this scene with these knobs, or "" when it can.
std::string refusal(const PreparedScene& scene, const Knobs& knobs);

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table =
      KnobTable<Knobs>()
          .choice("variant", &Knobs::variant, {{Variant::bsp, "bsp"}, {Variant::newell, "newell"}, {Variant::sort, "sort"}},
                  "bsp: BSP tree built once, walked far side first; newell: sort, then prove or repair each overlapping pair, "
                  "splitting cycles; sort: one depth key per triangle (wrong where triangles overlap in depth)")
          .choice("key", &Knobs::key, {{SortKey::centroid, "centroid"}, {SortKey::nearest, "nearest"}, {SortKey::farthest, "farthest"}},
                  "sort: the depth that orders a triangle: its centroid's, its nearest corner's or its farthest corner's")
          .onlyFor({"sort"})
          .number("split-cap", &Knobs::splitCap, {0, 1e9, true}, {"0", "10", "1000"},
                  "newell: the most splits; past it, conflicts are painted unresolved and the image is labelled partial")
          .onlyFor({"newell"})
          .number("split-limit", &Knobs::splitLimit, {0, 1e9, true}, {"1e5", "1e6", "1e8"},
                  "bsp: the most splits the build may make (each keeps a polygon, about 100 bytes); past it, it stops with an error")
          .onlyFor({"bsp"})
          .number("budget", &Knobs::budget, {1, 1e15}, {"1e10", "1e11"}, "newell: refuses scenes with more triangle pairs n(n-1)/2 than this")
          .onlyFor({"newell"})
          .number("build-budget", &Knobs::buildBudget, {1, 1e15}, {"1e9", "1e10"},
                  "bsp: refuses scenes whose tree build is estimated (n log2(n)^2) above this many plane-side tests")
          .onlyFor({"bsp"})
          .choice("splitter", &Knobs::splitter,
                  {{Splitter::leastSplits, "least-splits"}, {Splitter::first, "first"}, {Splitter::random, "random"}},
                  "bsp: each node's plane: the first triangle's, a random one's, or the fewest splits among candidates")
          .onlyFor({"bsp"})
          .number("seed", &Knobs::seed, {0, 9007199254740992.0}, {"2", "3"}, "bsp: seed of the random choices of random and least-splits")
          .onlyFor({"bsp"})
          .number("candidates", &Knobs::candidates, {1, 1024}, {"1", "2", "4", "16", "32"}, "bsp least-splits: planes tried per node")
          .onlyFor({"bsp"});
  return table;
}

// Steps 1 and 2: the requested triangles as screen triangles, clipped at the near and far
// planes as the reference sees the scene, and their pieces back to front.
PaintedPieces order(const VisibilityRequest& request, const Knobs& knobs);

// Step 3: the pieces painted in order into `frame` (ids and depth), each over what is
// already there. Stats: "pieces painted", "fragments written", "cut tests"; phase "painting".
// With `why`, every fragment painted at a pixel asked about is recorded there.
void paint(const PreparedScene& scene, const PaintedPieces& painted, int threads, Frame& frame, Stats& stats,
           StepRecorder* steps = nullptr, PixelWitness* why = nullptr);

// The whole algorithm: the order, then step 3, painting it into visibility.frame (ids and
// depth; the frame is labelled partial when the order is known to be wrong somewhere).
// threads: 0 = all cores (painting is tile-parallel; the ordering runs on one thread);
// the same bits for every count. With request.triangles (what culling stages kept) only
// those are painted; the BSP tree is still built over all of them, once per scene.
void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility);

// The registry's entry (algorithms/algorithm.hpp).
AlgorithmEntry entry();

}  // namespace hsr::painter
