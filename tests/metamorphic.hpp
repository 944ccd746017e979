// The metamorphic property (README, "Robustness"): moving a scene far from the origin,
// scaling it, or cutting its triangles into four must not change what any algorithm
// shows, except where the decision lies within rounding: a pixel center within the
// rasterizer's snapping of an edge, two depths the configuration cannot order, a tie
// the algorithm's own ordering cannot break, a face seen exactly edge-on, or a tie the
// reference marks ambiguous. Each configuration is compared with its own output on the
// scene as generated; the exact ones with the exact reference too. Scaling by a power of
// two is exact: the same bits. The random-scene tests (tests/property) and the hard
// cases (tests/numerics) share it. The A-buffer is compared through its shares of each
// pixel (renderer/raster/coverage.hpp): the same bits scaled, and few pixels changed moved.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "algorithms/culling/culling.hpp"
#include "algorithms/registry.hpp"
#include "renderer/lines/feature_edges.hpp"
#include "renderer/lines/line_set.hpp"
#include "renderer/raster/coverage.hpp"
#include "renderer/reference/line_reference.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "test_support.hpp"

namespace hsr::test {

// The scene after a change that must not change what is seen, and how its ids map back.
struct Variation {
  std::string name;
  dmat4 world{1.0};                    // the whole scene moved (PreparedScene's scene copy), the camera with it
  Scene scene;                         // subdivision: another mesh; otherwise the scene itself
  std::uint32_t idsPerOriginal = 1;    // subdivision: 4
  bool exact = false;                  // exact in floating point (scaling by a power of two): the very same output
};

// The scene with every triangle cut into four at its edges' midpoints; triangle t of the
// original becomes triangles 4t to 4t + 3 (so ids map back as (id - 1) / 4 + 1).
inline Scene subdivided(Scene scene) {
  for (SceneObject& object : scene.objects) {
    Mesh mesh;
    for (const Triangle& t : object.mesh->triangles) {
      const dvec3 a = object.mesh->positions[t[0]], b = object.mesh->positions[t[1]], c = object.mesh->positions[t[2]];
      const dvec3 ab = (a + b) * 0.5, bc = (b + c) * 0.5, ca = (c + a) * 0.5;
      const auto first = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.insert(mesh.positions.end(), {a, b, c, ab, bc, ca});
      for (const Triangle& piece : {Triangle{0, 3, 5}, Triangle{3, 1, 4}, Triangle{5, 4, 2}, Triangle{3, 4, 5}})
        mesh.triangles.push_back({first + piece[0], first + piece[1], first + piece[2]});
    }
    object.mesh = std::make_shared<const Mesh>(std::move(mesh));
    object.solid = Solid{};  // no longer the primitive the solid describes
  }
  return scene;
}

// Moved far from the origin (by offsets that are not powers of two, so every coordinate
// is rounded), scaled by 2^-20 and 2^20 (exact), and, when `subdivide`, cut into four.
inline std::vector<Variation> variations(const Scene& scene, bool subdivide) {
  std::vector<Variation> all;
  const auto moved = [&](const std::string& name, double scale, const dvec3& offset, bool exact) {
    Variation variation{name, glm::translate(dmat4(1.0), offset) * glm::scale(dmat4(1.0), dvec3(scale)), scene, 1, exact};
    variation.scene.camera = movedAndScaled(scene.camera, scale, offset);
    // The cells and portals with the objects, by the same operations.
    const auto place = [&](dvec3& p) { p = offset + scale * p; };
    for (Cell& cell : variation.scene.cells) place(cell.from), place(cell.to);
    for (Portal& portal : variation.scene.portals) {
      portal.at = offset[portal.axis] + scale * portal.at;
      for (dvec3& corner : portal.polygon) place(corner);
    }
    all.push_back(std::move(variation));
  };
  for (const double offset : {1e3, 1e5, 1e7}) {
    char name[32];
    std::snprintf(name, sizeof name, "translated by %g", offset);
    moved(name, 1, dvec3(offset, -offset, offset), false);
  }
  for (const int k : {-20, 20}) moved("scaled by 2^" + std::to_string(k), std::ldexp(1.0, k), dvec3(0), true);
  if (subdivide) all.push_back({"subdivided", dmat4(1.0), subdivided(scene), 4});
  return all;
}

inline PixelBuffer<std::uint32_t> originalIds(PixelBuffer<std::uint32_t> ids, std::uint32_t idsPerOriginal) {
  for (std::uint32_t& id : ids)
    if (id != 0) id = (id - 1) / idsPerOriginal + 1;
  return ids;
}

// Every surface configuration: each algorithm in each variant and depth format, with the
// depth tolerance its error model allows (the other half is snapping, the same for all).
struct Configuration {
  const char* algorithm;
  KnobSettings knobs;
  std::optional<DepthFormat> format;  // the z-buffer's; else the coplanar tolerance
  bool ordersWholeTriangles = false;  // the depth sort: subdividing changes what it orders, by design
  bool exact = false;                 // compared with the original reference as well
};
inline const std::vector<Configuration>& everyConfiguration() {
  static const std::vector<Configuration> all = {
      {"zbuffer", {{"depth-format", "float32"}}, DepthFormat::float32, false, true},
      {"zbuffer", {{"depth-format", "reversed-float32"}}, DepthFormat::reversedFloat32},
      {"zbuffer", {{"depth-format", "reversed-float32-inf"}}, DepthFormat::reversedFloat32Infinite},
      {"zbuffer", {{"depth-format", "unorm24"}}, DepthFormat::unorm24},
      {"zbuffer", {{"depth-format", "unorm16"}}, DepthFormat::unorm16},
      {"zbuffer", {{"variant", "scanline"}}, DepthFormat::float32},
      {"ray_casting", {{"variant", "bvh"}}, std::nullopt, false, true},
      {"ray_casting", {{"variant", "naive"}}, std::nullopt},
      {"painter", {{"variant", "sort"}, {"key", "centroid"}}, std::nullopt, true},
      {"painter", {{"variant", "sort"}, {"key", "nearest"}}, std::nullopt, true},
      {"painter", {{"variant", "sort"}, {"key", "farthest"}}, std::nullopt, true},
      {"painter", {{"variant", "newell"}}, std::nullopt, false, true},
      {"painter", {{"variant", "bsp"}}, std::nullopt, false, true},
      {"warnock", {}, std::nullopt, false, true},
      {"watkins", {}, std::nullopt, false, true},
      {"weiler_atherton", {}, std::nullopt, false, true},
  };
  return all;
}
// The line algorithms and their variants. Appel's surfaces=any is left out of the random
// scenes (`soups`): on a triangle whose boundary lies exactly on a coplanar neighbour's
// face (the generator's coplanar overlapping pairs), the contour crossing and the face's
// plane are each decided by rounding, and can disagree (algorithms/appel/README.md,
// "Known limits"); the hard cases include it.
inline std::vector<std::pair<const char*, KnobSettings>> everyDrawing(bool soups) {
  std::vector<std::pair<const char*, KnobSettings>> all = {
      {"roberts", {}}, {"appel", {}}, {"floating_horizon", {}}, {"floating_horizon", {{"interpolate", "off"}}}, {"floating_horizon", {{"mesh", "on"}}}};
  if (!soups) all.push_back({"appel", {{"surfaces", "any"}}});
  return all;
}

template <typename Knobs>
std::string label(const char* algorithm, const Knobs& knobs) {
  std::string text = algorithm;
  for (const auto& [knob, value] : knobs) text += ":" + knob + "=" + value;
  return text;
}

// Renders with the registry's entry, or returns nothing when the algorithm refuses.
inline std::optional<Frame> render(const PreparedScene& scene, const char* algorithm, const KnobSettings& settings) {
  const AlgorithmEntry& entry = findAlgorithm(algorithm);
  const pipeline::Configuration configuration = pipeline::configurationOf(entry, settings);
  if (!pipeline::refusal(scene, configuration).empty()) return std::nullopt;
  Stats stats;
  return pipeline::render(scene, configuration, 1, stats).frame;
}
inline std::optional<LineSet> draw(const PreparedScene& scene, const char* algorithm, const KnobSettings& settings) {
  const AlgorithmEntry& entry = findAlgorithm(algorithm);
  const KnobValues knobs = resolveKnobs(entry, settings);
  if (!entry.refusal(scene, knobs).empty()) return std::nullopt;
  Stats stats;
  return entry.drawLines(scene, knobs, 1, stats, nullptr);
}

inline DepthTie depthTieOf(const PreparedScene& scene, const Configuration& configuration) {
  if (!configuration.format) return coplanar;
  return depthFormatTie(*configuration.format, scene.camera());
}

// The depth sort's own ties: two triangles whose keys (of any of their screen pieces: a
// triangle the near plane cuts is a fan of pieces) are equal up to rounding. Equal keys
// are common where it counts: every piece cut by the near plane has its nearest corner on
// it. Rounding of the moved scene decides such a tie, as the sort's stable order did.
inline std::function<bool(std::uint32_t, std::uint32_t)> sortKeyTie(const PreparedScene& scene, const Configuration& configuration) {
  if (!configuration.ordersWholeTriangles) return nullptr;
  const std::string key = configuration.knobs.back().second;
  Stats stats;
  const ScreenGeometry geometry = buildScreenTriangles(scene, {.keepCorners = true}, 1, stats);
  auto keys = std::make_shared<std::vector<std::vector<double>>>(scene.triangleCount());
  for (std::size_t s = 0; s < geometry.triangles.size(); ++s) {
    double d[3];
    for (int k = 0; k < 3; ++k) d[k] = geometry.camera.distanceFromScreenAffine(geometry.corners[s][std::size_t(k)].z);
    (*keys)[geometry.triangles[s].triangle].push_back(key == "nearest"    ? std::min({d[0], d[1], d[2]})
                                                      : key == "farthest" ? std::max({d[0], d[1], d[2]})
                                                                          : (d[0] + d[1] + d[2]) / 3);
  }
  return [keys](std::uint32_t a, std::uint32_t b) {
    for (const double x : (*keys)[a - 1])
      for (const double y : (*keys)[b - 1])
        if (std::abs(x - y) <= 1e-9 * std::max(std::abs(x), std::abs(y))) return true;
    return false;
  };
}

// Faces seen exactly edge-on in either scene: the eye in a face's plane, where rounding of
// the moved scene decides the face's facing, and with it whether its edges are contours
// and what they hide. A junction line in such a face lies in a sight plane through it,
// where whether the face hides it is as undefined as 0/0.
using EdgeKey = std::tuple<std::uint32_t, double, double>;
struct EdgeOnFaces {
  std::set<EdgeKey> edges;               // their mesh edges
  std::vector<std::uint32_t> triangles;  // the triangles (the same indices in both scenes)
};
inline EdgeOnFaces edgeOnFaces(const PreparedScene& original, const PreparedScene& moved) {
  EdgeOnFaces edgeOn;
  Stats stats;
  for (const PreparedScene* scene : {&original, &moved}) {
    const std::vector<std::int8_t> facing = viewFacing(*scene, scene->camera(), stats);
    for (std::uint32_t t = 0; t < facing.size(); ++t)
      if (facing[t] == 0) {
        edgeOn.triangles.push_back(t);
        for (std::size_t k = 0; k < 3; ++k) {
          const std::uint32_t a = scene->triangles()[t][k], b = scene->triangles()[t][(k + 1) % 3];
          edgeOn.edges.insert({std::min(a, b), double(std::max(a, b)), 0.0});
        }
      }
  }
  return edgeOn;
}

// Whether a junction line runs along one of these triangles in this scene's view: both its
// ends within 1e-6 pixel of the line the triangle's projection collapses to (through its
// two projected corners farthest apart).
inline bool alongEdgeOnFace(const FeatureEdge& junction, const PreparedScene& scene, const std::vector<std::uint32_t>& triangles) {
  const CameraTransform& camera = scene.camera();
  for (const std::uint32_t t : triangles) {
    std::array<dvec2, 3> corners{};  // (read only when every corner is in front, and so set)
    bool inFront = true;
    for (std::size_t k = 0; k < 3; ++k) {
      const ClipVertex clip = camera.clipFromWorld(scene.positions()[scene.triangles()[t][k]]);
      inFront = inFront && clip.w > 0;
      if (inFront) corners[k] = camera.pixelFromClip(clip);
    }
    if (!inFront) continue;
    std::pair<dvec2, dvec2> farthest{corners[0], corners[1]};
    for (const auto& [a, b] : {std::pair{corners[1], corners[2]}, std::pair{corners[2], corners[0]}})
      if (glm::length(b - a) > glm::length(farthest.second - farthest.first)) farthest = {a, b};
    const dvec2 direction = farthest.second - farthest.first;
    if (glm::length(direction) == 0) continue;
    const auto distance = [&](const dvec2& p) {
      const dvec2 offset = p - farthest.first;
      return std::abs(offset.x * direction.y - offset.y * direction.x) / glm::length(direction);
    };
    if (distance(junction.pixelFrom) < 1e-6 && distance(junction.pixelTo) < 1e-6) return true;
  }
  return false;
}

// Per edge of a line drawing, its visible length in pixels, keyed by the mesh edge's
// vertices or the curve place (the same in every variation but subdivision, which the
// drawings leave out), and the total visible length of the other edges (junction lines).
struct DrawnLengths {
  std::map<EdgeKey, double> keyed;
  double otherEdges = 0;
};
// Junction lines along the edge-on triangles are left out of otherEdges.
inline DrawnLengths drawnLengths(const LineSet& lines, const PreparedScene& scene, const std::vector<std::uint32_t>& edgeOnTriangles) {
  DrawnLengths lengths;
  const std::vector<EdgeVisibility> visibility = edgeVisibility(lines);
  for (std::size_t e = 0; e < lines.edges.size(); ++e) {
    double visible = 0;
    for (const Interval& part : visibility[e].visible) visible += (part.end - part.begin) * visibility[e].lengthPixels;
    const FeatureEdge& edge = lines.edges[e];
    if (!lines.curvePlaces.empty())
      lengths.keyed[{lines.curvePlaces[e].curve, lines.curvePlaces[e].from, lines.curvePlaces[e].to}] = visible;
    else if (edge.vertexFrom != FeatureEdge::kNone)
      lengths.keyed[{std::min(edge.vertexFrom, edge.vertexTo), double(std::max(edge.vertexFrom, edge.vertexTo)), 0.0}] = visible;
    else if (!alongEdgeOnFace(edge, scene, edgeOnTriangles))
      lengths.otherEdges += visible;
  }
  return lengths;
}

// The A-buffer's shares at its default mask (renderer/raster/coverage.hpp), each id mapped
// back to the original triangle; nothing when it refuses the scene.
inline std::optional<PixelShares> aBufferShares(const PreparedScene& scene, std::uint32_t idsPerOriginal) {
  const pipeline::Configuration configuration = pipeline::configurationOf(findAlgorithm("abuffer"), {});
  if (!pipeline::refusal(scene, configuration).empty()) return std::nullopt;
  Stats stats;
  PixelShares shares = sharesOf(*pipeline::render(scene, configuration, 1, stats).coverage);
  for (auto& [id, share] : shares.shares)
    if (id != 0) id = (id - 1) / idsPerOriginal + 1;
  return shares;
}

// What a scene as generated shows, to compare its variations with.
struct Baseline {
  std::optional<PixelShares> antialiased;    // the A-buffer's shares
  std::vector<std::optional<Frame>> frames;  // per everyConfiguration()
  std::vector<std::pair<const char*, KnobSettings>> drawingAlgorithms;
  std::vector<std::optional<LineSet>> drawings;  // per drawingAlgorithms
};
inline Baseline baselineOf(const PreparedScene& scene, bool soups) {
  Baseline baseline;
  baseline.antialiased = aBufferShares(scene, 1);
  for (const Configuration& configuration : everyConfiguration())
    baseline.frames.push_back(render(scene, configuration.algorithm, configuration.knobs));
  baseline.drawingAlgorithms = everyDrawing(soups);
  for (const auto& [algorithm, knobs] : baseline.drawingAlgorithms) baseline.drawings.push_back(draw(scene, algorithm, knobs));
  return baseline;
}

struct MetamorphicTally {
  long renders = 0, identical = 0, excused = 0, compared = 0, labelledPartial = 0;
  long drawings = 0, lineEdges = 0, edgeOnEdges = 0, edgesTheReferenceMoved = 0, cullingRuns = 0;
  long sharedPixels = 0, sharesChanged = 0;  // the A-buffer's pixels compared, and those whose shares changed
  double largestLineChange = 0;
  std::string summary() const {
    char text[512];
    std::snprintf(text, sizeof text,
                  "%ld moved, scaled or subdivided renders checked; %ld scaled ones bit-identical; %ld of %ld pixels changed, "
                  "each within snapping of an edge or a tie; %ld labelled partial; %ld line drawings, %ld edges each within "
                  "1e-4 px (the largest change %.2g px), %ld on faces seen edge-on and %ld the exact reference decides otherwise "
                  "once moved left out; %ld culling runs, none dropping a visible triangle; the A-buffer's shares changed "
                  "at %ld of %ld pixels",
                  renders, identical, excused, compared, labelledPartial, drawings, lineEdges, largestLineChange, edgeOnEdges,
                  edgesTheReferenceMoved, cullingRuns, sharesChanged, sharedPixels);
    return text;
  }
};

// One variation of a scene against the scene as generated (`original`, its exact
// reference `truth` and what it showed, `baseline`); failures name `where`.
inline void expectSameAfter(const Variation& variation, const PreparedScene& original, const ReferenceImage& truth,
                            const Baseline& baseline, const std::string& where, MetamorphicTally& tally) {
  PreparedScene prepared(variation.scene, {variation.world});
  prepared.setSize(original.width(), original.height());
  const std::string what = variation.name + " on " + where;
  // The reference is exact for its input: only rounding of the moved input may move an
  // edge or tie two depths.
  Stats stats;
  const ReferenceImage movedTruth = traceReference(prepared, 1, stats);
  const WrongPixels referenceMoved =
      classifyDifferences(original, originalIds(movedTruth.frame.ids, variation.idsPerOriginal), truth.frame.ids, truth.ambiguous, coplanar);
  EXPECT_EQ(referenceMoved.unexplained, 0) << "reference " << what << ": " << referenceMoved.firstUnexplained;
  for (std::size_t c = 0; c < everyConfiguration().size(); ++c) {
    const Configuration& configuration = everyConfiguration()[c];
    if (configuration.ordersWholeTriangles && variation.idsPerOriginal != 1) continue;
    const std::optional<Frame> frame = render(prepared, configuration.algorithm, configuration.knobs);
    const std::string name = label(configuration.algorithm, configuration.knobs) + " " + what;
    ASSERT_EQ(frame.has_value(), baseline.frames[c].has_value()) << name << ": refused one and not the other";
    if (!frame) continue;
    if (!frame->partial.empty() || !baseline.frames[c]->partial.empty()) {  // wrong, but not silently: the image says so
      ++tally.labelledPartial;
      continue;
    }
    const PixelBuffer<std::uint32_t> ids = originalIds(frame->ids, variation.idsPerOriginal);
    if (variation.exact) {
      EXPECT_EQ(ids, baseline.frames[c]->ids) << name;
      tally.identical += ids == baseline.frames[c]->ids;
    }
    const WrongPixels changed = classifyDifferences(original, ids, baseline.frames[c]->ids, truth.ambiguous, depthTieOf(original, configuration),
                                                    sortKeyTie(original, configuration), &prepared, variation.idsPerOriginal);
    EXPECT_EQ(changed.unexplained, 0) << name << ": " << changed.firstUnexplained << " (as generated)";
    tally.excused += changed.snapping + changed.depthTie;
    tally.compared += static_cast<long>(ids.size());
    ++tally.renders;
    if (configuration.exact) {  // and still right, within its error model
      const WrongPixels wrong = classifyDifferences(original, ids, truth.frame.ids, truth.ambiguous, depthTieOf(original, configuration),
                                                    nullptr, &prepared, variation.idsPerOriginal);
      EXPECT_EQ(wrong.unexplained, 0) << name << ": " << wrong.firstUnexplained << " (exactly)";
    }
  }
  // The A-buffer, through its shares: the same bits scaled, and elsewhere changed only
  // where rounding moves an edge or a depth across a subsample (the caller bounds how often).
  if (baseline.antialiased) {
    const std::optional<PixelShares> shares = aBufferShares(prepared, variation.idsPerOriginal);
    ASSERT_TRUE(shares) << "abuffer " << what << ": refused moved, not as generated";
    for (std::size_t pixel = 0; pixel + 1 < shares->first.size(); ++pixel) {
      const bool changed = coverageDistance(*shares, *baseline.antialiased, pixel) > 0;
      if (variation.exact) {
        EXPECT_FALSE(changed) << "abuffer " << what << " at pixel " << pixel;
      }
      tally.sharesChanged += changed;
      ++tally.sharedPixels;
    }
  }
  if (variation.idsPerOriginal != 1) return;  // subdivision adds edges and triangles: the rest compares like with like
  // Conservative culling drops nothing the moved scene's reference shows.
  const std::vector<std::uint8_t> visible = visibleTriangles(movedTruth, prepared.triangleCount());
  for (const culling::StageEntry& stage : culling::stages()) {
    if (stage.name == "backface") continue;  // right only for closed solids seen from outside: tests/culling
    if (stage.needsCells && variation.scene.cells.empty()) continue;
    for (const std::string& cullVariant : stage.variantKnob().choices) {
      const culling::Pipeline pipeline = culling::parsePipeline(stage.name + ":" + cullVariant);
      if (pipeline.front().wrong()) continue;
      Stats cullStats;
      const VisibleSet kept = culling::runPipeline(prepared, pipeline, 1, cullStats);
      std::vector<std::uint8_t> keptFlags(prepared.triangleCount(), 0);
      for (const std::uint32_t t : kept.triangles) keptFlags[t] = 1;
      EXPECT_EQ(cullingError(keptFlags, visible).falseCulls, 0) << stage.name << ":" << cullVariant << " " << what;
      ++tally.cullingRuns;
    }
  }
  // The line drawings: every mesh edge's (or curve piece's) visible length, and the
  // junction lines' total, to 1e-4 pixel, the rounding the line algorithms are judged to
  // (README). Roberts' insideness tolerance grows with the coordinates (eight roundings of
  // the placement: 3.5e-8 at 1e7), which moves the ends of hidden parts by up to about
  // 2e-5 pixel in the random scenes' 32 x 24 images. Left out, and counted: edges on a face
  // seen exactly edge-on, and edges (junction lines among them) the exact line reference itself decides otherwise
  // once moved (a visibility the rounding of the input decides: traced only when a
  // drawing differs).
  constexpr double kLineTolerance = 1e-4;
  const EdgeOnFaces edgeOn = edgeOnFaces(original, prepared);
  for (std::size_t d = 0; d < baseline.drawings.size(); ++d) {
    if (!baseline.drawings[d]) continue;
    const auto& [algorithm, knobs] = baseline.drawingAlgorithms[d];
    const std::string name = label(algorithm, knobs) + " " + what;
    const std::optional<LineSet> lines = draw(prepared, algorithm, knobs);
    ASSERT_TRUE(lines.has_value()) << name << ": refused moved, not as generated";
    EXPECT_EQ(lines->partial.empty(), baseline.drawings[d]->partial.empty()) << name << ": " << lines->partial;
    const DrawnLengths before = drawnLengths(*baseline.drawings[d], original, edgeOn.triangles),
                       after = drawnLengths(*lines, prepared, edgeOn.triangles);
    std::optional<std::pair<DrawnLengths, DrawnLengths>> exact;  // the reference's, before and after, when needed
    const auto referenceChanged = [&](const std::optional<EdgeKey>& edge) {
      if (!exact) {
        const auto traced = [&edgeOn](const PreparedScene& scene, const LineSet& drawing) {
          Stats referenceStats;
          LineSet exactDrawing = drawing;
          exactDrawing.segments.clear();
          const std::vector<EdgeVisibility> visibility = traceLineReference(scene, drawing.edges, 1, referenceStats);
          for (std::uint32_t e = 0; e < visibility.size(); ++e)
            for (const Interval& part : visibility[e].visible) exactDrawing.segments.push_back({e, part.begin, part.end, 0});
          return drawnLengths(exactDrawing, scene, edgeOn.triangles);
        };
        exact.emplace(traced(original, *baseline.drawings[d]), traced(prepared, *lines));
      }
      const auto length = [&](const DrawnLengths& lengths) { return edge ? lengths.keyed.at(*edge) : lengths.otherEdges; };
      return std::abs(length(exact->first) - length(exact->second)) > kLineTolerance;
    };
    for (const auto& [edge, length] : before.keyed) {
      const auto moved = after.keyed.find(edge);
      ASSERT_NE(moved, after.keyed.end()) << name << ": an edge is no longer drawn";
      if (edgeOn.edges.contains(edge)) {
        ++tally.edgeOnEdges;
        continue;
      }
      if (std::abs(moved->second - length) > kLineTolerance && referenceChanged(edge)) {
        ++tally.edgesTheReferenceMoved;
        continue;
      }
      EXPECT_NEAR(moved->second, length, kLineTolerance) << name << ": edge " << std::get<0>(edge) << "-" << std::get<1>(edge);
      tally.largestLineChange = std::max(tally.largestLineChange, std::abs(moved->second - length));
      ++tally.lineEdges;
    }
    if (std::abs(after.otherEdges - before.otherEdges) > kLineTolerance && referenceChanged(std::nullopt))
      ++tally.edgesTheReferenceMoved;  // junction lines in a face seen edge-on, say
    else
      EXPECT_NEAR(after.otherEdges, before.otherEdges, kLineTolerance) << name << ": junction lines";
    ++tally.drawings;
  }
}

}  // namespace hsr::test
