// Effects on demand (algorithms/effects, renderer/shading/shading): a scene without an effect
// spends nothing on it, adding an effect adds only its own pass, and each effect is
// checked against an independent computation: shadow maps against exact shadow rays,
// blending against the reference's per-pixel sorted hits, fog against its formula,
// outlines against the faces' own edges, phong against lambert.
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "algorithms/culling/culling.hpp"
#include "algorithms/registry.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/shadow_maps.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/scene/obj.hpp"
#include "renderer/shading/fog.hpp"
#include "studies/effect_ladder.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

const char* const kShowcase = "scenes/effects.toml";

Frame renderWith(const std::string& algorithm, const PreparedScene& scene, Stats& stats, const KnobSettings& knobs = {},
                 int threads = 2) {
  const AlgorithmEntry& entry = findAlgorithm(algorithm);
  return pipeline::render(scene, pipeline::configurationOf(entry, knobs), threads, stats).frame;
}

// The counters and phases each effect may add or change (a pipeline pass times itself as
// "pass: NAME"); anything else changing between two steps of the ladder is a pass that ran
// without being asked for.
const std::map<std::string, std::set<std::string>>& ownedWork() {
  static const std::map<std::string, std::set<std::string>> owned = {
      {"flat", {}},
      {"lambert", {"normals computed", "vertex triangles"}},
      {"phong", {"specular terms"}},
      {"+ shadows", {"shadow maps rendered", "shadow map texels", "shadow map fragments written", "shadow lookups",
                     "shadowed lookups", "shadow maps", "pass: shadow maps", "specular terms"}},
      // The transparent objects leave the depth buffer for the sorted pass, and the shadow
      // maps' casters, so those passes' own counts change too: only the sorted pass is new.
      // It is the first pass that reads distances: the z-buffer decodes its depth for it.
      {"+ transparency", {"blended writes", "shading set-ups", "normals computed", "pieces painted", "cut tests", "transparency", "pass: transparency", "ordering", "shading invocations",
                          "specular terms", "shadow lookups", "shadowed lookups", "fragments written", "fragments tested",
                          "screen triangles", "triangles in", "triangles clipped", "triangles outside view",
                          "triangles between pixel centers", "vertices transformed", "shadow map fragments written", kDistancesDecodedCounter}},
      {"+ fog", {"fog blends", "fog", "pass: fog"}},
      {"+ outline", {"outline edges", "outline pixels", "feature edges", "mesh edges built", "facing tests",
                     "predicate evaluations", "predicate exact fall-backs", "edge adjacency", "outline", "pass: outline"}},
  };
  return owned;
}

// Counters that differ between two runs (those that vary with timing are not counters).
std::set<std::string> changedCounters(const Stats& before, const Stats& after) {
  std::set<std::string> changed;
  for (const std::string& name : after.counterNames())
    if (before.counter(name) != after.counter(name)) changed.insert(name);
  for (const std::string& name : before.counterNames())
    if (before.counter(name) != after.counter(name)) changed.insert(name);
  for (const std::string& name : after.phaseNames())
    if (before.seconds(name) == 0) changed.insert(name);
  return changed;
}

TEST(Effects, ASceneWithoutAnEffectSpendsNothingOnIt) {
  const test::LoadedScene showcase(test::sourcePath(kShowcase), 320);
  const std::vector<studies::EffectStep> ladder = studies::effectLadder(showcase.scene);
  const PreparedScene bare(ladder.front().scene);
  ASSERT_EQ(ladder.front().name, "none");
  for (const char* algorithm : {"zbuffer", "painter", "ray_casting"}) {
    Stats stats;
    renderWith(algorithm, bare, stats);
    for (const char* counter : {"normals computed", "specular terms", "shadow maps rendered", "shadow lookups", "blended writes",
                                "fog blends", "outline pixels", "feature edges"})
      EXPECT_EQ(stats.counter(counter), 0) << algorithm << ": " << counter;
    for (const char* phase : {"vertex triangles", "shadow maps", "transparency", "fog", "outline"})
      EXPECT_EQ(stats.seconds(phase), 0) << algorithm << ": " << phase;
    EXPECT_GT(stats.counter("shading invocations"), 0) << algorithm << ": ids still become colors";
  }
}

