// Culling stages: the correct ones never drop a triangle the exact reference sees, and
// change no pixel of the image; the wrong textbook variants do drop visible triangles,
// on the scenes built to show it; the counters show the work each one saves.
#include <gtest/gtest.h>

#include <random>

#include "algorithms/culling/culling.hpp"
#include "culling/culling_support.hpp"
#include "renderer/geometry/clip.hpp"
#include "renderer/geometry/predicates.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/util/error.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

// The triangle shown at a pixel faces away from the eye (an exact sign).
bool showsBackFace(const PreparedScene& scene, std::uint32_t id, ExactPredicates& predicates) {
  if (id == conventions::kBackgroundId) return false;
  const Triangle& t = scene.triangles()[id - 1];
  const Camera& camera = scene.scene().camera;
  const dvec3 &a = scene.positions()[t[0]], &b = scene.positions()[t[1]], &c = scene.positions()[t[2]];
  if (camera.projection == Projection::perspective) return predicates.orient3d(a, b, c, camera.eye) <= 0;
  return predicates.facing(a, b, c, camera.eye - camera.target) <= 0;
}

// ---------------------------------------------------------------------------------
// The frustum planes

TEST(FrustumPlanes, GribbHartmannPlanesAgreeWithTheClipVolume) {
  // A point is inside all six planes exactly when its clip coordinates are inside the
  // view (and the near and far planes): the same volume, two derivations.
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coordinate(-30, 30);
  for (const Projection projection : {Projection::perspective, Projection::orthographic}) {
    Camera camera;
    camera.projection = projection;
    camera.eye = {1, 2, 3};
    camera.target = {-2, 0.5, -4};
    camera.orthoHeight = 20;
    camera.near = 0.5;
    camera.far = 25;
    const CameraTransform transform(camera, 320, 200);
    const ClipVolume volume(transform, true);
    const auto planes = transform.frustumPlanes();
    constexpr std::uint32_t kViewVolume = kNearPlane | kFarPlane | kViewLeft | kViewRight | kViewBottom | kViewTop;
    int inside = 0;
    test::CaseFailures disagreements(std::string("the frustum planes and the clip volume disagree on a point, ") +
                                     (projection == Projection::perspective ? "perspective" : "orthographic"));
    for (int i = 0; i < 20000; ++i) {
      const dvec3 p(coordinate(random), coordinate(random), coordinate(random));
      double nearest = std::numeric_limits<double>::infinity();
      bool insidePlanes = true;
      for (const Plane& plane : planes) {
        nearest = std::min(nearest, std::abs(plane.distance(p)));
        insidePlanes = insidePlanes && plane.distance(p) >= 0;
      }
      if (nearest < 1e-9) continue;  // on a plane: either answer is within rounding
      const bool insideClip = (volume.outside(transform.clipFromWorld(p)) & kViewVolume) == 0;
      disagreements.expect(insidePlanes == insideClip, [&] {
        char text[96];
        std::snprintf(text, sizeof text, "(%g, %g, %g): %s the planes", p.x, p.y, p.z, insidePlanes ? "inside" : "outside");
        return std::string(text);
      });
      inside += insideClip;
    }
    EXPECT_NO_FAILED_CASES(disagreements);
    EXPECT_GT(inside, 200);  // the sample reaches into the volume, not only around it
    for (const Plane& plane : planes) EXPECT_NEAR(glm::length(plane.normal), 1.0, 1e-12);
  }
}

// ---------------------------------------------------------------------------------
// Backface culling

// Eyes all around a solid, near and far, including the six axis directions, from which
// some faces are seen exactly edge-on.
std::vector<dvec3> eyesAround() {
  std::vector<dvec3> eyes = {{3, 0, 0}, {-3, 0, 0}, {0, 3, 0}, {0, -3, 0}, {0, 0, 3}, {0, 0, -3}};
  const double golden = 2.399963229728653;  // the golden angle: directions spread evenly over the sphere
  for (int i = 0; i < 24; ++i) {
    const double y = 1 - (i + 0.5) / 12, r = std::sqrt(1 - y * y);
    const dvec3 direction(r * std::cos(golden * i), y, r * std::sin(golden * i));
    eyes.push_back(direction * (i % 2 ? 1.6 : 4.0));
  }
  return eyes;
}

