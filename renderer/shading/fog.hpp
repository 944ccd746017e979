// Fog (depth cueing): each covered pixel's color blended toward the fog color by its view
// distance, so that nearer things stand out; linear between a start and an end distance,
// or exponential with a density (scene.hpp: FogSettings). Counts "fog blends".
#pragma once

#include "renderer/image/frame.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/util/stats.hpp"

namespace hsr {

// The fraction of a surface's color left after fog at view distance d (1 = clear).
double fogClearFraction(const FogSettings& fog, double distance);

// Phase "fog": every pixel that shows a surface, blended by its view distance (frame.distances()). The background
// is already the far end.
void applyFog(const FogSettings& fog, Frame& frame, int threads, Stats& stats);

}  // namespace hsr
