// Shading an antialiasing algorithm's answer (Visibility::coverage, the A-buffer's):
// each pixel's colour is its surfaces' colours weighted by their shares, the rest the
// background's.
#pragma once

#include "algorithms/algorithm.hpp"
#include "renderer/shading/shading.hpp"

namespace hsr::pipeline {

// Phase "shading": every surface a pixel shares is set up and shaded once, at the pixel's
// center (as the A-buffer shades a fragment once), and the shares are summed in double
// precision, then quantized. Rows in parallel: the same bits for any thread count.
void shadeCoverage(const PreparedScene& scene, const PixelCoverage& coverage, PixelShader<float>& shader, int threads, Frame& frame,
                   Stats& stats);

}  // namespace hsr::pipeline