TEST(Backface, ObjectAndScreenCullTheSameSetOnEveryClosedSolid) {
  const std::vector<std::pair<std::string, Mesh>> solids = {{"box", makeBox({1, 0.6, 0.8})},
                                                            {"sphere", makeSphere(0.7, 24, 12)},
                                                            {"cylinder", makeCylinder(0.5, 1.2, 20)},
                                                            {"cone", makeCone(0.6, 1.0, 16)}};
  test::CaseFailures disagreements("backface:object and backface:screen disagree on a triangle not seen edge-on");
  for (const auto& [solidName, mesh] : solids) {
    const std::string& name = solidName;  // a structured binding cannot be captured (clang 14)
    for (const Projection projection : {Projection::perspective, Projection::orthographic}) {
      for (const dvec3& eye : eyesAround()) {
        Camera camera;
        camera.projection = projection;
        camera.eye = eye;
        camera.up = std::abs(eye.y) > 0.99 * glm::length(eye) ? dvec3(0, 0, 1) : dvec3(0, 1, 0);
        camera.orthoHeight = 3;
        camera.near = 0.05;
        const Scene scene = test::sceneOf(camera, 64, 64, {mesh});
        const PreparedScene prepared(scene);
        const VisibleSet object = cull(prepared, "backface:object"), screen = cull(prepared, "backface:screen");
        const auto objectKept = keptMask(object, prepared.triangleCount()), screenKept = keptMask(screen, prepared.triangleCount());
        int culled = 0;
        for (std::uint32_t t = 0; t < prepared.triangleCount(); ++t) {
          culled += !objectKept[t];
          if (objectKept[t] == screenKept[t]) continue;
          // They may differ only on a triangle seen edge-on to within rounding (the eye
          // within 1e-9, relatively, of its plane), which covers no pixel: the object
          // test's exact sign and the screen test's rounded area may then disagree.
          const Triangle& tri = prepared.triangles()[t];
          const dvec3 &a = prepared.positions()[tri[0]], &b = prepared.positions()[tri[1]], &c = prepared.positions()[tri[2]];
          const dvec3 normal = glm::cross(b - a, c - a);
          const dvec3 towardsEye = projection == Projection::perspective ? eye - a : eye;
          disagreements.expect(std::abs(glm::dot(normal, towardsEye)) <= 1e-9 * glm::length(normal) * glm::length(towardsEye), [&] {
            char eyeText[96];
            std::snprintf(eyeText, sizeof eyeText, " from (%g, %g, %g), %s", eye.x, eye.y, eye.z,
                          projection == Projection::perspective ? "perspective" : "orthographic");
            return name + ": " + test::describeTriangle(prepared, t) + eyeText;
          });
        }
        // Seen from outside, a closed solid shows some of its triangles, never all.
        EXPECT_GT(culled, 0) << name;
        EXPECT_LT(culled, int(prepared.triangleCount())) << name;
      }
    }
  }
  EXPECT_NO_FAILED_CASES(disagreements);
}

TEST(Backface, ViewDirectionCullsVisibleSidesOfOffCenterCubes) {
  // hard/cull_off_center: each cube's inner side faces the eye, but its normal points
  // away from the view direction.
  Judged judged(test::sourcePath("scenes/hard/cull_off_center.toml"));
  const PreparedScene& scene = judged.loaded.prepared;
  const ReferenceImage& truth = judged.truth;
  const Frame unculled = test::renderZBuffer(scene);
  for (const std::string variant : {"object", "screen", "view-direction"}) {
    const VisibleSet kept = cull(scene, "backface:" + variant);
    const SurfaceError pixels = surfaceError(renderKept(scene, kept), truth);
    if (variant == "view-direction") {
      EXPECT_EQ(judged.falseCulls(kept), 4) << "the two inner sides, two triangles each";
      EXPECT_GT(pixels.pixelError, 0.03) << "the sides are gone from the image";
    } else {
      EXPECT_EQ(judged.falseCulls(kept), 0) << variant;
      EXPECT_EQ(pixels.wrongPixels, surfaceError(unculled, truth).wrongPixels) << variant;
    }
  }
  // Seen through an orthographic camera every sight line is parallel to the view axis,
  // and the shortcut is exact: it culls what the eye-position test culls.
  judged.loaded.scene.camera.projection = Projection::orthographic;
  judged.loaded.scene.camera.orthoHeight = 5;
  EXPECT_EQ(cull(scene, "backface:view-direction").triangles, cull(scene, "backface:object").triangles);
}

