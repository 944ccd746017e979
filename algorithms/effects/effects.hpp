// Effects on demand: the passes after a surface algorithm's visibility pass, run only
// when the scene's effects ask for them (scene.hpp: Effects), in this order:
//   shadow maps   one z-buffer pass per light view          effects lists "shadows"
//   shading       one shader call per covered pixel         always (ids -> colors)
//   transparency  the transparent surfaces, back to front   effects lists "transparency"
//   fog           colors blended toward the fog by depth    effects lists "fog"
//   outline       feature edges drawn over the image        effects lists "outline"
// and, inside shading, corner normals only for lambert and phong, specular terms only for
// phong. planPasses says which run and why; each pass times itself in Stats.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "algorithms/effects/shadow_map.hpp"
#include "algorithms/registry.hpp"
#include "renderer/shading.hpp"

namespace hsr::effects {

// The shader of a frame with the light it needs: the shadow maps are rendered here,
// before any surface is shaded, when the scene declares shadows.
class Lighting {
 public:
  Lighting(const PreparedScene& scene, const CameraTransform& camera, int threads, Stats& stats);
  const PixelShader& shader() const { return shader_; }

 private:
  std::optional<ShadowMaps> shadowMaps_;
  PixelShader shader_;
};

// The passes after shading, each only when the scene declares it: fog (phase "fog"),
// then outlines (phase "outline"), each line faded by its own distance.
void applyImageEffects(const PreparedScene& scene, const CameraTransform& camera, Frame& frame, int threads, Stats& stats);

// Shading, then fog and outline, for a frame whose ids and depth a visibility pass filled.
void finishFrame(const PreparedScene& scene, const CameraTransform& camera, Frame& frame, int threads, Stats& stats);

// One step of the plan: a pass and the scene fact that makes it run or not.
struct PlannedPass {
  std::string pass;
  bool runs;
  std::string reason;
};
// What `algorithm` (after the culling stages named in `culling`, "" for none) will do on
// this scene, pass by pass: visibility, culling, the effects' passes and the work inside
// them, each with why.
std::vector<PlannedPass> planPasses(const PreparedScene& scene, const AlgorithmEntry& algorithm, const std::string& culling);

// One scene with each effect added in turn, for the README's figure, the goldens, the
// bench and the tests that check an effect adds only its own pass: none, flat, lambert,
// phong, + shadows, + transparency (only when some object is transparent; before that
// step every object is opaque), + fog, + outline. The settings of each effect are the
// scene's own, or the defaults.
struct EffectStep {
  std::string name;  // "none", "flat", ..., "+ shadows", ...
  Scene scene;
};
std::vector<EffectStep> effectLadder(const Scene& scene);

// The time of each pass of a render that took `totalSeconds`: the effects' passes from
// their phases, and the visibility pass (with geometry and culling) as the rest.
struct PassTime {
  std::string pass;
  double seconds;
};
std::vector<PassTime> passTimes(const Stats& stats, double totalSeconds);

// What the render decided on the way, read from its counters: the work each piece of
// expensive machinery did, or that it did none because the scene did not need it.
std::vector<std::string> decisionsTaken(const Stats& stats);

}  // namespace hsr::effects
