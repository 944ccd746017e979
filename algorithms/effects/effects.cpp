#include "algorithms/effects/effects.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "renderer/fog.hpp"
#include "renderer/outline.hpp"

namespace hsr::effects {

Lighting::Lighting(const PreparedScene& scene, const CameraTransform& camera, int threads, Stats& stats)
    : shadowMaps_(scene.scene().effects.shadows ? std::make_optional<ShadowMaps>(scene, scene.scene().effects.shadow, threads, stats)
                                                : std::nullopt),
      shader_(scene, camera, stats, shadowMaps_ ? &*shadowMaps_ : nullptr) {}

void applyImageEffects(const PreparedScene& scene, const CameraTransform& camera, Frame& frame, int threads, Stats& stats) {
  const Effects& effects = scene.scene().effects;
  if (effects.fog) applyFog(effects.fogSettings, frame, threads, stats);
  if (effects.outline) drawOutline(scene, camera, effects.outlineSettings, effects.fog ? &effects.fogSettings : nullptr, frame, stats);
}

void finishFrame(const PreparedScene& scene, const CameraTransform& camera, Frame& frame, int threads, Stats& stats) {
  const Lighting lighting(scene, camera, threads, stats);
  shadeFrame(scene, frame, lighting.shader(), threads, stats);
  applyImageEffects(scene, camera, frame, threads, stats);
}

namespace {

std::string count(std::size_t n, const std::string& what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); }

std::string formatted(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

}  // namespace

std::vector<PlannedPass> planPasses(const PreparedScene& scene, const AlgorithmEntry& algorithm, const std::string& culling) {
  const Scene& description = scene.scene();
  const Effects& effects = description.effects;
  const std::string listed = "effects lists ";
  std::vector<PlannedPass> plan;
  plan.push_back({"visibility: " + algorithm.name, true,
                  std::to_string(scene.width()) + "x" + std::to_string(scene.height()) + " pixels, " +
                      count(scene.triangleCount(), "triangle")});
  plan.push_back({"culling", !culling.empty(), culling.empty() ? "no --cull stages given" : "--cull " + culling});
  if (algorithm.kind == "line") {
    plan.push_back({"shading and effects", false, algorithm.name + " draws lines: a line drawing has no surfaces to shade"});
    return plan;
  }

  std::size_t views = 0;
  for (const Light& light : description.lights) views += std::size_t(shadowViewCount(light));
  if (!effects.shadows) {
    plan.push_back({"shadow maps", false, "effects does not list shadows"});
  } else {
    for (const Light& light : description.lights) {
      char size[64];
      std::snprintf(size, sizeof size, "%s of %dx%d, bias %g texels", shadowViewCount(light) == 1 ? "1 view" : "6 views (a cube)",
                    effects.shadow.resolution, effects.shadow.resolution, effects.shadow.biasTexels);
      plan.push_back({"shadow map for light '" + light.name + "'", true, listed + "shadows; " + size});
    }
  }

  char ambient[48];
  std::snprintf(ambient, sizeof ambient, ", ambient %g", description.ambient);
  plan.push_back({"shading: " + std::string(shadingName(effects.shading)), true,
                  effects.lit() ? count(description.lights.size(), "light") + ambient : "no lit effect: each object's own color"});
  plan.push_back({"corner normals", effects.smoothNormals(),
                  effects.smoothNormals() ? std::string(shadingName(effects.shading)) + " interpolates them"
                  : effects.lit()         ? "flat shading uses face normals"
                                          : "no lit effect"});
  plan.push_back({"specular highlights", effects.shading == Shading::phong,
                  effects.shading == Shading::phong ? listed + "phong" : "effects does not list phong"});
  plan.push_back({"shadow lookups", effects.shadows,
                  effects.shadows ? "per lit pixel and light facing it, " + count(views, "map view") : "effects does not list shadows"});

  std::size_t transparentObjects = 0;
  for (const SceneObject& object : description.objects) transparentObjects += object.opacity < 1;
  if (!effects.transparency)
    plan.push_back({"transparency", false, "effects does not list transparency: nothing is sorted for blending"});
  else
    plan.push_back({"transparency", true,
                    listed + "transparency; " + count(transparentObjects, "object") + " below opacity 1, blended back to front by " +
                        (algorithm.name == "painter" ? "the painter's own order" : "the sorted pass over the opaque depth")});
  if (!effects.fog) {
    plan.push_back({"fog", false, "effects does not list fog"});
  } else {
    char what[96];
    if (effects.fogSettings.kind == FogSettings::Kind::linear)
      std::snprintf(what, sizeof what, "linear from %g to %g", effects.fogSettings.start, effects.fogSettings.end);
    else
      std::snprintf(what, sizeof what, "exponential, density %g", effects.fogSettings.density);
    plan.push_back({"fog", true, listed + "fog; " + what});
  }
  char crease[64];
  std::snprintf(crease, sizeof crease, "; creases sharper than %g degrees", effects.outlineSettings.creaseDegrees);
  plan.push_back({"outline", effects.outline, effects.outline ? listed + "outline" + crease : "effects does not list outline"});
  return plan;
}

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

std::vector<PassTime> passTimes(const Stats& stats, double totalSeconds) {
  const std::vector<PassTime> effectPasses = {
      {"shadow maps", stats.seconds("shadow maps")},
      {"shading", stats.seconds("shading") + stats.seconds("normals")},
      {"transparency", stats.seconds("transparency")},
      {"fog", stats.seconds("fog")},
      {"outline", stats.seconds("outline")},
  };
  double effectsTotal = 0;
  for (const PassTime& pass : effectPasses) effectsTotal += pass.seconds;
  std::vector<PassTime> times = {{"visibility", std::max(0.0, totalSeconds - effectsTotal)}};
  for (const PassTime& pass : effectPasses)
    if (pass.seconds > 0) times.push_back(pass);
  return times;
}

std::vector<std::string> decisionsTaken(const Stats& stats) {
  std::vector<std::string> decisions;
  const auto counted = [&](const char* name) { return stats.counter(name); };
  const auto say = [&](bool ran, const std::string& yes, const std::string& no) { decisions.push_back(ran ? yes : no); };
  const auto n = [](std::int64_t value) { return std::to_string(value); };
  if (counted("triangles in") > 0)
    say(counted("triangles clipped") > 0,
        "clipping: " + n(counted("triangles clipped")) + " triangles cross the near plane or the guard band, and only they were clipped",
        "clipping: no triangle crosses the near plane or the guard band (every vertex's outcode checked first): nothing clipped");
  if (counted("newell pairs tested") > 0)
    say(counted("newell splits") > 0, "Newell: " + n(counted("newell splits")) + " splits, each where a cycle was found",
        "Newell: no cycle found among " + n(counted("newell pairs tested")) + " overlapping pairs: nothing split");
  if (counted("bsp nodes") > 0) decisions.push_back("BSP: " + n(counted("bsp splits")) + " splits while building " + n(counted("bsp nodes")) + " nodes");
  if (counted("reference rays") > 0)
    say(counted("reference exact fall-backs") > 0,
        "exact fall-back: " + n(counted("reference exact fall-backs")) + " of " + n(counted("reference rays")) +
            " rays where the double-precision filter could not decide",
        "exact fall-back: none; the double-precision filter decided every ray");
  if (counted("predicate evaluations") > 0)
    decisions.push_back("exact predicates: " + n(counted("predicate exact fall-backs")) + " of " + n(counted("predicate evaluations")) +
                        " evaluations fell back to exact arithmetic");
  if (counted("occlusion: estimated depth complexity x100") > 0 || counted("occlusion: skipped, below min-depth-complexity") > 0) {
    const std::string estimate = formatted(double(counted("occlusion: estimated depth complexity x100")) / 100);
    say(counted("occlusion: skipped, below min-depth-complexity") == 0,
        "occlusion culling: the objects' boxes cover the view " + estimate + " times over, at least min-depth-complexity: it runs",
        "occlusion culling: skipped; the objects' boxes cover the view only " + estimate + " times over, below min-depth-complexity");
  }
  if (counted("occlusion: occludees tested") > 0)
    decisions.push_back("occlusion culling: " + n(counted("occlusion: occluders rasterized")) + " occluders drawn, " +
                        n(counted("occlusion: occludees culled")) + " of " + n(counted("occlusion: occludees tested")) + " objects culled");
  say(counted("normals computed") > 0, "normals: " + n(counted("normals computed")) + " corner normals computed",
      "normals: none computed");
  if (counted("shadow maps rendered") > 0)
    decisions.push_back("shadows: " + count(std::size_t(counted("shadow maps rendered")), "map view") + ", " +
                        n(counted("shadow lookups")) + " lookups, " + n(counted("shadowed lookups")) + " in shadow");
  if (counted("specular terms") > 0) decisions.push_back("specular: " + n(counted("specular terms")) + " highlight terms");
  if (counted("blended writes") > 0) decisions.push_back("transparency: " + n(counted("blended writes")) + " blended writes");
  if (counted("fog blends") > 0) decisions.push_back("fog: " + n(counted("fog blends")) + " pixels blended");
  if (counted("outline edges") > 0)
    decisions.push_back("outline: " + n(counted("outline edges")) + " feature edges, " + n(counted("outline pixels")) + " pixels drawn");
  return decisions;
}

}  // namespace hsr::effects
