#include "pipeline/pipeline.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <optional>

#include "algorithms/painter/painter.hpp"
#include "algorithms/registry.hpp"
#include "pipeline/coverage.hpp"
#include "pipeline/shadow_maps.hpp"
#include "pipeline/transparency.hpp"
#include "renderer/lines/line_drawing.hpp"
#include "renderer/shading/fog.hpp"
#include "renderer/shading/outline.hpp"
#include "renderer/shading/shading.hpp"
#include "renderer/steps/steps.hpp"
#include "renderer/util/error.hpp"

namespace hsr::pipeline {
namespace {

// The order the transparency pass blends transparent surfaces in when the visibility
// pass found no order of its own: the painter's depth sort by centroid.
const painter::Knobs kTransparencySort{.variant = painter::Variant::sort, .key = painter::SortKey::centroid};

std::string count(std::size_t n, const std::string& what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); }

// What a render carries from pass to pass.
struct Context {
  const PreparedScene& scene;
  const CameraTransform camera;  // the scene's, for the whole render
  const Configuration& configuration;
  int threads;
  Stats& stats;
  const culling::PreviousFrame* previous;
  StepRecorder* steps;             // null unless steps were asked for
  std::optional<VisibleSet> kept;  // what the culling stages kept
  Visibility& visibility;          // the frame, and the painter's order
  LineSet drawing = {};
  std::optional<ShadowMaps> shadowMaps = {};
  std::optional<PixelShader<float>> shader = {};  // built by the first pass that shades
  PixelWitness* why = nullptr;                     // hsr why's pixels; null unless asked
  culling::CullingWitness* culled = nullptr;       // each culling stage's kept set and findings, for hsr why; null unless asked

  PixelShader<float>& pixelShader() {
    if (!shader) shader.emplace(scene, camera, shadowMaps ? &*shadowMaps : nullptr);
    return *shader;
  }
};

// The facts about a configuration that decide the passes.
struct Facts {
  const PreparedScene& scene;
  const Configuration& configuration;
  const AlgorithmEntry& algorithm = *configuration.algorithm;
  const Effects& effects = scene.scene().effects;
  bool surface = algorithm.kind == AlgorithmKind::surface;
  bool lines = algorithm.kind == AlgorithmKind::line;
  // The visibility pass answers with an order of its own, which transparency blends in.
  bool paintsInOrder = surface && algorithm.order != nullptr;
  // The visibility pass blends transparent surfaces itself (the A-buffer).
  bool blendsItself = surface && algorithm.resolvesTransparency;
  // The visibility pass sees the opaque surfaces only; transparency blends the rest over them.
  bool opaqueFirst = surface && effects.transparency && !paintsInOrder && !blendsItself;

