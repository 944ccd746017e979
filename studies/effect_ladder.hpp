// One scene with each effect added in turn, for the effects study, the README's figure,
// the goldens, the bench and the tests that check an effect adds only its own pass:
// none, flat, lambert, phong, + shadows, + transparency (only when some object is
// transparent; before that step every object is opaque), + fog, + outline. The settings
// of each effect are the scene's own, or the defaults.
#pragma once

#include <string>
#include <vector>

#include "renderer/scene/scene.hpp"

namespace hsr::studies {

struct EffectStep {
  std::string name;  // "none", "flat", ..., "+ shadows", ...
  Scene scene;
};
std::vector<EffectStep> effectLadder(const Scene& scene);

}  // namespace hsr::studies
