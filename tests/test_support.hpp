// Shared helpers for the tests: build small scenes in code, render them, and an
// independent visibility oracle (brute-force rays) that shares no code with the
// rasterizer, so agreement between the two means something.
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "algorithms/abuffer/abuffer.hpp"
#include "algorithms/painter/painter.hpp"
#include "algorithms/ray_casting/ray_casting.hpp"
#include "algorithms/registry.hpp"
#include "algorithms/warnock/warnock.hpp"
#include "algorithms/watkins/watkins.hpp"
#include "algorithms/weiler_atherton/weiler_atherton.hpp"
#include "algorithms/zbuffer/zbuffer.hpp"
#include "pipeline/pipeline.hpp"
#include "renderer/geometry/camera.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/raster/depth.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "renderer/reference/agreement.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/scene/scene.hpp"

namespace hsr::test {

// The pieces of edge e of a line drawing drawn with hsr why --edge watching that edge,
// or nothing when that drawing differs anywhere from the one drawn without (a piece's
// edge, QI or ends): watching must change nothing.
inline std::optional<std::vector<LineSegment>> piecesIfUnchanged(const LineSet& plain, const LineSet& watched, std::uint32_t e) {
  if (watched.segments.size() != plain.segments.size()) return std::nullopt;
  std::vector<LineSegment> pieces;
  for (std::size_t i = 0; i < watched.segments.size(); ++i) {
    const LineSegment &mine = watched.segments[i], &theirs = plain.segments[i];
    if (mine.edge != theirs.edge || mine.qi != theirs.qi || mine.begin != theirs.begin || mine.end != theirs.end) return std::nullopt;
    if (mine.edge == e) pieces.push_back(mine);
  }
  return pieces;
}

inline std::filesystem::path sourcePath(const std::string& relative) { return std::filesystem::path(HSR_SOURCE_DIR) / relative; }

// Every scene file under scenes/, sorted.
// scenes/study/ holds the occlusion studies' levels: thousands of objects each, made to
// be measured by the studies and judged by the occlusion tests, too big for Newell's
// pairs and the line algorithms within the test run's budget. The per-algorithm
// agreement tests and the goldens skip them.
inline bool isStudyLevel(const std::filesystem::path& scene) { return scene.parent_path().filename() == "study"; }

inline std::vector<std::filesystem::path> shippedScenes() {
  std::vector<std::filesystem::path> scenes;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(sourcePath("scenes")))
    if (entry.path().extension() == ".toml") scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

// A scene file loaded and prepared, optionally at another width (same aspect ratio).
struct LoadedScene {
  Scene scene;
  PreparedScene prepared;
  explicit LoadedScene(const std::filesystem::path& file, int width = 0) : scene(loadScene(file)), prepared(scene) {
    if (width > 0) prepared.setSize(width, std::max(1, width * scene.height / scene.width));
  }
};

// Whether two RGBA8 images differ at a pixel by more than `tolerance` levels in some
// color channel.
inline bool colorDiffers(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b, std::size_t pixel, int tolerance) {
  for (std::size_t c = 0; c < 3; ++c)
    if (std::abs(int(a[4 * pixel + c]) - int(b[4 * pixel + c])) > tolerance) return true;
  return false;
}

inline std::filesystem::path outputPath(const std::string& name) {
  std::filesystem::create_directories(HSR_TEST_OUTPUT_DIR);
  return std::filesystem::path(HSR_TEST_OUTPUT_DIR) / name;
}

// An orthographic camera looking down -z whose world units are pixels: world (x, y)
// lands on pixel coordinates (x + width/2, height/2 - y).
inline Camera pixelCamera(int height) {
  Camera camera;
  camera.projection = Projection::orthographic;
  camera.eye = {0, 0, 10};
  camera.target = {0, 0, 0};
  camera.orthoHeight = height;
  camera.near = 1;
  camera.far = 100;
  return camera;
}

inline Scene sceneOf(const Camera& camera, int width, int height, const std::vector<Mesh>& meshes) {
  Scene scene;
  scene.camera = camera;
  scene.width = width;
  scene.height = height;
  for (const Mesh& mesh : meshes) {
    SceneObject object;
    object.mesh = std::make_shared<const Mesh>(mesh);
    scene.objects.push_back(object);
  }
  return scene;
}

inline Mesh triangleMesh(const std::vector<dvec3>& corners) {
  Mesh mesh;
  mesh.positions = corners;
  for (std::uint32_t i = 0; i + 2 < corners.size(); i += 3) mesh.triangles.push_back({i, i + 1, i + 2});
  return mesh;
}

// For a pixelCamera(48) scene of 64 x 48: two planes covering the image, z = (x - 5.3) /
// 100 and its opposite, crossing along the vertical line x = 5.3 (pixel x 37.3, between
// the centers of columns 36 and 37); the first is nearer right of it, the second left.
inline std::vector<Mesh> crossingPlanes() {
  const auto plane = [](double sign) {
    return triangleMesh({{-300, -300, sign * -3.053}, {300, -300, sign * 2.947}, {0, 300, sign * -0.053}});
  };
  return {plane(1), plane(-1)};
}

// The scene seen the same way after the world map p -> scale p + offset: the camera
// moves with it, and each object's transform is composed with it (objects must be
// single, not instanced, for that: the map is not applied to instancing offsets).
inline Camera movedAndScaled(Camera camera, double scale, const dvec3& offset) {
  camera.eye = camera.eye * scale + offset;
  camera.target = camera.target * scale + offset;
  camera.near *= scale;
  camera.far *= scale;
  camera.orthoHeight *= scale;
  return camera;
}

inline Scene movedAndScaled(Scene scene, double scale, const dvec3& offset) {
  for (SceneObject& object : scene.objects) {
    object.transform.translate = object.transform.translate * scale + offset;
    object.transform.scale *= scale;
  }
  scene.camera = movedAndScaled(scene.camera, scale, offset);
  return scene;
}

// The cases a per-pixel or per-triangle check fails on, reported as one failure: the
// first kShown described, the rest counted. A broken algorithm fails on thousands of
// pixels at once; one line each would bury the first, most telling one.
class CaseFailures {
 public:
  static constexpr std::size_t kShown = 20;
  explicit CaseFailures(std::string check) : check_(std::move(check)) {}
  // Records a failing case; describe() is called only for the first kShown.
  template <typename Describe>
  void fail(Describe&& describe) {
    if (count_++ < kShown) shown_.push_back(describe());
  }
  template <typename Describe>
  void expect(bool holds, Describe&& describe) {
    if (!holds) fail(describe);
  }
  std::size_t count() const { return count_; }
  std::string report() const {
    std::string text = std::to_string(count_) + " case" + (count_ == 1 ? "" : "s") + " fail: " + check_;
    for (const std::string& line : shown_) text += "\n  " + line;
    if (count_ > shown_.size()) text += "\n  ... and " + std::to_string(count_ - shown_.size()) + " more";
    return text;
  }

