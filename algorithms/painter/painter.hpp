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
// Every variant produces a back-to-front list of pieces of screen triangles, and
// paint.cpp draws that list; with the scene's transparency effect it blends each piece
// over what lies behind it.
//
// Inputs: a PreparedScene, the knobs. Output: a Frame whose ids are the last piece
// painted at each pixel (0 = background), whose depth is that triangle's distance at the
// pixel center, and whose color is shaded as every algorithm shades it (blended, with
// transparency).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/frame.hpp"
#include "renderer/prepare.hpp"
#include "renderer/stats.hpp"
#include "renderer/visible_set.hpp"

namespace hsr::painter {

// Each enum lists its values in the order of the knob's choices in the registry.
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

// threads: 0 = all cores (painting is tile-parallel; the ordering runs on one thread).
// The image bits are the same for every thread count. `visible`: only these triangles
// are painted (what culling stages kept; the BSP tree is still built over all of them,
// once per scene); nullptr: all of them.
Frame run(const PreparedScene& scene, const Knobs& knobs, int threads, Stats& stats, const VisibleSet* visible = nullptr);

}  // namespace hsr::painter