TEST(Backface, HalvesTheWorkOnAClosedSolidAndDepthTestingIsThenUnneeded) {
  // A single convex solid: what backface culling keeps never overlaps itself on screen,
  // so even drawing with no depth test gives the z-buffer's image.
  test::LoadedScene loaded(test::sourcePath("scenes/cube.toml"));
  const PreparedScene& scene = loaded.prepared;
  const Frame zbuffer = test::renderZBuffer(scene);
  zbuffer::Knobs noDepthTest;
  noDepthTest.depthTest = false;
  Stats stats;
  const VisibleSet kept = cull(scene, "backface", stats);
  EXPECT_EQ(stats.counter("backface: triangles tested"), 12);
  EXPECT_EQ(stats.counter("backface: triangles culled"), 6);  // three faces seen, three not
  EXPECT_EQ(renderKept(scene, kept, noDepthTest).ids, zbuffer.ids);
  // Without the culling, the back faces drawn last paint over the front.
  const VisibleSet all = VisibleSet::everything(scene);
  const Frame painted = renderKept(scene, all, noDepthTest);
  std::int64_t differing = 0;
  for (std::size_t i = 0; i < painted.ids.size(); ++i) differing += painted.ids[i] != zbuffer.ids[i];
  EXPECT_GT(differing, 1000);
  Stats noTest;
  test::render(scene, noDepthTest, 1, noTest);
  EXPECT_EQ(noTest.counter("fragments written"), noTest.counter("fragments tested"));
}

// ---------------------------------------------------------------------------------
// Frustum culling

TEST(Frustum, AnyVertexDropsAFloorBiggerThanTheView) {
  // hard/cull_big_floor: two floor triangles with every corner outside the view volume.
  Judged judged(test::sourcePath("scenes/hard/cull_big_floor.toml"));
  const PreparedScene& scene = judged.loaded.prepared;
  const VisibleSet anyVertex = cull(scene, "frustum:any-vertex"), perTriangle = cull(scene, "frustum:triangle");
  EXPECT_EQ(judged.falseCulls(anyVertex), 2);
  EXPECT_GT(surfaceError(renderKept(scene, anyVertex), judged.truth).pixelError, 0.4);
  EXPECT_EQ(judged.falseCulls(perTriangle), 0);
  EXPECT_EQ(renderKept(scene, perTriangle).ids, test::renderZBuffer(scene).ids);
}

TEST(Frustum, PlaneMaskingTestsFewerPlanesAndKeepsWhatTheBoxTestKeeps) {
  // trees: 136 objects around the camera, most outside the view.
  test::LoadedScene loaded(test::sourcePath("scenes/trees.toml"));
  Stats boxStats, bvhStats;
  const VisibleSet box = cull(loaded.prepared, "frustum:aabb", boxStats);
  const VisibleSet hierarchical = cull(loaded.prepared, "frustum:bvh", bvhStats);
  EXPECT_EQ(hierarchical.triangles, box.triangles);
  EXPECT_EQ(boxStats.counter("frustum: objects tested"), 136);
  EXPECT_GT(boxStats.counter("frustum: objects culled"), 60);
  EXPECT_GT(bvhStats.counter("frustum: bvh nodes visited"), 0);
  EXPECT_LT(bvhStats.counter("frustum: planes tested"), boxStats.counter("frustum: planes tested") / 2);
  EXPECT_LT(bvhStats.counter("frustum: objects tested"), 136);
}