  // Why a pass after visibility does not run for an algorithm that is not a surface one.
  std::string notForThisKind() const {
    return lines ? algorithm.name + " draws lines: a line drawing has no surfaces to shade"
                 : "the reference renders its effects itself, exactly (exact shadow rays, exact blending, the same fog and outline)";
  }
};

struct Decision {
  bool runs;
  std::string title, reason;
  std::vector<PlannedPass> work = {};
};

struct Pass {
  const char* name;  // its phase is "pass: NAME"
  Decision (*decide)(const Facts&);
  void (*run)(Context&);
};

const std::string kListed = "effects lists ";

Decision decideCulling(const Facts& facts) {
  const culling::Pipeline& stages = facts.configuration.culling;
  return {!stages.empty(), "culling", stages.empty() ? "no --cull stages given" : "--cull " + culling::describePipeline(stages)};
}

void runCulling(Context& context) {
  context.kept = culling::runPipeline(context.scene, context.configuration.culling, context.threads, context.stats, context.previous,
                                      context.steps, context.culled);
}

Decision decideVisibility(const Facts& facts) {
  std::string reason = std::to_string(facts.scene.width()) + "x" + std::to_string(facts.scene.height()) + " pixels, " +
                       count(facts.scene.triangleCount(), "triangle");
  if (facts.opaqueFirst) reason += "; the opaque surfaces only (transparency blends the others over them)";
  return {true, "visibility: " + facts.algorithm.name, reason};
}

void runVisibility(Context& context) {
  const PreparedScene& scene = context.scene;
  const AlgorithmEntry& algorithm = *context.configuration.algorithm;
  switch (algorithm.kind) {
    case AlgorithmKind::reference:
      context.visibility.frame = algorithm.renderExactly(scene, context.threads, context.stats);
      return;
    case AlgorithmKind::line:
      context.drawing = algorithm.drawLines(scene, context.configuration.knobs, context.threads, context.stats, context.steps);
      return;
    case AlgorithmKind::surface: {
      const VisibleSet* triangles = context.kept ? &*context.kept : nullptr;
      std::optional<VisibleSet> opaque;
      if (Facts{scene, context.configuration}.opaqueFirst) triangles = &opaque.emplace(trianglesByOpacity(scene, triangles, true));
      if (context.visibility.frame.width != scene.width() || context.visibility.frame.height != scene.height()) {
        PhaseTimer timer(context.stats, "frame buffers");
        context.visibility.frame = Frame(scene.width(), scene.height(), context.threads);
      }
      context.visibility.polygons.clear();  // what only some algorithms answer, never left from another's
      context.visibility.coverage.reset();
      algorithm.visibility({scene, context.camera, triangles, context.threads, context.stats, context.steps, context.why},
                           context.configuration.knobs, context.visibility);
      if (context.why) context.stats.add("why: events recorded", context.why->events());
      return;
    }
  }
}

Decision decideDrawing(const Facts& facts) {
  if (!facts.lines) return {false, "drawing", "only a line algorithm draws lines"};
  return {true, "drawing", "the drawing's visible lines rasterized into the image"};
}

void runDrawing(Context& context) { context.visibility.frame = lineSetFrame(context.drawing, LineStyle::visible); }

Decision decideShadowMaps(const Facts& facts) {
  if (!facts.surface) return {false, "shadow maps", facts.notForThisKind()};
  if (!facts.effects.shadows) return {false, "shadow maps", "effects does not list shadows"};
  std::string views;
  for (const Light& light : facts.scene.scene().lights) {
    char view[160];
    std::snprintf(view, sizeof view, "%slight '%s': %s of %dx%d", views.empty() ? "" : "; ", light.name.c_str(),
                  shadowViewCount(light) == 1 ? "1 view" : "6 views (a cube)", facts.effects.shadow.resolution,
                  facts.effects.shadow.resolution);
    views += view;
  }
  char bias[48];
  std::snprintf(bias, sizeof bias, ", bias %g texels", facts.effects.shadow.biasTexels);
  return {true, "shadow maps", kListed + "shadows; " + views + bias};
}

void runShadowMaps(Context& context) {
  context.shadowMaps.emplace(context.scene, context.scene.scene().effects.shadow, context.threads, context.stats);
}

// The work inside shading (renderer/shading/shading: PixelShader), wherever a pass shades.
std::vector<PlannedPass> shadingWork(const Facts& facts) {
  const Effects& effects = facts.effects;
  std::size_t views = 0;
  for (const Light& light : facts.scene.scene().lights) views += std::size_t(shadowViewCount(light));
  return {
      {"corner normals", effects.smoothNormals(),
       effects.smoothNormals() ? std::string(shadingName(effects.shading)) + " interpolates them; only for the triangles it shades"
       : effects.lit()         ? "flat shading uses face normals"
                               : "no lit effect"},
      {"specular highlights", effects.shading == Shading::phong,
       effects.shading == Shading::phong ? kListed + "phong" : "effects does not list phong"},
      {"shadow lookups", effects.shadows,
       effects.shadows ? "per lit pixel and light facing it, " + count(views, "map view") : "effects does not list shadows"},
  };
}

Decision decideShading(const Facts& facts) {
  const Effects& effects = facts.effects;
  const std::string title = "shading: " + std::string(shadingName(effects.shading));
  if (!facts.surface) return {false, title, facts.notForThisKind()};
  if (facts.paintsInOrder && effects.transparency)
    return {false, title, "transparency shades every surface as it blends it, in " + facts.algorithm.name + "'s own order"};
  char ambient[48];
  std::snprintf(ambient, sizeof ambient, ", ambient %g", facts.scene.scene().ambient);
  const std::string blended = facts.blendsItself ? "; each pixel's surfaces shaded at its center and weighted by their shares" : "";
  return {true, title,
          (effects.lit() ? count(facts.scene.scene().lights.size(), "light") + ambient : "no lit effect: each object's own color") + blended,
          shadingWork(facts)};
}

void runShading(Context& context) {
  if (context.visibility.coverage)
    shadeCoverage(context.scene, *context.visibility.coverage, context.pixelShader(), context.threads, context.visibility.frame,
                  context.stats);
  else
    shadeFrame(context.scene, context.visibility.frame, context.pixelShader(), context.threads, context.stats);
}

Decision decideTransparency(const Facts& facts) {
  if (!facts.surface) return {false, "transparency", facts.notForThisKind()};
  if (!facts.effects.transparency) return {false, "transparency", "effects does not list transparency: nothing is sorted for blending"};
  if (facts.blendsItself)
    return {false, "transparency", facts.algorithm.name + " blends the transparent surfaces itself, in each pixel's list of fragments"};
  std::size_t transparent = 0;
  for (const SceneObject& object : facts.scene.scene().objects) transparent += object.opacity < 1;
  if (!facts.paintsInOrder)
    return {true, "transparency",
            kListed + "transparency; " + count(transparent, "object") +
                " below opacity 1, blended back to front by the sorted pass over the opaque depth (the painter's sort by centroid)"};
  return {true, "transparency",
          kListed + "transparency; " + count(transparent, "object") + " below opacity 1; every surface shaded and blended back to front in " +
              facts.algorithm.name + "'s own order",
          shadingWork(facts)};
}

void runTransparency(Context& context) {
  const PreparedScene& scene = context.scene;
  Frame& frame = context.visibility.frame;
  if (context.visibility.painted) {
    blendInOrder(scene, *context.visibility.painted, context.pixelShader(), context.threads, frame, context.stats);
    return;
  }
  const VisibleSet glass = trianglesByOpacity(scene, context.kept ? &*context.kept : nullptr, false);
  const PaintedPieces order = painter::order({scene, context.camera, &glass, context.threads, context.stats}, kTransparencySort);
  blendOverOpaque(scene, order, context.pixelShader(), context.threads, frame, context.stats);
}

Decision decideFog(const Facts& facts) {
  if (!facts.surface) return {false, "fog", facts.notForThisKind()};
  const FogSettings& fog = facts.effects.fogSettings;
  if (!facts.effects.fog) return {false, "fog", "effects does not list fog"};
  char what[96];
  if (fog.kind == FogSettings::Kind::linear)
    std::snprintf(what, sizeof what, "linear from %g to %g", fog.start, fog.end);
  else
    std::snprintf(what, sizeof what, "exponential, density %g", fog.density);
  return {true, "fog", kListed + "fog; " + what};
}

void runFog(Context& context) {
  applyFog(context.scene.scene().effects.fogSettings, context.visibility.frame, context.threads, context.stats);
}

Decision decideOutline(const Facts& facts) {
  if (!facts.surface) return {false, "outline", facts.notForThisKind()};
  if (!facts.effects.outline) return {false, "outline", "effects does not list outline"};
  char crease[64];
  std::snprintf(crease, sizeof crease, "; creases sharper than %g degrees", facts.effects.outlineSettings.creaseDegrees);
  return {true, "outline", kListed + "outline" + crease};
}

void runOutline(Context& context) {
  const Effects& effects = context.scene.scene().effects;
  drawOutline(context.scene, context.camera, effects.outlineSettings, effects.fog ? &effects.fogSettings : nullptr,
              context.visibility.frame, context.stats);
}

// The passes, in the order they run; the first two answer visibility.
const std::vector<Pass>& passes() {
  static const std::vector<Pass> all = {
      {"culling", decideCulling, runCulling},
      {"visibility", decideVisibility, runVisibility},
      {"drawing", decideDrawing, runDrawing},
      {"shadow maps", decideShadowMaps, runShadowMaps},
      {"shading", decideShading, runShading},
      {"transparency", decideTransparency, runTransparency},
      {"fog", decideFog, runFog},
      {"outline", decideOutline, runOutline},
  };
  return all;
}

std::string phaseOf(const Pass& pass) { return std::string("pass: ") + pass.name; }
constexpr std::size_t kVisibilityPasses = 2;

// Runs the first `count` passes that the configuration calls for.
void runPasses(Context& context, std::size_t count) {
  HSR_CHECK(context.configuration.culling.empty() || context.configuration.algorithm->takesTriangleSubsets);
  const Facts facts{context.scene, context.configuration};
  for (std::size_t p = 0; p < count; ++p) {
    const Pass& pass = passes()[p];
    if (!pass.decide(facts).runs) continue;
    PhaseTimer timer(context.stats, phaseOf(pass));
    pass.run(context);
  }
}

}  // namespace

