// Occlusion culling (occlusion.hpp has the methods and the knobs).
#include "algorithms/culling/occlusion/occlusion.hpp"

#include "algorithms/culling/occlusion/queries.hpp"
#include "renderer/steps/why.hpp"
#include "renderer/util/simd.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace hsr::culling::occlusion {
namespace {

// How much of the view an object can hide: its world volume, or the solid angle of its
// bounding sphere from the eye (the projected area under orthographic projection).
double occluderScore(const CameraTransform& camera, Occluders occluders, const Instance& instance) {
  if (occluders == Occluders::volume) {
    const dvec3 size = instance.box.hi - instance.box.lo;
    return size.x * size.y * size.z;
  }
  const double r = instance.sphereRadius;
  if (!camera.perspective()) return r * r;
  const double distance = glm::length(instance.sphereCenter - camera.camera().eye);
  if (distance <= r) return 4 * std::numbers::pi;  // the eye is inside: it fills the view
  // The cap a sphere of radius r subtends at distance D: 2 pi (1 - cos(asin(r / D))).
  return 2 * std::numbers::pi * (1 - std::sqrt(1 - (r / distance) * (r / distance)));
}

}  // namespace

StageEntry stage() {
  StageEntry entry = stageEntry("occlusion", "drop objects hidden behind nearer ones, by their boxes against a small depth map", knobTable());
  entry.mayDropVisible = [](const KnobValues& values) {
    const Knobs& knobs = values.as<Knobs>();
    if (knobs.method == Method::queries) return knobs.strategy == QueryStrategy::delayed || knobs.threshold > 0;
    return knobs.method == Method::previousFrame || knobs.rule == Rule::center;
  };
  entry.conflict = [](const KnobValues& values) {
    const Knobs& knobs = values.as<Knobs>();
    const Knobs defaults;
    if (knobs.occluders == Occluders::all && !(knobs.fraction == defaults.fraction))
      return std::string("fraction applies only with occluders=volume or solid-angle");
    const bool chcppKnobsChanged = knobs.batch != defaults.batch || knobs.assumeVisible != defaults.assumeVisible ||
                                   knobs.multiqueries != defaults.multiqueries || knobs.tightBounds != defaults.tightBounds;
    if (knobs.method == Method::queries && knobs.strategy != QueryStrategy::chcpp && chcppKnobsChanged)
      return std::string("batch, assume-visible, multiqueries and tight-bounds apply only to the chcpp strategy");
    return std::string();
  };
  entry.run = [](const KnobValues& values, const StageInput& input) {
    const Knobs& knobs = values.as<Knobs>();
    if (knobs.method == Method::queries)
      return cullWithQueries(input.scene, input.camera, knobs, input.in, input.memory, input.previous ? input.previous->gpu : nullptr,
                             input.stats, input.why);
    return cull(input.scene, input.camera, knobs, input.in, input.previous, input.stats, input.steps, input.why);
  };
  return entry;
}

std::optional<std::array<dvec3, 8>> boxOfSolid(const PreparedScene& scene, const Instance& instance) {
  const Solid& solid = scene.scene().objects[instance.object].solid;
  if (solid.kind != Solid::Kind::box) return std::nullopt;
  Aabb own;
  own.lo = -0.5 * solid.size, own.hi = 0.5 * solid.size;
  std::array<dvec3, 8> corners = cornersOf(own);
  for (dvec3& corner : corners) corner = dvec3(instance.worldFromObject * dvec4(corner, 1));
  return corners;
}

void drawOccluder(const PreparedScene& scene, const Instance& instance, OccluderRasterizer& rasterizer) {
  if (const auto solid = boxOfSolid(scene, instance)) {
    rasterizer.box(*solid);
    return;
  }
  const std::vector<dvec3>& positions = scene.positions();
  for (std::uint32_t t = instance.firstTriangle; t < instance.firstTriangle + instance.triangleCount; ++t) {
    const Triangle& triangle = scene.triangles()[t];
    rasterizer.triangle(positions[triangle[0]], positions[triangle[1]], positions[triangle[2]]);
  }
}

double estimatedDepthComplexity(const PreparedScene& scene, const MapView& view, const VisibleSet& in) {
  const double texels = double(view.width) * double(view.height);
  double covered = 0;
  for (const std::uint32_t instance : instancesIn(scene, in)) {
    const BoxFootprint box = footprint(view, scene.instances()[instance].box);
    covered += box.crossesNear ? texels : box.empty() ? 0.0 : double(box.x1 - box.x0) * double(box.y1 - box.y0);
  }
  return covered / texels;
}