TEST(Frustum, ObjectsOutOfViewCostNoVertexWork) {
  // dragons: four dragons around the camera, one in view.
  test::LoadedScene loaded(test::sourcePath("scenes/dragons.toml"));
  const PreparedScene& scene = loaded.prepared;
  Stats culled, unculled;
  const VisibleSet kept = cull(scene, "frustum:sphere", culled);
  const Frame frame = test::visibilityOf(scene, zbuffer::Knobs{}, 2, culled, &kept);
  const Frame reference = test::visibilityOf(scene, zbuffer::Knobs{}, 2, unculled);
  EXPECT_EQ(culled.counter("frustum: objects tested"), 4);
  EXPECT_EQ(culled.counter("frustum: objects culled"), 3);
  EXPECT_EQ(culled.counter("vertices transformed"), unculled.counter("vertices transformed") / 4);
  EXPECT_EQ(culled.counter("triangles in"), unculled.counter("triangles in") / 4);
  EXPECT_EQ(culled.counter("screen triangles"), unculled.counter("screen triangles"));
  EXPECT_EQ(frame.ids, reference.ids);
}

TEST(Culling, TheSameSetForAnyThreadCount) {
  test::LoadedScene loaded(test::sourcePath("scenes/counters.toml"));
  for (const std::string pipeline : {"backface:object", "backface:screen", "frustum:triangle", "backface,frustum:bvh"}) {
    Stats one, three;
    EXPECT_EQ(cull(loaded.prepared, pipeline, one, 1).triangles, cull(loaded.prepared, pipeline, three, 3).triangles) << pipeline;
  }
}

// hsr why's culling witness (culling.hpp): asked about every object, each stage's own
// test says what it found for every object it tested one by one, and what it says is
// what it did: the sphere and box tests name a plane exactly for the objects they
// culled, the map test says every texel hid the box exactly for those it culled, the
// portal search says its box lies within a view exactly for those it kept, the PVS that
// the set holds it exactly for those it kept. Watching changes nothing it keeps.
TEST(Culling, TheWitnessSaysWhatEachStageDid) {
  struct Case {
    const char* scene;
    const char* pipeline;
    const char* culledSays;  // what the finding begins with, exactly for the objects the stage removed
    const char* keptSays;
    const char* keptAlsoSays = "\n";  // another beginning for a kept object (a box off the map, or crossing the near plane)
    const char* culledAlsoSays = "\n";  // another for a culled one (a cell reached, the box outside every view)
  };
  std::int64_t culledSeen = 0;
  for (const Case& c : {Case{"scenes/trees.toml", "frustum:sphere", "its bounding sphere lies wholly outside", "its bounding sphere lies outside none"},
                        Case{"scenes/trees.toml", "frustum:aabb", "its box lies wholly outside", "its box lies outside none"},
                        Case{"scenes/city.toml", "occlusion", "every texel of its footprint", "texel (", "its box"},
                        Case{"scenes/city.toml", "occlusion:pyramid=on", "every texel of its footprint", "texel (", "its box"},
                        Case{"scenes/hard/occ_gap.toml", "occlusion:raster=center", "every texel of its footprint", "texel (", "its box"},
                        Case{"scenes/hard/portal_rooms.toml", "portals", "no chain of portals", "a chain of portals from the eye's cell reaches", "\n",
                             "a chain of portals reaches"},
                        Case{"scenes/hard/portal_rooms.toml", "pvs", "it is not in", "it is in"},
                        Case{"scenes/trees.toml", "frustum:bvh", "the box of a BVH node holding it", "its box, reached in a BVH leaf",
                             "\n", "its box, reached in a BVH leaf at depth"}}) {
    const std::string where = std::string(c.scene) + " --cull " + c.pipeline;
    test::LoadedScene loaded(test::sourcePath(c.scene));
    const culling::Pipeline pipeline = culling::parsePipeline(c.pipeline);
    Stats plainStats, stats;
    const VisibleSet plain = culling::runPipeline(loaded.prepared, pipeline, 1, plainStats);
    culling::CullingWitness why;
    for (std::uint32_t i = 0; i < loaded.prepared.instances().size(); ++i) why.instances.push_back(i);
    const VisibleSet kept = culling::runPipeline(loaded.prepared, pipeline, 1, stats, nullptr, nullptr, &why);
    ASSERT_EQ(kept.triangles, plain.triangles) << where;
    ASSERT_EQ(why.byStage.size(), 1u) << where;
    for (std::uint32_t i = 0; i < loaded.prepared.instances().size(); ++i) {
      const Instance& object = loaded.prepared.instances()[i];
      const bool keeps = std::binary_search(kept.triangles.begin(), kept.triangles.end(), object.firstTriangle);
      const std::string& found = why.byStage[0].found[i];
      const bool saysWhatItDid = keeps ? found.rfind(c.keptSays, 0) == 0 || found.rfind(c.keptAlsoSays, 0) == 0
                                       : found.rfind(c.culledSays, 0) == 0 || found.rfind(c.culledAlsoSays, 0) == 0;
      EXPECT_TRUE(saysWhatItDid) << where << ", object " << i << (keeps ? " kept" : " culled") << ": " << found;
      culledSeen += !keeps;
    }
  }
  EXPECT_GT(culledSeen, 20) << "too few objects culled to test anything";
}

