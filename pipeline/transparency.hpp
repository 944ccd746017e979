// Transparency: surfaces with an object opacity below 1 blended back to front with
// Porter and Duff's "over" (each surface in front of everything drawn so far), two ways,
// depending on how the visibility pass answered:
//   - an algorithm that decided by painting in order (the painter) already has a
//     back-to-front order of every surface: blend them all in that order;
//   - an algorithm that decided by depth (the z-buffer) drew the opaque surfaces only,
//     and shading colored them: blend the transparent ones over that image, in the order
//     of the painter's depth sort (by centroid, farthest first), each only where it lies
//     in front of the opaque depth. Transparent surfaces that overlap in depth cyclically
//     or pass through each other blend in the wrong order somewhere: only the painter's
//     newell and bsp split them.
// Either way each blended fragment is shaded when it is drawn (renderer/shading/shading), and a
// pixel's id and depth end as the nearest surface's.
#pragma once

#include "renderer/image/frame.hpp"
#include "renderer/raster/pieces.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/shading/shading.hpp"
#include "renderer/util/stats.hpp"

namespace hsr::pipeline {

// Phase "transparency": frame.color from every piece of `painted`, blended in its order
// from the background (ids and depth are the painting's already). Counts "blended
// writes" (fragments of a surface below opacity 1) and the shading counters.
void blendInOrder(const PreparedScene& scene, const PaintedPieces& painted, PixelShader<float>& shader, int threads, Frame& frame,
                  Stats& stats);

// Phase "transparency": the pieces of `glass` (the transparent surfaces, back to front)
// blended over frame, an image of the opaque surfaces already shaded, each fragment only
// where it lies in front of their depth; a pixel's id and depth become the nearest
// surface's. Counts "pieces painted", "fragments written", "cut tests" (as the painter
// counts its own), "blended writes" and the shading counters.
void blendOverOpaque(const PreparedScene& scene, const PaintedPieces& glass, PixelShader<float>& shader, int threads, Frame& frame,
                     Stats& stats);

}  // namespace hsr::pipeline
