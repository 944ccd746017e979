// Ray casting (Appel 1968; Roth 1982): visibility decided per pixel in object space. A
// ray leaves the eye through each pixel center, and the nearest surface it meets between
// the near and far planes is the one the pixel shows. Three textbook ways to find it:
//
//   naive  every ray against every triangle: O(pixels x triangles), the baseline.
//   march  step along the ray at a fixed step and ask, at each sample, whether the point
//          is inside an object; the first object entered wins. Cheap per sample, but a
//          step longer than an object is thin skips the object.
//   bvh    the nearest hit through a bounding volume hierarchy (renderer/bvh): ordered
//          traversal, nearer child first, stopping at boxes beyond the nearest hit.
//
// Inputs: a PreparedScene, the knobs. Output: a Frame with, per pixel, the visible
// triangle's id + 1 (0 = background), its distance along the view axis, and the color
// the scene's effects give it (renderer/shading), as every surface algorithm writes it.
#pragma once

#include <cstdint>
#include <string>

#include "renderer/frame.hpp"
#include "renderer/prepare.hpp"
#include "renderer/stats.hpp"

namespace hsr::ray_casting {

enum class Variant { bvh, naive, march };

// The march's step: a length in world units, or a percentage of the diagonal of the
// scene's bounding box.
struct Step {
  double value = 0.5;
  bool percentOfScene = true;
};

inline constexpr int kMaxGrid = 256;  // voxels per side of an occupancy grid: 16 M voxels at most

struct Knobs {
  Variant variant = Variant::bvh;
  // naive and march: refuse when the work a run may do exceeds this: pixels x triangles
  // ray-triangle tests (naive), or pixels x the most samples a ray can take (march).
  double budget = 1e9;
  // march: sample spacing, voxels along each object's longest side for the occupancy
  // grid of meshes, and bisection steps back to the surface once inside.
  Step step;
  int grid = 64;
  int refine = 0;
};

// Why the knobs cannot render this scene ("" when they can): naive or march over budget.
std::string refusal(const PreparedScene& scene, const Knobs& knobs);

// threads: 0 = all cores. The image bits are the same for every thread count.
// Throws InputError when refusal() is not empty.
Frame run(const PreparedScene& scene, const Knobs& knobs, int threads, Stats& stats);

// run's visibility pass alone: ids and depth; the color is left black.
Frame castVisibility(const PreparedScene& scene, const Knobs& knobs, int threads, Stats& stats);

}  // namespace hsr::ray_casting