TEST(Effects, AddingAnEffectAddsOnlyItsOwnPass) {
  const test::LoadedScene showcase(test::sourcePath(kShowcase), 320);
  const std::vector<studies::EffectStep> ladder = studies::effectLadder(showcase.scene);
  std::vector<std::string> names;
  for (const auto& step : ladder) names.push_back(step.name);
  EXPECT_EQ(names, (std::vector<std::string>{"none", "flat", "lambert", "phong", "+ shadows", "+ transparency", "+ fog", "+ outline"}));
  for (const char* algorithm : {"zbuffer", "painter"}) {
    Stats previous;
    {
      const PreparedScene first(ladder.front().scene);
      renderWith(algorithm, first, previous);
    }
    for (std::size_t step = 1; step < ladder.size(); ++step) {
      const PreparedScene prepared(ladder[step].scene);
      Stats stats;
      renderWith(algorithm, prepared, stats);
      const std::set<std::string>& allowed = ownedWork().at(ladder[step].name);
      for (const std::string& changed : changedCounters(previous, stats))
        EXPECT_TRUE(allowed.count(changed)) << algorithm << ", " << ladder[step].name << " changed '" << changed << "'";
      previous = stats;
    }
  }
}

// The z-buffer keeps its depth buffer undecoded until a pass reads distances: up the
// ladder, transparency is the first (the glass is tested against the opaque distances),
// and fog alone asks too; the shadow maps' light views decode their own, not counted here.
TEST(Effects, TheZBufferDecodesDistancesOnlyForAPassThatReadsThem) {
  const test::LoadedScene showcase(test::sourcePath(kShowcase), 320);
  const std::vector<studies::EffectStep> ladder = studies::effectLadder(showcase.scene);
  bool reading = false;
  for (const studies::EffectStep& step : ladder) {
    reading = reading || step.name == "+ transparency";
    const PreparedScene prepared(step.scene);
    Stats stats;
    renderWith("zbuffer", prepared, stats);
    EXPECT_EQ(stats.counter(kDistancesDecodedCounter), reading ? std::int64_t(prepared.width()) * prepared.height() : 0) << step.name;
  }
  Scene fogOnly = ladder.front().scene;
  fogOnly.effects.fog = true;
  const PreparedScene foggy(fogOnly);
  Stats stats;
  renderWith("zbuffer", foggy, stats);
  EXPECT_EQ(stats.counter(kDistancesDecodedCounter), std::int64_t(foggy.width()) * foggy.height());
  EXPECT_GT(stats.counter("fog blends"), 0);
}

TEST(Effects, EachEffectCountsItsWorkWhenDeclared) {
  const test::LoadedScene showcase(test::sourcePath(kShowcase), 320);
  Stats stats;
  const Frame frame = renderWith("zbuffer", showcase.prepared, stats);
  long covered = 0;
  std::set<std::uint32_t> shown;
  for (const std::uint32_t id : frame.ids) {
    covered += id != 0;
    if (id != 0) shown.insert(id);
  }
  // Corner normals only for the triangles shading set up: those the image shows, and
  // the transparent ones blended over them (some of which end up hidden).
  EXPECT_EQ(stats.counter("normals computed"), 3 * stats.counter("shading set-ups"));
  EXPECT_GE(stats.counter("shading set-ups"), std::int64_t(shown.size()));
  EXPECT_LT(stats.counter("shading set-ups"), std::int64_t(showcase.prepared.triangleCount()));
  EXPECT_EQ(stats.counter("shadow maps rendered"), 1) << "one directional light: one view";
  EXPECT_EQ(stats.counter("shadow map texels"), 1024 * 1024);
  EXPECT_GT(stats.counter("shadowed lookups"), 0);
  EXPECT_LT(stats.counter("shadowed lookups"), stats.counter("shadow lookups"));
  EXPECT_GT(stats.counter("blended writes"), 0);
  EXPECT_EQ(stats.counter("fog blends"), covered) << "every covered pixel, once";
  EXPECT_GT(stats.counter("outline pixels"), 0);
}

