#include "renderer/reference/reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "renderer/geometry/rounding.hpp"
#include "renderer/rays/ray_packet.hpp"
#include "renderer/reference/bounded_woop.hpp"
#include "renderer/reference/nearest_hit.hpp"
#include "renderer/reference/tile_proof.hpp"
#include "renderer/shading/fog.hpp"
#include "renderer/shading/outline.hpp"
#include "renderer/shading/shading.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr {
namespace {

using namespace reference_search;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

SurfaceReference::SurfaceReference(const PreparedScene& scene, Stats& stats, ReferenceTraversal traversal, int threads)
    : scene_(scene),
      bvh_(scene.triangleBvh(stats, threads)),
      triangles_(scene.leafTriangles(stats)),
      wideBvh_(traversal == ReferenceTraversal::packets && cpuHasAvx2() ? &scene.wideTriangleBvh(stats, threads) : nullptr) {
  if (!bvh_.empty()) sceneBox_ = bvh_.nodes()[0].box();
}

void SurfaceReference::traceRun(const CameraTransform& camera, int y, int x0, int count, ReferenceHit* hits, Counters& counters) const {
  // Eight rays at a time; where they cannot travel together (they straddle a plane of
  // the view where a direction's component changes sign, or where its largest component
  // changes axis), four and four; and where four cannot, one by one, each still through
  // the wide tree unless a component of its direction is zero.
  const auto traceOneByOne = [&](int x, int rays) {
    for (int i = 0; i < rays; ++i) {
      const Ray ray = camera.rayThroughPixel(conventions::pixelCenter(x + i), conventions::pixelCenter(y));
      const bool travels = ray.direction.x != 0 && ray.direction.y != 0 && ray.direction.z != 0;  // as a packet of one
      if (!wideBvh_ || !travels || !tracePacket(camera, y, x + i, 1, hits + (x - x0 + i), counters)) hits[x - x0 + i] = trace(camera, ray, counters);
    }
  };
  for (int x = x0; x < x0 + count; x += RayPacket::kRays) {
    const int rays = std::min(RayPacket::kRays, x0 + count - x);
    if (!wideBvh_) traceOneByOne(x, rays);
    else if (tracePacket(camera, y, x, rays, hits + (x - x0), counters)) continue;
    else
      for (int half = x; half < x + rays; half += 4)
        if (!tracePacket(camera, y, half, std::min(4, x + rays - half), hits + (half - x0), counters)) traceOneByOne(half, std::min(4, x + rays - half));
  }
}

namespace {

// Whether a row of hits shows one answer plainly: the same triangle (or nothing) at every
// pixel, no pixel ambiguous, no decision exact. Such a row gives a tile its candidate.
bool oneAnswer(const ReferenceHit* row, int count, std::uint32_t id) {
  return std::all_of(row, row + count, [&](const ReferenceHit& hit) { return hit.id == id && !hit.ambiguous && !hit.usedExact; });
}

}  // namespace

bool SurfaceReference::answerByProof(const CameraTransform& camera, int x0, int y0, int width, int height, std::uint32_t id,
                                     ReferenceHit* hits, std::size_t stride, Counters& counters) const {
  std::optional<PackedTriangle> candidate;
  if (id != 0) candidate = scene_.leafTriangle(id - 1);
  // The proof, over the pixels' rectangle, edges and all.
  const std::optional<TileRegion> region = TileRegion::of(camera, sceneBox_, x0, y0, x0 + width, y0 + height, candidate ? &*candidate : nullptr);
  if (!region || region->touchedByAnother(bvh_, triangles_, counters.nodesVisited)) return false;
  ++counters.tilesProved;
  for (int row = 0; row < height; ++row) {
    ReferenceHit* rowHits = hits + std::size_t(row) * stride;
    if (!candidate) {
      std::fill(rowHits, rowHits + width, ReferenceHit{});
      counters.raysProved += width;
      continue;
    }
    for (int x = 0; x < width; x += RayPacket::kRays) {
      const int count = std::min(RayPacket::kRays, width - x);
      if (candidateRun(camera, y0 + row, x0 + x, count, *candidate, rowHits + x, counters)) counters.raysProved += count;
      else traceRun(camera, y0 + row, x0 + x, count, rowHits + x, counters);
    }
  }
  return true;
}

void SurfaceReference::traceTile(const CameraTransform& camera, int x0, int y0, int width, int height, std::optional<std::uint32_t> candidateId,
                                 ReferenceHit* hits, std::size_t stride, Counters& counters) const {
  const auto searchRows = [&](int from) {
    for (int row = from; row < height; ++row) traceRun(camera, y0 + row, x0, width, hits + std::size_t(row) * stride, counters);
  };
  if (!wideBvh_) return searchRows(0);
  if (candidateId && answerByProof(camera, x0, y0, width, height, *candidateId, hits, stride, counters)) return;
  // Else the tile's own first row, searched ray by ray, gives the other rows their
  // candidate, if it shows one answer plainly (the same one may now be proved for the
  // smaller region of the rows below it).
  traceRun(camera, y0, x0, width, hits, counters);
  if (height == 1 || !oneAnswer(hits, width, hits[0].id) ||
      !answerByProof(camera, x0, y0 + 1, width, height - 1, hits[0].id, hits + stride, stride, counters))
    searchRows(1);
}

void SurfaceReference::traceTileRow(const CameraTransform& camera, int y0, int height, const ReferenceHit* above, ReferenceHit* hits,
                                    std::size_t stride, Counters& counters) const {
  const int width = camera.width(), tiles = (width + kTileSize - 1) / kTileSize;
  const auto tileWidth = [&](int tile) { return std::min(kTileSize, width - tile * kTileSize); };
  // Each tile's candidate: what the row above shows along it, if it shows one answer
  // plainly; with no row above (a band's first tile row), what one ray through the
  // tile's middle shows, if plainly. (That ray's work is counted with the rest; its
  // pixel is answered again, by the proof or by the search.)
  std::vector<std::optional<std::uint32_t>> candidateIds(static_cast<std::size_t>(tiles));
  if (wideBvh_)
    for (int tile = 0; tile < tiles; ++tile) {
      const int x0 = tile * kTileSize;
      if (above) {
        if (oneAnswer(above + x0, tileWidth(tile), above[x0].id)) candidateIds[std::size_t(tile)] = above[x0].id;
        continue;
      }
      ReferenceHit sample;
      traceRun(camera, y0 + height / 2, x0 + tileWidth(tile) / 2, 1, &sample, counters);
      if (oneAnswer(&sample, 1, sample.id)) candidateIds[std::size_t(tile)] = sample.id;
    }
  for (int tile = 0; tile < tiles;) {
    // Neighbouring tiles with the same candidate are proved as one run first (a single
    // proof for a stretch of floor or sky), and tile by tile where that fails.
    const std::optional<std::uint32_t> candidateId = candidateIds[std::size_t(tile)];
    int last = tile + 1;
    while (candidateId && last < tiles && last - tile < kRunTiles && candidateIds[std::size_t(last)] == candidateId) ++last;
    const int x0 = tile * kTileSize, runWidth = std::min(last * kTileSize, width) - x0;
    if (last - tile > 1 && answerByProof(camera, x0, y0, runWidth, height, *candidateId, hits + x0, stride, counters)) {
      tile = last;
      continue;
    }
    for (; tile < last; ++tile)
      traceTile(camera, tile * kTileSize, y0, tileWidth(tile), height, candidateIds[std::size_t(tile)], hits + tile * kTileSize, stride,
                counters);
  }
}

ReferenceHit SurfaceReference::trace(const CameraTransform& camera, const Ray& ray, Counters& counters,
                                     std::vector<std::uint32_t>* tied) const {
  if (bvh_.empty()) return {};
  RayQuery query(ray, camera);
  const RayBoxTest boxes(ray.origin, ray.direction);
  NearestHitSearch search;

  // Front-to-back traversal: the nearer child first, and a node is skipped once its
  // entry lies beyond the horizon (widened by the rounding of the entry itself).
  constexpr double widen = NearestHitSearch::kEntryWidening;
  struct Pending {
    std::uint32_t node;
    double entry;
  };
  std::array<Pending, Bvh::kMaxDepth + 1> stack;
  int size = 0;
  const std::vector<BvhNode>& nodes = bvh_.nodes();
  const double rootEntry = boxes.entry(nodes[0], kInfinity);
  if (rootEntry < kInfinity) stack[size++] = {0, rootEntry};
  while (size > 0) {
    const Pending pending = stack[--size];
    if (pending.entry > search.horizon() * widen) continue;
    const BvhNode& node = nodes[pending.node];
    ++counters.nodesVisited;
    if (node.leaf()) {
      for (std::uint32_t slot = node.index; slot < node.index + node.count; ++slot)
        search.offer(boundedHitInDouble(query, triangles_[slot], search.horizon(), counters), slot);
      continue;
    }
    const double limit = search.horizon() * widen;
    Pending first{node.index, boxes.entry(nodes[node.index], limit)};
    Pending second{node.index + 1, boxes.entry(nodes[node.index + 1], limit)};
    if (second.entry < first.entry) std::swap(first, second);
    if (second.entry < kInfinity) stack[size++] = second;
    if (first.entry < kInfinity) stack[size++] = first;
  }
  return search.nearest(triangles_, counters, [&](double t) { return query.distance(t); }, [&]() -> RayQuery& { return query; }, tied);
}

SurfaceReference::Layers SurfaceReference::traceAll(const CameraTransform& camera, const Ray& ray, Counters& counters) const {
  Layers layers;
  if (bvh_.empty()) return layers;
  RayQuery query(ray, camera);
  const RayBoxTest boxes(ray.origin, ray.direction);
  struct Candidate {
    double t, bound;
    std::uint32_t slot;
    bool exact;
  };
  std::vector<Candidate> candidates;
  bvh_.visitPrimitives([&](const BvhNode& node) { return ++counters.nodesVisited, boxes.entry(node, kInfinity) < kInfinity; },
                       [&](std::uint32_t, std::uint32_t slot) {
                         const BoundedHit hit = boundedHit(query, triangles_[slot], kInfinity, counters);
                         if (hit.hit) candidates.push_back({hit.t, hit.bound, slot, hit.exact});
                       });
  // Nearest first: by the double t where the bounds separate two hits, exactly where
  // they do not; exact ties go by id.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ties;
  std::sort(candidates.begin(), candidates.end(), [&](const Candidate& a, const Candidate& b) {
    if (a.t + a.bound < b.t - b.bound) return true;
    if (b.t + b.bound < a.t - a.bound) return false;
    ++counters.exactComparisons;
    const woop::ExactParameter ta = *query.exactHit(triangles_[a.slot].a, triangles_[a.slot].b, triangles_[a.slot].c);
    const woop::ExactParameter tb = *query.exactHit(triangles_[b.slot].a, triangles_[b.slot].b, triangles_[b.slot].c);
    if (const int order = compare(ta, tb); order != 0) return order < 0;
    if (triangles_[a.slot].id != triangles_[b.slot].id) ties.emplace_back(triangles_[a.slot].id, triangles_[b.slot].id);
    return triangles_[a.slot].id < triangles_[b.slot].id;
  });
  // Nothing behind the nearest opaque surface shows, so only ties up to it matter.
  for (const Candidate& candidate : candidates) {
    const std::uint32_t id = triangles_[candidate.slot].id;
    layers.hits.push_back({id, query.distance(candidate.t), false, candidate.exact});
    if (scene_.instanceOf(id - 1).opacity >= 1) break;
  }
  const auto shown = [&](std::uint32_t id) {
    return std::any_of(layers.hits.begin(), layers.hits.end(), [&](const ReferenceHit& hit) { return hit.id == id; });
  };
  layers.tied = std::any_of(ties.begin(), ties.end(), [&](const auto& tie) { return shown(tie.first) && shown(tie.second); });
  return layers;
}

bool SurfaceReference::blocked(const Ray& segment, double tMin, std::uint32_t except, Counters& counters) const {
  if (bvh_.empty()) return false;
  const ShearedRay<double> shear(segment);
  const RayBoxTest boxes(segment.origin, segment.direction);
  const auto meets = [&](const PackedTriangle& tri) {
    ++counters.triangleTests;
    const WoopTerms<double> terms = woopTerms(shear, tri.a, tri.b, tri.c);
    const WoopBounds<double> bounds = woopBounds(shear, tri.a, tri.b, tri.c, terms);
    const double t = bounds.t;
    const Certainty hit = certainty(insideWithBounds(terms, bounds));
    if (hit == Certainty::no) return false;
    if (hit == Certainty::yes && t - bounds.tBound > tMin && t + bounds.tBound <= 1) return true;
    if (hit == Certainty::yes && (t + bounds.tBound <= tMin || t - bounds.tBound > 1)) return false;
    ++counters.exactTriangleTests;
    const woop::ExactTerms exact = woop::exactTerms(segment, tri.a, tri.b, tri.c);
    return woop::inside(exact) && exact.t.compareWith(tMin) > 0 && exact.t.compareWith(1) <= 0;
  };
  std::array<std::uint32_t, Bvh::kMaxDepth + 1> stack;
  int size = 0;
  const std::vector<BvhNode>& nodes = bvh_.nodes();
  stack[size++] = 0;
  while (size > 0) {
    const BvhNode& node = nodes[stack[--size]];
    ++counters.nodesVisited;
    if (boxes.entry(node, 1.0) == kInfinity) continue;
    if (!node.leaf()) {
      stack[size++] = node.index;
      stack[size++] = node.index + 1;
      continue;
    }
    for (std::uint32_t slot = node.index; slot < node.index + node.count; ++slot)
      if (triangles_[slot].id != except + 1 && scene_.instanceOf(triangles_[slot].id - 1).opacity >= 1 && meets(triangles_[slot]))
        return true;
  }
  return false;
}

ExactShadows::ExactShadows(const PreparedScene& scene, Stats& stats) : scene_(scene), reference_(scene, stats) {
  const Aabb bounds = scene.bounds();
  reach_ = bounds.empty() ? 1.0 : 2 * glm::length(bounds.hi - bounds.lo) + 1.0;
}

bool ExactShadows::shadowed(std::size_t light, const dvec3& point, std::uint32_t triangle) const {
  const Light& source = scene_.scene().lights[light];
  const dvec3 direction = source.kind == Light::Kind::directional ? -source.direction * reach_ : source.position - point;
  SurfaceReference::Counters counters;
  return reference_.blocked({point, direction}, 1e-9, triangle, counters);
}

ReferenceImage traceReference(const PreparedScene& scene, int threads, Stats& stats, ReferenceTraversal traversal) {
  ReferenceImage image;
  traceReference(scene, threads, stats, traversal, image);
  return image;
}

void traceReference(const PreparedScene& scene, int threads, Stats& stats, ReferenceTraversal traversal, ReferenceImage& image) {
  const SurfaceReference reference(scene, stats, traversal, threads);  // the BVHs built on first use, on this render's threads
  const CameraTransform& camera = scene.camera();
  PhaseTimer timer(stats, "reference");
  // Every pixel's id, depth and ambiguity is written below: an image of this size is
  // reused as it is, as a renderer reuses its framebuffer.
  if (image.frame.width != scene.width() || image.frame.height != scene.height()) image.frame = Frame(scene.width(), scene.height(), threads);
  image.ambiguous.resize(image.frame.pixelCount());
  image.ambiguousPixels = image.exactFallbacks = image.blendTiedPixels = 0;
  image.blendTied.clear();

  // One work item per band of four rows of tiles; each writes only its own pixels and
  // counters. Within a band, a tile's candidate may come from the tile above it.
  constexpr int kTile = SurfaceReference::kTileSize, kBand = 4 * kTile;
  const auto width = static_cast<std::size_t>(scene.width());
  const auto bands = static_cast<std::size_t>((scene.height() + kBand - 1) / kBand);
  std::vector<SurfaceReference::Counters> counters(bands);
  std::vector<std::int64_t> exactRays(bands, 0), ambiguousPixels(bands, 0);
  std::vector<std::vector<ReferenceHit>> bandHits(std::size_t(resolveThreadCount(threads)), std::vector<ReferenceHit>(kBand * width));
  parallelFor(bands, threads, [&](std::size_t band, int worker) {
    // Counted on this thread's stack and stored once: neighbouring bands' counters share
    // cache lines, and other threads work on them.
    SurfaceReference::Counters bandCounters;
    std::int64_t bandExact = 0, bandAmbiguous = 0;
    std::vector<ReferenceHit>& hits = bandHits[std::size_t(worker)];
    const int y0 = int(band) * kBand, rows = std::min(kBand, scene.height() - y0);
    for (int top = 0; top < rows; top += kTile) {
      ReferenceHit* tileRow = &hits[std::size_t(top) * width];
      reference.traceTileRow(camera, y0 + top, std::min(kTile, rows - top), top > 0 ? tileRow - width : nullptr, tileRow, width, bandCounters);
    }
    // Through pointers taken once: stored through a vector, a byte could alias the
    // vectors' own pointers, which were then read again for every pixel.
    const std::size_t at = std::size_t(y0) * width;
    std::uint32_t* ids = image.frame.ids.data() + at;
    float* depth = image.frame.depth.data() + at;
    std::uint8_t* ambiguous = image.ambiguous.data() + at;
    for (std::size_t pixel = 0; pixel < std::size_t(rows) * width; ++pixel) {
      const ReferenceHit& hit = hits[pixel];
      ids[pixel] = hit.id;
      depth[pixel] = static_cast<float>(hit.distance);
      ambiguous[pixel] = hit.ambiguous;
      bandExact += hit.usedExact;
      bandAmbiguous += hit.ambiguous;
    }
    counters[band] = bandCounters;
    exactRays[band] = bandExact;
    ambiguousPixels[band] = bandAmbiguous;
  });
  SurfaceReference::Counters total;
  for (std::size_t band = 0; band < bands; ++band) {
    total.nodesVisited += counters[band].nodesVisited;
    total.triangleTests += counters[band].triangleTests;
    total.exactTriangleTests += counters[band].exactTriangleTests;
    total.exactComparisons += counters[band].exactComparisons;
    total.tilesProved += counters[band].tilesProved;
    total.raysProved += counters[band].raysProved;
    image.exactFallbacks += exactRays[band];
    image.ambiguousPixels += ambiguousPixels[band];
  }
  stats.add("reference rays", static_cast<std::int64_t>(image.frame.pixelCount()));
  stats.add("reference exact fall-backs", image.exactFallbacks);
  stats.add("reference ambiguous pixels", image.ambiguousPixels);
  stats.add("reference tiles proved", total.tilesProved);
  stats.add("reference rays proved", total.raysProved);
  stats.add("bvh nodes visited", total.nodesVisited);
  stats.add("ray-triangle tests", total.triangleTests);
  stats.add("exact ray-triangle tests", total.exactTriangleTests);
  stats.add("exact depth comparisons", total.exactComparisons);
}

ReferenceImage renderReference(const PreparedScene& scene, int threads, Stats& stats) {
  ReferenceImage image = traceReference(scene, threads, stats);
  const CameraTransform& camera = scene.camera();
  const Effects& effects = scene.scene().effects;
  std::optional<ExactShadows> shadows;
  if (effects.shadows) shadows.emplace(scene, stats);
  PixelShader<double> shader(scene, camera, shadows ? &*shadows : nullptr);
  if (!effects.transparency) {
    shadeFrame(scene, image.frame, shader, threads, stats);
  } else {
    // The exact blend: every surface along the pixel's ray, in exact depth order, each
    // "over" the ones behind it, from the nearest opaque one (or the background) forward.
    PhaseTimer timer(stats, "shading");
    // Any surface may be seen through glass: every one is set up.
    std::vector<std::uint32_t> everyTriangle(scene.triangleCount());
    std::iota(everyTriangle.begin(), everyTriangle.end(), 0u);
    shader.setUp(everyTriangle, threads, stats);
    const SurfaceReference reference(scene, stats);
    const dvec3 background(scene.scene().background);
    const auto rows = static_cast<std::size_t>(scene.height());
    image.blendTied.assign(image.frame.pixelCount(), 0);
    std::vector<ShadingCounts> counts(rows);
    parallelFor(rows, threads, [&](std::size_t row, int) {
      SurfaceReference::Counters rayCounters;
      for (int x = 0; x < scene.width(); ++x) {
        const std::size_t pixel = row * std::size_t(scene.width()) + std::size_t(x);
        const auto layers = reference.traceAll(camera, camera.rayThroughPixel(conventions::pixelCenter(x), conventions::pixelCenter(int(row))), rayCounters);
        // The last layer is the opaque surface everything else is seen over, if any.
        std::size_t layer = layers.hits.size();
        const bool opaqueLast = layer > 0 && scene.instanceOf(layers.hits[layer - 1].id - 1).opacity >= 1;
        dvec3 color = opaqueLast ? shader.shade(layers.hits[--layer].id - 1, x, int(row), counts[row]) : background;
        while (layer-- > 0) {
          const double opacity = scene.instanceOf(layers.hits[layer].id - 1).opacity;
          color = opacity * shader.shade(layers.hits[layer].id - 1, x, int(row), counts[row]) + (1 - opacity) * color;
        }
        image.blendTied[pixel] = layers.tied;
        for (int c = 0; c < 3; ++c) image.frame.color[4 * pixel + std::size_t(c)] = channelByte(color[c]);
        image.frame.color[4 * pixel + 3] = 255;
      }
    });
    ShadingCounts total;
    for (const ShadingCounts& row : counts) total += row;
    total.addTo(stats);
    for (const std::uint8_t tied : image.blendTied) image.blendTiedPixels += tied;
  }
  if (effects.fog) applyFog(effects.fogSettings, image.frame, threads, stats);
  if (effects.outline) drawOutline(scene, camera, effects.outlineSettings, effects.fog ? &effects.fogSettings : nullptr, image.frame, stats);
  return image;
}

}  // namespace hsr