// The tests of triangles (backface, the frustum's per-triangle variants) say what they
// found for each triangle asked about; the occlusion queries, for each object, what was
// decided at its leaf or where the walk stopped above it.
TEST(Culling, TheWitnessSaysWhatEachTriangleTestAndEachQueryFound) {
  struct Case {
    const char* scene;
    const char* pipeline;
    std::vector<const char*> culledSays, keptSays;  // one of them is in what it found, for each triangle (object) it removed (kept)
  };
  std::int64_t culledSeen = 0;
  const std::vector<const char*> outsideOnePlane{"all three of its corners lie outside the view volume's"};
  for (const Case& c : {Case{"scenes/counters.toml", "backface", {"the eye lies behind its plane"}, {"the eye lies in front of its plane"}},
                        Case{"scenes/counters.toml", "backface:screen", {"clockwise on the screen or is flat"}, {"counter-clockwise on the screen", "nothing projects"}},
                        Case{"scenes/counters.toml", "backface:view-direction", {"turns away from the eye"}, {"turns toward the eye"}},
                        Case{"scenes/trees.toml", "frustum:triangle", outsideOnePlane, {"no plane of the view volume has all three"}},
                        Case{"scenes/trees.toml", "frustum:any-vertex", {"none of its corners lies inside all six planes"}, {"lies inside all six planes"}},
                        Case{"scenes/city.toml", "occlusion:queries:stop-and-wait", {"hidden, nothing below it drawn", "outside the view volume"},
                             {"visible", "drawn"}},
                        Case{"scenes/city.toml", "occlusion:queries:chc", {"hidden, nothing below it drawn", "outside the view volume"}, {"visible", "drawn"}},
                        Case{"scenes/city.toml", "occlusion:queries:chcpp", {"nothing below it drawn", "outside the view volume"}, {"visible", "drawn"}}}) {
    const std::string where = std::string(c.scene) + " --cull " + c.pipeline;
    test::LoadedScene loaded(test::sourcePath(c.scene));
    const PreparedScene& scene = loaded.prepared;
    const culling::Pipeline pipeline = culling::parsePipeline(c.pipeline);
    Stats plainStats, stats;
    const VisibleSet plain = culling::runPipeline(scene, pipeline, 1, plainStats);
    const bool byObject = std::string(c.pipeline).starts_with("occlusion");
    culling::CullingWitness why;
    for (std::uint32_t i = 0; i < (byObject ? scene.instances().size() : scene.triangles().size()); ++i)
      (byObject ? why.instances : why.triangles).push_back(i);
    const VisibleSet kept = culling::runPipeline(scene, pipeline, 1, stats, nullptr, nullptr, &why);
    ASSERT_EQ(kept.triangles, plain.triangles) << where;
    ASSERT_EQ(why.byStage.size(), 1u) << where;
    const std::vector<std::string>& found = byObject ? why.byStage[0].found : why.byStage[0].foundForTriangle;
    for (std::uint32_t i = 0; i < found.size(); ++i) {
      const std::uint32_t first = byObject ? scene.instances()[i].firstTriangle : i;
      const bool keeps = std::binary_search(kept.triangles.begin(), kept.triangles.end(), first);
      const std::vector<const char*>& says = keeps ? c.keptSays : c.culledSays;
      const bool saysWhatItDid = std::any_of(says.begin(), says.end(), [&](const char* part) { return found[i].find(part) != std::string::npos; }) &&
                                 (!keeps || found[i].find("nothing below it drawn") == std::string::npos);
      EXPECT_TRUE(saysWhatItDid) << where << (byObject ? ", object " : ", triangle ") << i << (keeps ? " kept" : " culled") << ": " << found[i];
      culledSeen += !keeps;
    }
  }
  EXPECT_GT(culledSeen, 100) << "too few culled to test anything";
}