std::vector<std::uint32_t> chooseOccluders(const PreparedScene& scene, const CameraTransform& camera, const Knobs& knobs,
                                           const VisibleSet& in) {
  std::vector<std::uint32_t> candidates = instancesIn(scene, in);
  if (knobs.occluders == Occluders::all || candidates.empty()) return candidates;
  const std::size_t count =
      std::clamp<std::size_t>(std::size_t(std::ceil(knobs.fraction.value / 100 * double(candidates.size()))), 1, candidates.size());
  std::vector<double> score(scene.instances().size());
  for (const std::uint32_t instance : candidates)
    score[instance] = occluderScore(camera, knobs.occluders, scene.instances()[instance]);
  // The largest first, ties to the earlier object: the same choice on every run.
  std::stable_sort(candidates.begin(), candidates.end(), [&](std::uint32_t a, std::uint32_t b) { return score[a] > score[b]; });
  candidates.resize(count);
  std::sort(candidates.begin(), candidates.end());
  return candidates;
}

namespace {

// How many occluders ahead their data is asked for (renderer/util/simd.hpp, prefetch): on
// the city at 1920 x 1080 (occlusion_bench, least of 4 x 5 runs) 3.93 ms without, 3.40
// at 4 ahead, 3.37 at 8.
constexpr std::size_t kPrefetchAhead = 8;

// The positions of `keys` in increasing order of key, equal keys in position order: an
// LSD radix sort of the keys' bits made monotonic (a float's bits order as its value
// when the sign bit is flipped on positives and every bit on negatives), a byte per
// pass. For the thousands of occluders of a frame, a tenth of std::sort's time, whose
// comparisons the branch predictor cannot guess.
std::vector<std::uint32_t> nearestFirst(const std::vector<float>& keys) {
  std::vector<std::uint32_t> order(keys.size()), sorted(keys.size());
  std::vector<std::uint32_t> monotonic(keys.size());
  for (std::uint32_t i = 0; i < keys.size(); ++i) {
    const auto bits = bitCast<std::uint32_t>(keys[i]);
    monotonic[i] = bits & 0x8000'0000u ? ~bits : bits | 0x8000'0000u;
    order[i] = i;
  }
  for (int shift = 0; shift < 32; shift += 8) {
    std::array<std::uint32_t, 257> start{};
    for (const std::uint32_t position : order) ++start[(monotonic[position] >> shift & 0xFF) + 1];
    for (std::size_t digit = 1; digit < start.size(); ++digit) start[digit] += start[digit - 1];
    for (const std::uint32_t position : order) sorted[start[monotonic[position] >> shift & 0xFF]++] = position;
    order.swap(sorted);
  }
  return order;
}

}  // namespace

DepthMap occluderDepthMap(const PreparedScene& scene, const MapView& view, const Knobs& knobs,
                          const std::vector<std::uint32_t>& occluders, Stats& stats) {
  PhaseTimer timer(stats, "occlusion: rasterize occluders");
  DepthMap map(view.width, view.height);
  // The occluders' footprints on the map. One that misses the map would draw nothing:
  // it is left out before the sort.
  std::vector<BoxFootprint> boxes;
  boxes.reserve(occluders.size());
  std::vector<std::uint32_t> onMap;  // the occluders of `boxes`, as instances
  onMap.reserve(occluders.size());
  std::vector<float> nearest;
  nearest.reserve(occluders.size());
  for (std::size_t i = 0; i < occluders.size(); ++i) {
    // Each box lies inside its instance, and instances are large: the boxes are too far
    // apart for the hardware to guess the next one in time.
    if (i + kPrefetchAhead < occluders.size()) prefetch(scene.instances()[occluders[i + kPrefetchAhead]].box);
    const BoxFootprint box = footprint(view, scene.instances()[occluders[i]].box);
    if (box.empty() && !box.crossesNear) continue;
    boxes.push_back(box);
    onMap.push_back(occluders[i]);
    nearest.push_back(box.crossesNear ? -std::numeric_limits<float>::infinity() : box.nearest);
  }
  // Nearest first, so that an occluder wholly behind what is already drawn can be
  // skipped: everything it would write is farther than what the map holds.
  const std::vector<std::uint32_t> order = nearestFirst(nearest);
  OccluderRasterizer rasterizer(view, knobs.rule, map);
  TileMaxima tiles(map);
  std::int64_t rasterized = 0, skipped = 0, texelsRead = 0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    // Nearest first is no order in memory: ask for what the occluders a few ahead will
    // read, whether they are then drawn or skipped.
    if (i + kPrefetchAhead < order.size()) {
      const std::uint32_t ahead = order[i + kPrefetchAhead];
      prefetch(boxes[ahead]);
      prefetch(scene.instances()[onMap[ahead]]);
    }
    const std::uint32_t position = order[i];
    const BoxFootprint& box = boxes[position];
    if (tiles.hidden(box, texelsRead)) {
      ++skipped;
      continue;
    }
    ++rasterized;
    tiles.invalidate(box);  // it draws within its box's footprint
    drawOccluder(scene, scene.instances()[onMap[position]], rasterizer);
  }
  stats.add("occlusion: occluders rasterized", rasterized);
  stats.add("occlusion: occluders skipped", skipped);
  stats.add("occlusion: occluders outside the map", std::int64_t(occluders.size() - onMap.size()));
  stats.add("occlusion: occluder triangles", rasterizer.trianglesRasterized);
  stats.add("occlusion: texels written", rasterizer.texelsWritten);
  return map;
}

