// The hidden tests' scenes: each hard case as a generator that makes a new scene from a
// seed, so that a submission cannot be tuned to the shipped scenes. The same seed gives
// the same scene, bit for bit, on every machine: the numbers come from a counter-based
// generator (splitmix64) and portable sine and cosine, never from the standard library's
// distributions, whose results differ between implementations.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/scene/scene.hpp"

namespace hsr::grading {

struct SceneGenerator {
  const char* skill;  // the hard case, as a submission's implemented.txt names it
  const char* what;   // a line for the feedback
  Scene (*make)(std::uint64_t seed);
  // The rasterizer places this generator's vertices exactly (an orthographic camera
  // whose pixel coordinates are dyadic): the conventions decide every pixel.
  bool pixelExact = false;
  // A line exercise's scene too (Exercise 5): every object a closed solid in front of
  // the near plane (Appel's quantitative invisibility counts the faces of closed solids).
  bool forLines = false;
};

// One per hard case: visibility, orthographic, fill-rule, near-plane, far-from-origin,
// coplanar, slivers, interpenetrating, cycles, far-plane, occlusion.
const std::vector<SceneGenerator>& sceneGenerators();

}  // namespace hsr::grading