TEST(Effects, TheSameBitsOnAnyThreadCount) {
  const test::LoadedScene showcase(test::sourcePath(kShowcase), 320);
  for (const char* algorithm : {"zbuffer", "painter"}) {
    Stats one, three;
    EXPECT_EQ(renderWith(algorithm, showcase.prepared, one, {}, 1).color, renderWith(algorithm, showcase.prepared, three, {}, 3).color)
        << algorithm;
  }
}

TEST(Effects, PhongOnlyAddsHighlightsToLambert) {
  const test::LoadedScene showcase(test::sourcePath(kShowcase), 320);
  const std::vector<studies::EffectStep> ladder = studies::effectLadder(showcase.scene);
  const PreparedScene lambert(ladder[2].scene), phong(ladder[3].scene);
  ASSERT_EQ(ladder[3].name, "phong");
  Stats stats;
  const Frame diffuse = renderWith("zbuffer", lambert, stats), shiny = renderWith("zbuffer", phong, stats);
  long brighter = 0;
  for (std::size_t i = 0; i < diffuse.color.size(); ++i) {
    ASSERT_GE(shiny.color[i], diffuse.color[i]) << "a highlight only adds light, at byte " << i;
    brighter += shiny.color[i] > diffuse.color[i] + 20;
  }
  EXPECT_GT(brighter, 50) << "the ball's highlight";
}

// The shadow map's decisions against exact shadow rays at the same surface points: within
// the bound documented in algorithms/effects/README.md at the scene's settings; with no
// bias the surfaces shadow themselves (acne), with a huge one shadows come loose
// (peter-panning), and a coarser map is wrong more often.
TEST(Effects, ShadowMapsAgreeWithExactShadowRaysWithinTheDocumentedBound) {
  const test::LoadedScene showcase(test::sourcePath(kShowcase), 320);
  Stats stats;
  const Frame frame = renderWith("zbuffer", showcase.prepared, stats);
  const ExactShadows exact(showcase.prepared, stats);
  const auto errorWith = [&](int resolution, double bias) {
    Stats mapStats;
    const pipeline::ShadowMaps maps(showcase.prepared, {resolution, bias}, 2, mapStats);
    return shadowError(showcase.prepared, frame, maps, exact, 2);
  };
  const ShadowError standard = errorWith(1024, 1.5);
  EXPECT_GT(standard.lookups, 30000);
  EXPECT_LT(standard.fraction, 0.01) << standard.differing << " of " << standard.lookups;
  const ShadowError acne = errorWith(1024, 0);
  EXPECT_GT(acne.falselyShadowed, 5 * standard.falselyShadowed + 100) << "no bias: self-shadowing";
  const ShadowError loose = errorWith(1024, 40);
  EXPECT_GT(loose.falselyLit, 5 * standard.falselyLit + 100) << "a huge bias: shadows come loose";
  const ShadowError coarse = errorWith(128, 1.5);
  EXPECT_GT(coarse.differing, 2 * standard.differing) << "an eighth of the resolution";
}

