#include "studies/effect_ladder.hpp"

#include <algorithm>
#include <utility>

namespace hsr::studies {

std::vector<EffectStep> effectLadder(const Scene& scene) {
  std::vector<EffectStep> ladder;
  Scene step = scene;
  step.effects = Effects{};
  step.effects.shadow = scene.effects.shadow;
  step.effects.fogSettings = scene.effects.fogSettings;
  step.effects.outlineSettings = scene.effects.outlineSettings;
  if (!scene.effects.fog) step.effects.fogSettings = {.end = scene.camera.far, .color = scene.background};
  std::vector<double> opacity;
  for (SceneObject& object : step.objects) opacity.push_back(std::exchange(object.opacity, 1.0));
  const auto add = [&](const std::string& name) { ladder.push_back({name, step}); };
  for (const Shading shading : {Shading::none, Shading::flat, Shading::lambert, Shading::phong}) {
    step.effects.shading = shading;
    add(shadingName(shading));
  }
  step.effects.shadows = true;
  add("+ shadows");
  if (std::any_of(opacity.begin(), opacity.end(), [](double value) { return value < 1; })) {
    step.effects.transparency = true;
    for (std::size_t i = 0; i < opacity.size(); ++i) step.objects[i].opacity = opacity[i];
    add("+ transparency");
  }
  step.effects.fog = true;
  add("+ fog");
  step.effects.outline = true;
  add("+ outline");
  return ladder;
}

}  // namespace hsr::studies