TEST(Culling, PipelineSyntax) {
  EXPECT_EQ(culling::describePipeline(culling::parsePipeline("backface,frustum")), "backface:object,frustum:sphere");
  EXPECT_EQ(culling::describePipeline(culling::parsePipeline("frustum:bvh,backface:screen")), "frustum:bvh,backface:screen");
  EXPECT_TRUE(culling::parsePipeline("frustum:any-vertex").front().wrong());
  EXPECT_FALSE(culling::parsePipeline("frustum:triangle").front().wrong());
  for (const std::string bad : {"", "backfaces", "frustum:cone", "backface,", "backface:object:screen"})
    EXPECT_THROW(culling::parsePipeline(bad), InputError) << bad;
}

// ---------------------------------------------------------------------------------
// Every shipped scene, against the exact reference (320 pixels wide, as the goldens)

class ShippedScene : public testing::TestWithParam<std::filesystem::path> {};

TEST_P(ShippedScene, CorrectStagesDropNothingVisibleAndChangeNoPixel) {
  Judged judged(GetParam(), 320);
  const PreparedScene& scene = judged.loaded.prepared;
  const std::vector<std::uint8_t>& visible = judged.visible;
  const Frame unculled = test::renderZBuffer(scene);

  // Frustum culling: no false cull, and (as it removes only what the geometry stage
  // would reject) not one pixel changes.
  for (const std::string variant : {"sphere", "aabb", "bvh", "triangle"}) {
    const VisibleSet kept = cull(scene, "frustum:" + variant);
    EXPECT_EQ(judged.falseCulls(kept), 0) << variant;
    EXPECT_EQ(renderKept(scene, kept).ids, unculled.ids) << variant;
  }

  // Backface culling is right exactly where its premise holds: every triangle it drops
  // that the reference sees is one whose back the reference sees (an open surface from
  // behind), and a pixel changes only where the unculled image showed such a back.
  ExactPredicates predicates;
  for (const std::string variant : {"object", "screen"}) {
    const VisibleSet kept = cull(scene, "backface:" + variant);
    const auto keptTriangles = keptMask(kept, scene.triangleCount());
    test::CaseFailures culled("backface:" + variant + " dropped a visible triangle whose front the reference shows");
    for (std::uint32_t t = 0; t < scene.triangleCount(); ++t) {
      const bool falseCull = visible[t] && !keptTriangles[t];
      culled.expect(!falseCull || showsBackFace(scene, t + 1, predicates), [&] { return test::describeTriangle(scene, t); });
    }
    EXPECT_NO_FAILED_CASES(culled);
    const Frame frame = renderKept(scene, kept);
    test::CaseFailures changedPixels("backface:" + variant + " changed a pixel that did not show a back face");
    for (std::size_t i = 0; i < frame.ids.size(); ++i) {
      const bool changed = frame.ids[i] != unculled.ids[i];
      changedPixels.expect(!changed || showsBackFace(scene, unculled.ids[i], predicates), [&] {
        return test::describePixel(frame, i) + ": " + test::describeTriangle(scene, unculled.ids[i] - 1);
      });
    }
    EXPECT_NO_FAILED_CASES(changedPixels);
  }
}

std::string sceneName(const testing::TestParamInfo<std::filesystem::path>& info) {
  std::string name = std::filesystem::relative(info.param, test::sourcePath("scenes")).replace_extension().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Culling, ShippedScene, testing::ValuesIn(test::shippedScenes()), sceneName);

}  // namespace
}  // namespace hsr