// The painter's exact orders blend as the reference does from its sorted hits, pixel by
// pixel; the z-buffer's sorted pass (whole triangles by centroid) cannot where the cycle
// closes, and says so by differing there.
TEST(Effects, ExactOrdersBlendTheCyclicGlassAsTheReferenceDoes) {
  const test::LoadedScene glass(test::sourcePath("scenes/hard/cyclic_glass.toml"));
  Stats stats;
  const ReferenceImage reference = renderReference(glass.prepared, 2, stats);
  const auto wrongPixels = [&](const Frame& frame) {
    long wrong = 0;
    for (std::size_t pixel = 0; pixel < frame.pixelCount(); ++pixel)
      wrong += !reference.blendTied[pixel] && test::colorDiffers(frame.color, reference.frame.color, pixel, 1);
    return wrong;
  };
  long compared = 0;
  for (std::size_t pixel = 0; pixel < reference.frame.pixelCount(); ++pixel) compared += !reference.blendTied[pixel];
  EXPECT_GT(compared, 30000);
  for (const char* variant : {"newell", "bsp"}) {
    const Frame frame = renderWith("painter", glass.prepared, stats, {{"variant", variant}});
    EXPECT_EQ(wrongPixels(frame), 0) << variant;
    EXPECT_EQ(surfaceError(frame, reference).wrongPixels, 0) << variant << ": the nearest layer's id";
  }
  EXPECT_GT(wrongPixels(renderWith("painter", glass.prepared, stats, {{"variant", "sort"}})), 100) << "a depth sort cannot";
  EXPECT_GT(wrongPixels(renderWith("zbuffer", glass.prepared, stats)), 100) << "the sorted pass cannot either";
}

// One glass box over opaque things: the depth sort orders its front and back faces
// right, but at its rim a side face's centroid is nearer than the front face's while the
// ray meets it behind: the only pixels it blends wrong, all on the glass or within a pixel
// of its outline (where snapping decides whether the glass covers the pixel).
TEST(Effects, TheZBufferSortedPassMisordersOnlyAGlassBoxRim) {
  const test::LoadedScene showcase(test::sourcePath(kShowcase), 320);
  Scene scene = showcase.scene;
  scene.effects.shadows = scene.effects.fog = scene.effects.outline = false;
  const PreparedScene prepared(scene);
  Stats stats;
  const ReferenceImage reference = renderReference(prepared, 2, stats);
  const Frame frame = renderWith("zbuffer", prepared, stats);
  const auto glassNear = [&](std::size_t pixel) {
    const int x = int(pixel % std::size_t(frame.width)), y = int(pixel / std::size_t(frame.width));
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = std::clamp(x + dx, 0, frame.width - 1), ny = std::clamp(y + dy, 0, frame.height - 1);
        const std::uint32_t id = reference.frame.ids[std::size_t(ny) * std::size_t(frame.width) + std::size_t(nx)];
        if (id != 0 && scene.objects[prepared.instanceOf(id - 1).object].name == "glass") return true;
      }
    return false;
  };
  long compared = 0, wrong = 0;
  for (std::size_t pixel = 0; pixel < frame.pixelCount(); ++pixel) {
    // A pixel showing another surface than the reference's is a visibility error (snapping,
    // judged by tests/zbuffer), not a blending one.
    if (reference.blendTied[pixel] || frame.ids[pixel] != reference.frame.ids[pixel]) continue;
    ++compared;
    if (!test::colorDiffers(frame.color, reference.frame.color, pixel, 1)) continue;
    ++wrong;
    EXPECT_TRUE(glassNear(pixel)) << "pixel " << pixel;
  }
  EXPECT_GT(compared, 250000);
  EXPECT_GT(wrong, 0) << "the rim";
  EXPECT_LT(wrong, compared / 300);
}

