// Variant march: fixed-step ray marching with point-inside tests (see march.cpp).
#pragma once

#include "algorithms/ray_casting/cast.hpp"
#include "algorithms/ray_casting/ray_casting.hpp"
#include "renderer/geometry/camera.hpp"

namespace hsr::ray_casting {

// The march's step in world units for this scene.
double marchStepLength(const PreparedScene& scene, const KnobNumber& step);

// The most samples one ray can take: the march box's diagonal over the step, plus one.
double marchSamplesPerRay(const PreparedScene& scene, const KnobNumber& step);

// Fills frame.ids and frame.depth; leaves frame.color alone. With a recording, records
// rows as castRays does (cast.hpp); with hsr why's pixels, their samples.
void march(const PreparedScene& scene, const Knobs& knobs, const CameraTransform& camera, int threads, Frame& frame,
           Stats& stats, const Recording* recording = nullptr, PixelWitness* why = nullptr);

}  // namespace hsr::ray_casting