Configuration configurationOf(const AlgorithmEntry& algorithm, const KnobSettings& settings, const std::string& where) {
  return {&algorithm, resolveKnobs(algorithm, settings, where)};
}

std::string refusal(const PreparedScene& scene, const Configuration& configuration) {
  const AlgorithmEntry& algorithm = *configuration.algorithm;
  if (std::string own = algorithm.refusal(scene, configuration.knobs); !own.empty()) return own;
  if (algorithm.kind != AlgorithmKind::surface || !scene.scene().effects.transparency || algorithm.order || algorithm.takesTriangleSubsets)
    return "";
  std::string able;
  for (const AlgorithmEntry& other : algorithms())
    if (other.kind == AlgorithmKind::surface && (other.order || other.takesTriangleSubsets))
      able += (able.empty() ? "" : " or ") + other.name;
  return "the scene declares transparency, which needs the surfaces behind a pixel blended back to front; " + displayName(algorithm) +
         " keeps only the nearest (use --algo " + able + ")";
}

std::string cullableAlgorithms() {
  std::string names;
  for (const AlgorithmEntry& entry : algorithms())
    if (entry.takesTriangleSubsets) names += (names.empty() ? "" : " or ") + entry.name;
  return names;
}

culling::Pipeline cullingOf(const std::string& text, const AlgorithmEntry& algorithm) {
  if (text.empty()) return {};
  culling::Pipeline stages = culling::parsePipeline(text, "--cull");
  if (!algorithm.takesTriangleSubsets)
    throw InputError("--cull: " + algorithm.name + " does not draw from a culled set of triangles; expected --algo " +
                     cullableAlgorithms());
  return stages;
}