TEST(Effects, FogBlendsEachPixelByItsFormula) {
  for (const FogSettings::Kind kind : {FogSettings::Kind::linear, FogSettings::Kind::exponential}) {
    const test::LoadedScene loaded(test::sourcePath("scenes/cube.toml"), 160);
    Scene clear = loaded.scene;
    Scene foggy = clear;
    foggy.effects.fog = true;
    foggy.effects.fogSettings = {kind, 4, 8, 0.2, vec3(0.2f, 0.4f, 0.6f)};
    const PreparedScene plain(clear), fogged(foggy);
    Stats stats;
    const Frame before = renderWith("zbuffer", plain, stats), after = renderWith("zbuffer", fogged, stats);
    long covered = 0;
    for (std::size_t pixel = 0; pixel < before.pixelCount(); ++pixel) {
      if (before.ids[pixel] == 0) {
        EXPECT_EQ(before.color[4 * pixel], after.color[4 * pixel]) << "the background is not fogged";
        continue;
      }
      ++covered;
      const double keep = fogClearFraction(foggy.effects.fogSettings, before.distances()[pixel]);
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(after.color[4 * pixel + c], channelByte(keep * before.color[4 * pixel + c] / 255.0 + (1 - keep) * foggy.effects.fogSettings.color[c]))
            << "pixel " << pixel;
    }
    EXPECT_GT(covered, 1000);
  }
  const FogSettings linear{FogSettings::Kind::linear, 2, 6, 0, vec3(0)};
  EXPECT_EQ(fogClearFraction(linear, 1), 1);
  EXPECT_EQ(fogClearFraction(linear, 4), 0.5);
  EXPECT_EQ(fogClearFraction(linear, 7), 0);
}

// On a cube every edge is a crease or a silhouette: each outline pixel lies within a
// pixel of where the id changes, and there is an outline wherever two faces meet.
TEST(Effects, OutlinesLieOnTheEdgesBetweenFaces) {
  const test::LoadedScene loaded(test::sourcePath("scenes/cube.toml"), 200);
  Scene scene = loaded.scene;
  scene.effects.outline = true;
  scene.effects.outlineSettings.color = vec3(1, 0, 1);
  const PreparedScene prepared(scene);
  Stats stats;
  const Frame frame = renderWith("zbuffer", prepared, stats);
  const auto objectFace = [&](int x, int y) {
    const std::uint32_t id = frame.ids[std::size_t(y) * std::size_t(frame.width) + std::size_t(x)];
    return id == 0 ? -1 : static_cast<int>((id - 1) / 2);  // a box's faces are triangle pairs
  };
  long drawn = 0, faceMeetings = 0, meetingsDrawn = 0;
  for (int y = 1; y + 1 < frame.height; ++y)
    for (int x = 1; x + 1 < frame.width; ++x) {
      const std::uint8_t* rgba = &frame.color[4 * (std::size_t(y) * std::size_t(frame.width) + std::size_t(x))];
      const auto isOutline = [](const std::uint8_t* color) { return color[0] == 255 && color[1] == 0 && color[2] == 255; };
      const bool outline = isOutline(rgba);
      std::set<int> faces;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) faces.insert(objectFace(x + dx, y + dy));
      drawn += outline;
      if (outline) {
        EXPECT_GT(faces.size(), 1u) << "an outline inside a face at (" << x << ", " << y << ")";
      }
      if (objectFace(x, y) != objectFace(x + 1, y)) {
        ++faceMeetings;
        meetingsDrawn += outline || isOutline(rgba + 4);  // the line covers the center nearer the edge
      }
    }
  EXPECT_GT(drawn, 200);
  EXPECT_EQ(meetingsDrawn, faceMeetings) << "every edge between faces (or with the background) is outlined";
  EXPECT_EQ(stats.counter("outline pixels"), drawn);
}