 private:
  std::string check_;
  std::size_t count_ = 0;
  std::vector<std::string> shown_;
};
#define EXPECT_NO_FAILED_CASES(failures) EXPECT_EQ((failures).count(), 0u) << (failures).report()

// A triangle as a reader would find it: "triangle 17 of object 'bunny'" (with its copy
// when the object has several).
inline std::string describeTriangle(const PreparedScene& scene, std::uint32_t triangle) {
  const Instance& instance = scene.instanceOf(triangle);
  const SceneObject& object = scene.scene().objects[instance.object];
  std::string text = "triangle " + std::to_string(triangle - instance.firstTriangle) + " of object " +
                     (object.name.empty() ? std::to_string(instance.object) + " (unnamed)" : "'" + object.name + "'");
  if (object.instancing.copyCount() > 1) text += " (copy " + std::to_string(instance.copy) + ")";
  return text;
}
// A pixel by its coordinates: "pixel (12, 40)".
inline std::string describePixel(const Frame& frame, std::size_t pixel) {
  return "pixel (" + std::to_string(pixel % std::size_t(frame.width)) + ", " + std::to_string(pixel / std::size_t(frame.width)) + ")";
}

// An algorithm's knobs given as its own struct, for the registry and the pipeline.
inline const AlgorithmEntry& algorithmOf(const zbuffer::Knobs&) { return findAlgorithm("zbuffer"); }
inline const AlgorithmEntry& algorithmOf(const ray_casting::Knobs&) { return findAlgorithm("ray_casting"); }
inline const AlgorithmEntry& algorithmOf(const painter::Knobs&) { return findAlgorithm("painter"); }
inline const AlgorithmEntry& algorithmOf(const warnock::Knobs&) { return findAlgorithm("warnock"); }
inline const AlgorithmEntry& algorithmOf(const watkins::Knobs&) { return findAlgorithm("watkins"); }
inline const AlgorithmEntry& algorithmOf(const weiler_atherton::Knobs&) { return findAlgorithm("weiler_atherton"); }
inline const AlgorithmEntry& algorithmOf(const abuffer::Knobs&) { return findAlgorithm("abuffer"); }
inline KnobValues valuesOf(const zbuffer::Knobs& knobs) { return zbuffer::knobTable().valuesOf(knobs); }
inline KnobValues valuesOf(const ray_casting::Knobs& knobs) { return ray_casting::knobTable().valuesOf(knobs); }
inline KnobValues valuesOf(const painter::Knobs& knobs) { return painter::knobTable().valuesOf(knobs); }
inline KnobValues valuesOf(const warnock::Knobs& knobs) { return warnock::knobTable().valuesOf(knobs); }
inline KnobValues valuesOf(const watkins::Knobs& knobs) { return watkins::knobTable().valuesOf(knobs); }
inline KnobValues valuesOf(const weiler_atherton::Knobs& knobs) { return weiler_atherton::knobTable().valuesOf(knobs); }
inline KnobValues valuesOf(const abuffer::Knobs& knobs) { return abuffer::knobTable().valuesOf(knobs); }

// The whole render of a surface algorithm (pipeline/pipeline.hpp): visibility, then the
// passes the scene's effects call for.
template <typename Knobs>
Frame render(const PreparedScene& scene, const Knobs& knobs, int threads, Stats& stats) {
  return pipeline::render(scene, {&algorithmOf(knobs), valuesOf(knobs)}, threads, stats).frame;
}

// The algorithm's visibility pass alone, over `triangles` (what culling stages kept; all
// when null): the frame's ids and depth.
template <typename Knobs>
Frame visibilityOf(const PreparedScene& scene, const Knobs& knobs, int threads, Stats& stats, const VisibleSet* triangles = nullptr) {
  Visibility visibility{Frame(scene.width(), scene.height()), std::nullopt};
  algorithmOf(knobs).visibility({scene, scene.camera(), triangles, threads, stats}, valuesOf(knobs), visibility);
  return std::move(visibility.frame);
}

// Why the pipeline refuses the algorithm with these knobs on the scene ("" when it does not).
template <typename Knobs>
std::string refusalOf(const PreparedScene& scene, const Knobs& knobs) {
  return pipeline::refusal(scene, {&algorithmOf(knobs), valuesOf(knobs)});
}

inline Frame renderZBuffer(const PreparedScene& scene, zbuffer::Variant variant = zbuffer::Variant::full,
                           DepthFormat format = DepthFormat::float32, int threads = 1) {
  Stats stats;
  return render(scene, zbuffer::Knobs{variant, format}, threads, stats);
}

inline ray_casting::Knobs rayCastingKnobs(ray_casting::Variant variant) {
  ray_casting::Knobs knobs;
  knobs.variant = variant;
  return knobs;
}

inline Frame renderRayCasting(const PreparedScene& scene, const ray_casting::Knobs& knobs, int threads = 2) {
  Stats stats;
  return render(scene, knobs, threads, stats);
}

inline painter::Knobs painterKnobs(painter::Variant variant) {
  painter::Knobs knobs;
  knobs.variant = variant;
  return knobs;
}

inline Frame renderPainter(const PreparedScene& scene, const painter::Knobs& knobs, int threads = 2) {
  Stats stats;
  return render(scene, knobs, threads, stats);
}

// What an image-space algorithm that samples each pixel center exactly must show: the
// screen triangles of the geometry stage, each pixel center tested against every one
// whose box holds it, the nearest plane depth in double precision kept, a tie going to
// the earlier triangle. The simplest loop there is (a z-buffer of doubles), against
// which the subdividing and scanning algorithms are checked: ids, and depth as the
// float of the view distance.
inline Frame sampledOneByOne(const PreparedScene& scene) {
  Stats stats;
  const ScreenGeometry geometry = buildScreenTriangles(scene, {}, 1, stats);
  Frame frame(scene.width(), scene.height());
  std::fill(frame.ids.begin(), frame.ids.end(), conventions::kBackgroundId);
  std::fill(frame.depth.begin(), frame.depth.end(), std::numeric_limits<float>::infinity());
  std::vector<double> nearest(frame.pixelCount(), std::numeric_limits<double>::infinity());
  const double nearer = geometry.camera.perspective() ? -1 : 1;  // t is 1/distance under perspective
  for (const ScreenTriangle& tri : geometry.triangles)
    for (int y = tri.minY; y <= tri.maxY; ++y)
      rasterizeSpan(tri, y, tri.minX, tri.maxX + 1, [&](int x) {
        const std::size_t pixel = std::size_t(y) * std::size_t(frame.width) + std::size_t(x);
        const double t = tri.depthAt(x + 0.5, y + 0.5);
        if (!(nearer * t < nearest[pixel])) return;
        nearest[pixel] = nearer * t;
        frame.ids[pixel] = tri.triangle + 1;
        frame.depth[pixel] = static_cast<float>(geometry.camera.distanceFromScreenAffine(t));
      });
  return frame;
}

// The shares of every one of samples x samples points of each pixel traced by the
// reference (an image `samples` times finer, width x height the scene's size): what
// traceExactShares must give, without its survey and proof.
inline PixelShares everyPointTraced(const Scene& scene, int width, int height, int samples, int threads) {
  PreparedScene fine(scene);
  fine.setSize(width * samples, height * samples);
  Stats stats;
  return sharesOfSamples(traceReference(fine, threads, stats).frame.ids, width, height, samples);
}

// Whether two frames hold the same depth, bit for bit (NaN and -0 included).
inline bool sameDepthBits(const Frame& a, const Frame& b) {
  return a.distances().size() == b.distances().size() && std::memcmp(a.distances().data(), b.distances().data(), a.distances().size() * sizeof(float)) == 0;
}

// A frame against sampledOneByOne's: the same id at every pixel (the first that differ
// named) and the same depth bits. `where` names the algorithm and scene.
inline void expectSameAsSampledOneByOne(const Frame& frame, const Frame& sampled, const std::string& where) {
  CaseFailures failures("pixels where " + where + " and the per-pixel loop differ");
  for (std::size_t p = 0; p < frame.pixelCount(); ++p)
    failures.expect(frame.ids[p] == sampled.ids[p], [&] { return describePixel(frame, p) + ", per-pixel id " + std::to_string(sampled.ids[p]); });
  EXPECT_NO_FAILED_CASES(failures);
  EXPECT_TRUE(sameDepthBits(frame, sampled)) << where;
}

// Nearest hit of a ray among all triangles with a view distance in [near, far]
// (Möller–Trumbore, double precision): returns triangle index + 1, or 0 for none.
inline std::uint32_t nearestHit(const PreparedScene& scene, const CameraTransform& camera, const Ray& ray) {
  const dvec3 forward = glm::normalize(camera.camera().target - camera.camera().eye);
  double nearest = camera.camera().far;
  std::uint32_t id = 0;
  for (std::uint32_t i = 0; i < scene.triangleCount(); ++i) {
    const Triangle& t = scene.triangles()[i];
    const dvec3 a = scene.positions()[t[0]], e1 = scene.positions()[t[1]] - a, e2 = scene.positions()[t[2]] - a;
    const dvec3 p = glm::cross(ray.direction, e2);
    const double det = glm::dot(e1, p);
    if (det == 0) continue;
    const dvec3 s = ray.origin - a;
    const double u = glm::dot(s, p) / det, v = glm::dot(ray.direction, glm::cross(s, e1)) / det;
    if (u < 0 || v < 0 || u + v > 1) continue;
    const double along = glm::dot(e2, glm::cross(s, e1)) / det;
    const double distance = along * glm::dot(ray.direction, forward);  // distance along the view axis
    if (along > 0 && distance >= camera.camera().near && distance < nearest) {
      nearest = distance;
      id = i + 1;
    }
  }
  return id;
}

struct Agreement {
  long clearPixels = 0;  // pixels whose answer cannot depend on snapping (see below)
  long mismatches = 0;   // clear pixels where the frame's id differs from the rays'
};

// The classification of an algorithm's differences from the reference lives in the core
// (renderer/reference/agreement.hpp), where hsr grade uses it too.
using hsr::classifyDifferences;
using hsr::classifyWrongPixels;
using hsr::coplanar;
using hsr::depthFormatTie;
using hsr::DepthTie;
using hsr::distanceToProjectedEdges;
using hsr::float32DepthTie;
using hsr::hitDistance;
using hsr::kSnapDistance;
using hsr::nearestProjectedEdge;
using hsr::projectedOutline;
using hsr::WrongPixels;

// Compares a frame's ids with brute-force rays. Snapping moves vertices by at most
// 1/512 pixel, so a pixel is "clear" when its center is at least 0.01 pixel from the
// projected (near-clipped) outline of every triangle, and the rays through its center
// and four points 0.01 pixel away all hit the same triangle. On a clear pixel the
// rasterizer must agree exactly.
inline Agreement agreementWithRays(const PreparedScene& scene, const Frame& frame) {
  const CameraTransform& camera = scene.camera();
  std::vector<std::uint32_t> inFront;
  for (std::uint32_t t = 0; t < scene.triangleCount(); ++t)
    if (!projectedOutline(scene, camera, t).empty()) inFront.push_back(t);
  Agreement result;
  const double offsets[5][2] = {{0, 0}, {0.01, 0}, {-0.01, 0}, {0, 0.01}, {0, -0.01}};
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      const dvec2 center(x + 0.5, y + 0.5);
      const bool nearAnEdge = std::any_of(inFront.begin(), inFront.end(), [&](std::uint32_t t) {
        return distanceToProjectedEdges(scene, camera, t, center) < 0.01;
      });
      if (nearAnEdge) continue;
      std::uint32_t ids[5];
      for (int k = 0; k < 5; ++k)
        ids[k] = nearestHit(scene, camera, camera.rayThroughPixel(x + 0.5 + offsets[k][0], y + 0.5 + offsets[k][1]));
      if (std::count(ids, ids + 5, ids[0]) != 5) continue;
      ++result.clearPixels;
      if (frame.ids[std::size_t(y) * std::size_t(frame.width) + std::size_t(x)] != ids[0]) ++result.mismatches;
    }
  return result;
}

struct CommandResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

inline CommandResult runCommand(const std::string& command) {
  CommandResult result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) result.output += buffer;
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace hsr::test
