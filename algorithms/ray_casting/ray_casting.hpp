// Ray casting (Appel 1968; Roth 1982): visibility decided per pixel in object space. A
// ray leaves the eye through each pixel center, and the nearest surface it meets between
// the near and far planes is the one the pixel shows. Three textbook ways to find it:
//
//   naive  every ray against every triangle: O(pixels x triangles), the baseline.
//   march  step along the ray at a fixed step and ask, at each sample, whether the point
//          is inside an object; the first object entered wins. Cheap per sample, but a
//          step longer than an object is thin skips the object.
//   bvh    the nearest hit through a bounding volume hierarchy (renderer/rays/bvh): ordered
//          traversal, nearer child first, stopping at boxes beyond the nearest hit.
//
// Inputs: a PreparedScene, a view, the knobs. Output: per pixel, the visible triangle's
// id + 1 (0 = background) and its distance along the view axis.
#pragma once

#include <cstdint>
#include <string>

#include "algorithms/algorithm.hpp"
#include "algorithms/knobs.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::ray_casting {

enum class Variant { bvh, naive, march };

// How the bvh variant runs: a fast path (fast_path.hpp) over the BVH with eight children
// to a node, one ray at a time or eight neighbours at once, or the textbook traversal of
// the binary BVH. The same ids and depths.
enum class Path { simd, packet, scalar };


inline constexpr int kMaxGrid = 256;  // voxels per side of an occupancy grid: 16 M voxels at most

struct Knobs {
  Variant variant = Variant::bvh;
  // naive and march: refuse when the work a run may do exceeds this: pixels x triangles
  // ray-triangle tests (naive), or pixels x the most samples a ray can take (march).
  double budget = 1e9;
  // march: sample spacing (a length in world units, or a percentage of the diagonal of
  // the scene's bounding box), voxels along each object's longest side for the
  // occupancy grid of meshes, and bisection steps back to the surface once inside.
  KnobNumber step{0.5, true};
  int grid = 64;
  int refine = 0;
  Path path = Path::packet;
};

// Why the knobs cannot render this scene ("" when they can): naive or march over budget.
std::string refusal(const PreparedScene& scene, const Knobs& knobs);

inline const KnobTable<Knobs>& knobTable() {
  static const KnobTable<Knobs> table =
      KnobTable<Knobs>()
          .choice("variant", &Knobs::variant, {{Variant::bvh, "bvh"}, {Variant::naive, "naive"}, {Variant::march, "march"}},
                  "bvh: nearest hit through the BVH; naive: every ray against every triangle; march: fixed steps with inside tests")
          .number("budget", &Knobs::budget, {1, 1e15}, {"1e10", "1e11"},
                  "naive and march refuse a run of more ray-triangle tests (naive) or samples (march) than this")
          .onlyFor({"naive", "march"})
          .number("step", &Knobs::step, {1e-6, 1e6, false, true}, {"2%", "1%", "0.25%", "0.1%"},
                  "march: the distance between samples, in world units, or P% of the scene's bounding-box diagonal")
          .onlyFor({"march"})
          .number("grid", &Knobs::grid, {1, kMaxGrid}, {"16", "32", "128", "256"},
                  "march: occupancy-grid voxels along each mesh's longest side")
          .onlyFor({"march"})
          .number("refine", &Knobs::refine, {0, 52}, {"2", "4", "8"}, "march: bisection steps back to the surface once a sample is inside")
          .onlyFor({"march"})
          .choice("path", &Knobs::path, {{Path::packet, "packet"}, {Path::simd, "simd"}, {Path::scalar, "scalar"}},
                  "bvh: packet: eight neighbouring rays together through a BVH of eight children to a node; simd: one "
                  "ray at a time through it, the eight boxes tested at once (fast_path.hpp); both with AVX2 where the "
                  "CPU has it, else the textbook traversal; scalar: the textbook traversal of the binary BVH. The same "
                  "ids and depths")
          .onlyFor({"bvh"});
  return table;
}

// The visibility pass into visibility.frame (ids and depth), from request.view, over
// every triangle. threads: 0 = all cores; the same bits for every count. Throws
// InputError when refusal() is not empty.
void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility);

// The registry's entry (algorithms/algorithm.hpp).
AlgorithmEntry entry();

}  // namespace hsr::ray_casting