TEST(Effects, ThePlanSaysWhyEachPassRunsOrNot) {
  const test::LoadedScene cube(test::sourcePath("scenes/cube.toml"));
  const auto plan = pipeline::plan(cube.prepared, pipeline::configurationOf(findAlgorithm("zbuffer"), {}));
  std::map<std::string, std::pair<bool, std::string>> byPass;
  for (const auto& pass : plan) {
    byPass[pass.pass] = {pass.runs, pass.reason};
    for (const auto& work : pass.work) byPass[work.pass] = {pass.runs && work.runs, work.reason};
  }
  EXPECT_EQ(byPass.at("shadow maps"), std::make_pair(false, std::string("effects does not list shadows")));
  EXPECT_EQ(byPass.at("corner normals"), std::make_pair(true, std::string("lambert interpolates them; only for the triangles it shades")));
  EXPECT_FALSE(byPass.at("fog").first);
  EXPECT_FALSE(byPass.at("transparency").first);

  const test::LoadedScene showcase(test::sourcePath(kShowcase));
  std::set<std::string> running;
  pipeline::Configuration painter = pipeline::configurationOf(findAlgorithm("painter"), {});
  painter.culling = culling::parsePipeline("frustum");
  for (const auto& pass : pipeline::plan(showcase.prepared, painter)) {
    if (pass.runs) running.insert(pass.pass);
    for (const auto& work : pass.work)
      if (pass.runs && work.runs) running.insert(work.pass);
  }
  // The painter blends every surface in its own order: transparency shades them, not a shading pass.
  EXPECT_EQ(running, (std::set<std::string>{"culling", "visibility: painter", "shadow maps", "transparency", "corner normals",
                                            "specular highlights", "shadow lookups", "fog", "outline"}));
  const auto lines = pipeline::plan(showcase.prepared, pipeline::configurationOf(findAlgorithm("appel"), {}));
  EXPECT_FALSE(lines.back().runs) << "a line drawing has nothing to shade";
}

// Lambert shading reads the normals an OBJ file gives (vn), and computes only the
// corners the file leaves without one.
TEST(Effects, LambertUsesTheMeshFilesNormalsWhereItGivesThem) {
  const auto obj = test::outputPath("effects_normals.obj");
  std::filesystem::create_directories(obj.parent_path());
  // A square facing the camera (+z), lit head-on: by its own normal fully, by the file's
  // tilted normal (0, 0.6, 0.8) to 0.8.
  const auto centerRed = [&](const std::string& faces, Stats& stats) {
    std::ofstream(obj) << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0 0.6 0.8\n" << faces;
    Scene scene = test::sceneOf(Camera{}, 33, 33, {loadObj(obj)});
    scene.effects.shading = Shading::lambert;
    scene.ambient = 0;
    scene.lights = {Light{"head-on", Light::Kind::directional, dvec3(0, 0, -1), dvec3(0), 1.0}};
    scene.objects[0].color = vec3(1);
    const PreparedScene prepared(scene);
    return renderWith("zbuffer", prepared, stats).color[(16 * 33 + 16) * 4];
  };
  Stats given, computed, mixed;
  EXPECT_EQ(centerRed("f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n", given), channelByte(0.8));
  EXPECT_EQ(given.counter("normals from the mesh"), 6);
  EXPECT_EQ(given.counter("normals computed"), 0);
  EXPECT_EQ(centerRed("f 1 2 3\nf 1 3 4\n", computed), 255);
  EXPECT_EQ(computed.counter("normals from the mesh"), 0);
  EXPECT_EQ(computed.counter("normals computed"), 6);
  centerRed("f 1//1 2//1 3//1\nf 1 3 4\n", mixed);
  EXPECT_EQ(mixed.counter("normals from the mesh"), 3);
  EXPECT_EQ(mixed.counter("normals computed"), 3);
}

TEST(Effects, APointLightCastsShadowsThroughSixViews) {
  const test::LoadedScene showcase(test::sourcePath(kShowcase), 160);
  Scene scene = showcase.scene;
  scene.lights = {Light{"lamp", Light::Kind::point, dvec3(0), dvec3(1.5, 4, 2), 1.0}};
  const PreparedScene prepared(scene);
  Stats stats;
  const Frame frame = renderWith("zbuffer", prepared, stats);
  EXPECT_EQ(stats.counter("shadow maps rendered"), 6);
  const ExactShadows exact(prepared, stats);
  const pipeline::ShadowMaps maps(prepared, scene.effects.shadow, 2, stats);
  const ShadowError error = shadowError(prepared, frame, maps, exact, 2);
  EXPECT_GT(error.lookups, 5000);
  EXPECT_GT(stats.counter("shadowed lookups"), 500);
  EXPECT_LT(error.fraction, 0.02) << error.differing << " of " << error.lookups;
}

}  // namespace
}  // namespace hsr