void checkRenders(const Configuration& configuration, const std::string& sceneName, const PreparedScene& scene) {
  if (const std::string reason = refusal(scene, configuration); !reason.empty())
    throw InputError(sceneName + ": " + configuration.algorithm->name + " cannot render it: " + reason);
}

// The frame's own buffers are the part that grows with the size for every algorithm; an
// algorithm's own (a depth buffer, fragment lists, a tree) come on top.
std::string outOfMemory(int width, int height, const std::string& algorithm) {
  const double pixels = double(width) * double(height);
  const double frameBytes = pixels * (sizeof(std::uint32_t) + sizeof(float) + 4);  // ids, depth, RGBA colour
  char text[320];
  std::snprintf(text, sizeof text,
                "out of memory rendering %dx%d with %s: the frame alone needs %.1f GiB (ids, depth and colour, 12 bytes a pixel), "
                "and the algorithm's own buffers come on top; expected a smaller --size",
                width, height, algorithm.c_str(), frameBytes / double(1u << 30));
  return text;
}

std::vector<PlannedPass> plan(const PreparedScene& scene, const Configuration& configuration) {
  const Facts facts{scene, configuration};
  std::vector<PlannedPass> planned;
  for (const Pass& pass : passes()) {
    Decision decision = pass.decide(facts);
    planned.push_back({decision.title, decision.runs, decision.reason, std::move(decision.work)});
  }
  return planned;
}

Rendered render(const PreparedScene& scene, const Configuration& configuration, int threads, Stats& stats,
                const culling::PreviousFrame* previous, StepRecorder* steps) {
  Visibility visibility;
  Context context{scene, scene.camera(), configuration, threads, stats, previous, steps, std::nullopt, visibility};
  runPasses(context, passes().size());
  return {std::move(visibility.frame), std::move(context.drawing), std::move(visibility.polygons), std::move(visibility.coverage)};
}

VisibleSet renderVisibility(const PreparedScene& scene, const Configuration& configuration, int threads, Stats& stats,
                            Visibility& visibility, const culling::PreviousFrame* previous, PixelWitness* why,
                            culling::CullingWitness* culled, StepRecorder* steps) {
  HSR_CHECK(configuration.algorithm->kind == AlgorithmKind::surface);
  HSR_CHECK(!why || configuration.algorithm->answersWhy);
  Context context{scene, scene.camera(), configuration, threads, stats, previous, steps, std::nullopt, visibility};
  context.why = why;
  context.culled = culled;
  runPasses(context, kVisibilityPasses);
  return context.kept ? std::move(*context.kept) : VisibleSet::everything(scene);
}

void recordFinishedStep(StepRecorder& steps, const Frame& shown, bool lines, SourceLocation where) {
  steps.record(lines ? "the finished drawing" : kFinishedImageStep, Image{shown.width, shown.height, 4, {shown.color.begin(), shown.color.end()}},
               where);
}

std::vector<PassTime> passTimes(const Stats& stats) {
  const std::vector<std::string> phases = stats.phaseNames();
  std::vector<PassTime> times;
  for (std::size_t p = 0; p < passes().size(); ++p) {
    const Pass& pass = passes()[p];
    if (std::find(phases.begin(), phases.end(), phaseOf(pass)) != phases.end())
      times.push_back({pass.name, stats.seconds(phaseOf(pass)), p < kVisibilityPasses});
  }
  return times;
}

}  // namespace hsr::pipeline