DepthMap depthMapOfFrame(const MapView& view, const Frame& frame, Stats& stats) {
  DepthMap map(view.width, view.height);
  const PixelBuffer<float>& distance = frame.distances(&stats);
  // Texel x spans view pixels [x / scale, (x + 1) / scale): the pixels it overlaps.
  const auto pixels = [](int texel, double scale, int size) {
    const int first = static_cast<int>(std::floor(texel / scale));
    const int last = static_cast<int>(std::ceil((texel + 1) / scale)) - 1;
    return std::pair(std::clamp(first, 0, size - 1), std::clamp(last, 0, size - 1));
  };
  for (int y = 0; y < map.height; ++y) {
    const auto [top, bottom] = pixels(y, view.scale.y, frame.height);
    for (int x = 0; x < map.width; ++x) {
      const auto [left, right] = pixels(x, view.scale.x, frame.width);
      double farthest = -std::numeric_limits<double>::infinity();
      for (int py = top; py <= bottom; ++py)
        for (int px = left; px <= right; ++px) {
          const float depth = distance[std::size_t(py) * std::size_t(frame.width) + std::size_t(px)];
          farthest = std::max(farthest, std::isinf(depth) ? std::numeric_limits<double>::infinity() : view.key(depth));
        }
      map.at(x, y) = roundedUp(farthest);
    }
  }
  return map;
}

namespace {

// hsr why: what the map test found for a box, with the depths as distances along the view axis.
std::string decided(const MapView& view, const DepthMap& level, const MapDecision& decision, bool hidden) {
  const BoxFootprint& box = decision.tested;
  if (box.crossesNear) return "its box crosses the near plane, so its footprint is unbounded: never hidden";
  if (box.empty()) return "its box's footprint covers no texel of the map";
  const auto distance = [&](double key) { return whyNumber(view.camera.perspective() ? -1.0 / key : key); };
  const std::string where = (decision.level == 0 ? "the " : "pyramid level " + std::to_string(decision.level) + " of the ") +
                            std::to_string(view.width) + "x" + std::to_string(view.height) + " map";
  const std::string nearest = "its box's nearest point (distance " + distance(box.nearest) + ")";
  if (hidden)
    return "every texel of its footprint on " + where + " (x " + std::to_string(box.x0) + " to " + std::to_string(box.x1 - 1) + ", y " +
           std::to_string(box.y0) + " to " + std::to_string(box.y1 - 1) + ") holds an occluder nearer than " + nearest;
  const float key = level.at(decision.x, decision.y);
  return "texel (" + std::to_string(decision.x) + ", " + std::to_string(decision.y) + ") of " + where + " holds " +
         (std::isinf(key) ? std::string("no occluder") : "an occluder as far as distance " + distance(key)) + ", not nearer than " + nearest +
         ": it may show there";
}

// A map as a step's picture: its depths (nearest white), each texel enlarged to whole
// pixels so that a small map is seen at about the image's width.
void recordMap(const DepthMap& map, int imageWidth, const std::string& caption, StepRecorder& steps,
               SourceLocation where = SourceLocation::current()) {
  const int scale = std::max(1, int(std::lround(double(imageWidth) / std::max(1, map.width))));
  std::vector<float> enlarged(std::size_t(map.width * scale) * std::size_t(map.height * scale));
  for (int y = 0; y < map.height * scale; ++y)
    for (int x = 0; x < map.width * scale; ++x) enlarged[std::size_t(y) * std::size_t(map.width * scale) + std::size_t(x)] = map.at(x / scale, y / scale);
  steps.record(caption, depthPicture(enlarged, map.width * scale, map.height * scale), where);
}

}  // namespace

VisibleSet cull(const PreparedScene& scene, const CameraTransform& camera, const Knobs& knobs, const VisibleSet& in,
                const PreviousFrame* previous, Stats& stats, StepRecorder* steps, StageWitness* why) {
  PhaseTimer timer(stats, "culling: occlusion");
  // Occlusion culling pays only where objects hide one another: a cheap estimate first.
  if (knobs.minDepthComplexity > 0) {
    const double complexity = estimatedDepthComplexity(scene, MapView(camera, knobs.mapWidth, knobs.mapHeight), in);
    stats.add("occlusion: estimated depth complexity x100", std::llround(100 * complexity));
    if (complexity < knobs.minDepthComplexity) {
      stats.add("occlusion: skipped, below min-depth-complexity");
      return in;
    }
  }
  // The map, and the camera that saw it: this frame's, or the previous frame's.
  std::optional<CameraTransform> previousCamera;
  if (knobs.method == Method::previousFrame) {
    if (!previous || !previous->frame) {
      stats.add("occlusion: no previous frame", 1);
      return in;
    }
    previousCamera.emplace(previous->camera, previous->frame->width, previous->frame->height);
  }
  const MapView view(previousCamera ? *previousCamera : camera, knobs.mapWidth, knobs.mapHeight);
  const DepthMap map = previousCamera ? depthMapOfFrame(view, *previous->frame, stats)
                                      : occluderDepthMap(scene, view, knobs, chooseOccluders(scene, camera, knobs, in), stats);
  std::optional<Pyramid> pyramid;
  if (knobs.pyramid) pyramid.emplace(map);
  if (steps) {
    recordMap(map, scene.width(),
              std::string(previousCamera ? "the previous frame's depth" : "the occluders' depth") + " as a " + std::to_string(map.width) + "x" +
                  std::to_string(map.height) + " map (nearest white, empty black)",
              *steps);
    for (std::size_t level = 1; pyramid && level < pyramid->levels().size(); ++level) {
      const DepthMap& texels = pyramid->levels()[level];
      const bool empty = std::none_of(texels.keys.begin(), texels.keys.end(), [](float key) { return std::isfinite(key); });
      recordMap(texels, scene.width(),
                "pyramid level " + std::to_string(level) + ", " + std::to_string(texels.width) + "x" + std::to_string(texels.height) +
                    (empty ? ": every texel empty (some texel below it was), so this level and those above hide nothing"
                           : ": each texel the farthest of the four below it"),
                *steps);
      if (empty) break;
    }
  }

  PhaseTimer testing(stats, "occlusion: test occludees");
  std::int64_t tested = 0, culled = 0, texelsRead = 0;
  VisibleSet out = keepObjects(scene, in, [&](std::uint32_t instance) {
    ++tested;
    const BoxFootprint box = footprint(view, scene.instances()[instance].box);
    std::string* const found = why ? why->about(instance) : nullptr;
    MapDecision decision;
    MapDecision* const watched = found ? &decision : nullptr;
    const bool hidden = pyramid ? pyramid->hidden(box, texelsRead, watched) : hiddenOnMap(map, box, texelsRead, watched);
    if (found) [[unlikely]]
      *found = decided(view, pyramid ? pyramid->levels()[std::size_t(decision.level)] : map, decision, hidden);
    culled += hidden;
    return !hidden;
  });
  stats.add("occlusion: occludees tested", tested);
  stats.add("occlusion: occludees culled", culled);
  stats.add("occlusion: texels read", texelsRead);
  stats.add("occlusion: triangles culled", static_cast<std::int64_t>(in.triangles.size() - out.triangles.size()));
  return out;
}

}  // namespace hsr::culling::occlusion
