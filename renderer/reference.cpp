#include "renderer/reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include <gmpxx.h>

#include "renderer/conventions.hpp"
#include "renderer/error.hpp"
#include "renderer/parallel.hpp"
#include "renderer/rounding.hpp"
#include "renderer/fog.hpp"
#include "renderer/outline.hpp"
#include "renderer/shading.hpp"

namespace hsr {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Woop, Benthin, Wald 2013, section 4, the per-ray set-up: kz is the dominant axis of
// the direction, and the shear (sx, sy, sz) maps the ray onto the +z axis from the
// origin. Swapping kx and ky when the ray runs down kz keeps the winding. Number is
// double for the fast test and mpq_class (exact rationals) for the fall-back.
template <typename Number>
struct ShearedRay {
  int kx, ky, kz;
  std::array<Number, 3> origin;
  Number sx, sy, sz;

  explicit ShearedRay(const Ray& ray) {
    const dvec3 size = glm::abs(ray.direction);
    kz = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
    kx = (kz + 1) % 3;
    ky = (kx + 1) % 3;
    if (ray.direction[kz] < 0) std::swap(kx, ky);
    for (int i = 0; i < 3; ++i) origin[i] = Number(ray.origin[i]);
    const Number dz = Number(ray.direction[kz]);
    sx = Number(ray.direction[kx]) / dz;
    sy = Number(ray.direction[ky]) / dz;
    sz = Number(1) / dz;
  }
};

// The test's values for one triangle (section 4, steps 2-5): u, v, w are the edge
// functions of the sheared triangle at the ray (the scaled barycentrics); the ray
// meets the triangle when they share a sign and det = u + v + w is not 0, at
// parameter t = scaledT / det.
template <typename Number>
struct WoopTerms {
  Number u, v, w, det, scaledT;
};

template <typename Number>
WoopTerms<Number> woopTerms(const ShearedRay<Number>& ray, const dvec3& a, const dvec3& b, const dvec3& c) {
  std::array<Number, 3> A, B, C;
  for (int i = 0; i < 3; ++i) {
    A[i] = Number(a[i]) - ray.origin[i];
    B[i] = Number(b[i]) - ray.origin[i];
    C[i] = Number(c[i]) - ray.origin[i];
  }
  const Number ax = A[ray.kx] - ray.sx * A[ray.kz], ay = A[ray.ky] - ray.sy * A[ray.kz];
  const Number bx = B[ray.kx] - ray.sx * B[ray.kz], by = B[ray.ky] - ray.sy * B[ray.kz];
  const Number cx = C[ray.kx] - ray.sx * C[ray.kz], cy = C[ray.ky] - ray.sy * C[ray.kz];
  WoopTerms<Number> terms;
  terms.u = cx * by - cy * bx;
  terms.v = ax * cy - ay * cx;
  terms.w = bx * ay - by * ax;
  terms.det = terms.u + terms.v + terms.w;
  terms.scaledT = terms.u * (ray.sz * A[ray.kz]) + terms.v * (ray.sz * B[ray.kz]) + terms.w * (ray.sz * C[ray.kz]);
  return terms;
}

// Forward error bounds of the double-precision terms against the exact values of the
// same formulas. Each sheared coordinate (a translation, a product with the rounded
// shear, a subtraction) is within 4u of its magnitude bound m = |x| + |s||z|; each
// edge function adds two products and a subtraction. The constants below round those
// counts up generously: a loose bound costs a rare extra exact test, a tight one is a bug.
// The error bounds of the edge functions u, v, w and of det; and the hit parameter
// t = scaledT / det with its bound tBound, computed only where |det| is surely above 0 (a
// ray surely not parallel to the triangle). Elsewhere no hit can be certain: t is 0 and
// tBound infinite, and nothing divides by zero.
struct WoopBounds {
  double u, v, w, det;
  double t = 0, tBound = 0;
};

WoopBounds woopBounds(const ShearedRay<double>& ray, const dvec3& a, const dvec3& b, const dvec3& c,
                      const WoopTerms<double>& terms) {
  struct Magnitude {
    double x, y, z;
  };
  const auto magnitude = [&](const dvec3& p) {
    const dvec3 q = p - dvec3(ray.origin[0], ray.origin[1], ray.origin[2]);
    const double along = std::abs(q[ray.kz]);
    return Magnitude{std::abs(q[ray.kx]) + std::abs(ray.sx) * along, std::abs(q[ray.ky]) + std::abs(ray.sy) * along,
                     std::abs(ray.sz) * along};
  };
  const Magnitude A = magnitude(a), B = magnitude(b), C = magnitude(c);
  constexpr double edge = 16 * kUnitRoundoff, sum = 4 * kUnitRoundoff;
  WoopBounds bounds;
  bounds.u = edge * (C.x * B.y + C.y * B.x);
  bounds.v = edge * (A.x * C.y + A.y * C.x);
  bounds.w = edge * (B.x * A.y + B.y * A.x);
  const double absU = std::abs(terms.u), absV = std::abs(terms.v), absW = std::abs(terms.w);
  bounds.det = bounds.u + bounds.v + bounds.w + sum * (absU + absV + absW);
  const double scaledT = edge * ((absU + bounds.u) * A.z + (absV + bounds.v) * B.z + (absW + bounds.w) * C.z) +
                         bounds.u * A.z + bounds.v * B.z + bounds.w * C.z;
  const double absDet = std::abs(terms.det);
  if (!(absDet > bounds.det)) {
    bounds.tBound = kInfinity;
    return bounds;
  }
  const double t = terms.scaledT / terms.det;
  bounds.t = t;
  bounds.tBound = (scaledT + std::abs(t) * bounds.det) / (absDet - bounds.det) + sum * std::abs(t);
  return bounds;
}

enum class Certainty { no, yes, unsure };

// Inside when u, v, w share a sign (zero counts as either: the edge belongs to both
// triangles that share it, which is what makes the test watertight) and det != 0.
template <typename Number>
bool inside(const WoopTerms<Number>& terms) {
  const bool allNonNegative = terms.u >= 0 && terms.v >= 0 && terms.w >= 0;
  const bool allNonPositive = terms.u <= 0 && terms.v <= 0 && terms.w <= 0;
  return (allNonNegative || allNonPositive) && terms.det != 0;
}

Certainty insideWithBounds(const WoopTerms<double>& terms, const WoopBounds& bounds) {
  const bool surelyPositive[3] = {terms.u > bounds.u, terms.v > bounds.v, terms.w > bounds.w};
  const bool surelyNegative[3] = {terms.u < -bounds.u, terms.v < -bounds.v, terms.w < -bounds.w};
  const bool somePositive = surelyPositive[0] || surelyPositive[1] || surelyPositive[2];
  const bool someNegative = surelyNegative[0] || surelyNegative[1] || surelyNegative[2];
  if (somePositive && someNegative) return Certainty::no;
  if ((surelyPositive[0] && surelyPositive[1] && surelyPositive[2]) ||
      (surelyNegative[0] && surelyNegative[1] && surelyNegative[2]))
    return Certainty::yes;
  return Certainty::unsure;
}

// Everything one ray needs: the shear in both arithmetics (the exact one built only
// when first needed) and the view distance of the point at parameter t,
// distance(t) = originDistance + t * slope, with its error bound.
class RayQuery {
 public:
  RayQuery(const Ray& ray, const CameraTransform& camera)
      : ray_(ray), camera_(camera), shear_(ray), near_(camera.camera().near), far_(camera.camera().far) {
    const dvec3 fromEye = ray.origin - camera.camera().eye;
    originDistance_ = glm::dot(fromEye, camera.forward());
    slope_ = glm::dot(ray.direction, camera.forward());
    const dvec3 f = glm::abs(camera.forward());
    originDistanceBound_ = 5 * kUnitRoundoff * glm::dot(glm::abs(fromEye), f);
    slopeBound_ = 4 * kUnitRoundoff * glm::dot(glm::abs(ray.direction), f);
  }

  const ShearedRay<double>& shear() const { return shear_; }

  double distance(double t) const { return originDistance_ + t * slope_; }

  // Is the hit at t (within tBound) between the near and far planes?
  Certainty inRange(double t, double tBound) const {
    const double d = distance(t);
    const double bound = originDistanceBound_ + std::abs(t) * slopeBound_ + std::abs(slope_) * tBound +
                         3 * kUnitRoundoff * (std::abs(originDistance_) + std::abs(t * slope_));
    if (d + bound < near_ || d - bound > far_) return Certainty::no;
    if (d - bound >= near_ && d + bound <= far_) return Certainty::yes;
    return Certainty::unsure;
  }

  // The exact hit parameter of a triangle, or nothing when the ray misses it or meets
  // it outside [near, far].
  std::optional<mpq_class> exactHit(const dvec3& a, const dvec3& b, const dvec3& c) {
    if (!exactShear_) exactShear_.emplace(ray_);
    const WoopTerms<mpq_class> terms = woopTerms(*exactShear_, a, b, c);
    if (!inside(terms)) return std::nullopt;
    mpq_class t = terms.scaledT / terms.det;
    mpq_class distance = t * exactDot(ray_.direction);
    for (int i = 0; i < 3; ++i)
      distance += (mpq_class(ray_.origin[i]) - mpq_class(camera_.camera().eye[i])) * mpq_class(camera_.forward()[i]);
    if (distance < mpq_class(near_) || distance > mpq_class(far_)) return std::nullopt;
    return t;
  }

 private:
  mpq_class exactDot(const dvec3& v) const {
    mpq_class sum = 0;
    for (int i = 0; i < 3; ++i) sum += mpq_class(v[i]) * mpq_class(camera_.forward()[i]);
    return sum;
  }

  const Ray& ray_;
  const CameraTransform& camera_;
  ShearedRay<double> shear_;
  std::optional<ShearedRay<mpq_class>> exactShear_;
  double near_, far_;
  double originDistance_, slope_, originDistanceBound_, slopeBound_;
};

// One triangle against the ray, between the near and far planes: the hit's parameter t
// within +-bound, decided in double precision where the error bounds allow and exactly
// where they do not (`exact`, set whenever the exact test ran, hit or not). A sure hit
// whose t - bound lies beyond `beyond` is dropped before any exact work (the nearest
// hit's search passes its horizon).
struct BoundedHit {
  double t = 0, bound = 0;
  bool hit = false, exact = false;
};

BoundedHit boundedHit(RayQuery& query, const PreparedScene::LeafTriangle& tri, double beyond, SurfaceReference::Counters& counters) {
  ++counters.triangleTests;
  const WoopTerms<double> terms = woopTerms(query.shear(), tri.a, tri.b, tri.c);
  const WoopBounds bounds = woopBounds(query.shear(), tri.a, tri.b, tri.c, terms);
  const double t = bounds.t;
  Certainty hit = insideWithBounds(terms, bounds);
  if (hit == Certainty::no) return {};
  if (hit == Certainty::yes) {
    if (t - bounds.tBound > beyond) return {};
    hit = query.inRange(t, bounds.tBound);
    if (hit == Certainty::no) return {};
    if (hit == Certainty::yes) return {t, bounds.tBound, true, false};
  }
  // A center on an edge, a grazing ray, or a hit on the near or far plane.
  ++counters.exactTriangleTests;
  const std::optional<mpq_class> exact = query.exactHit(tri.a, tri.b, tri.c);
  if (!exact) return {0, 0, false, true};
  const double rounded = exact->get_d();
  return {rounded, 2 * kUnitRoundoff * std::abs(rounded), true, true};
}

}  // namespace

SurfaceReference::SurfaceReference(const PreparedScene& scene, Stats& stats)
    : scene_(scene), bvh_(scene.triangleBvh(stats)), triangles_(scene.leafTriangles(stats)) {}

ReferenceHit SurfaceReference::trace(const CameraTransform& camera, const Ray& ray, Counters& counters) const {
  ReferenceHit result;
  if (bvh_.empty()) return result;
  RayQuery query(ray, camera);
  const RayBoxTest boxes(ray.origin, ray.direction);

  // Candidates for the nearest hit: every hit whose interval [t - bound, t + bound] can
  // still reach below the horizon, the smallest upper end t + bound seen so far.
  struct Candidate {
    double t, bound;
    std::uint32_t slot;  // index into triangles_
  };
  std::vector<Candidate> candidates;
  double horizon = kInfinity;
  const auto offer = [&](std::uint32_t slot) {
    const BoundedHit hit = boundedHit(query, triangles_[slot], horizon, counters);
    result.usedExact = result.usedExact || hit.exact;
    if (!hit.hit) return;
    horizon = std::min(horizon, hit.t + hit.bound);
    candidates.push_back({hit.t, hit.bound, slot});
    std::erase_if(candidates, [&](const Candidate& c) { return c.t - c.bound > horizon; });
  };

  // Front-to-back traversal: the nearer child first, and a node is skipped once its
  // entry lies beyond the horizon (widened by the rounding of the entry itself).
  constexpr double widen = 1 + 4 * kUnitRoundoff;
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
    if (pending.entry > horizon * widen) continue;
    const BvhNode& node = nodes[pending.node];
    ++counters.nodesVisited;
    if (node.leaf()) {
      for (std::uint32_t slot = node.index; slot < node.index + node.count; ++slot) offer(slot);
      continue;
    }
    const double limit = horizon * widen;
    Pending first{node.index, boxes.entry(nodes[node.index], limit)};
    Pending second{node.index + 1, boxes.entry(nodes[node.index + 1], limit)};
    if (second.entry < first.entry) std::swap(first, second);
    if (second.entry < kInfinity) stack[size++] = second;
    if (first.entry < kInfinity) stack[size++] = first;
  }

  std::erase_if(candidates, [&](const Candidate& c) { return c.t - c.bound > horizon; });
  if (candidates.empty()) return result;
  std::uint32_t winner = triangles_[candidates.front().slot].id;
  double winnerT = candidates.front().t;
  if (candidates.size() > 1) {
    // Depths too close for their bounds: compare exactly, and keep every exact tie.
    ++counters.exactComparisons;
    result.usedExact = true;
    std::optional<mpq_class> nearest;
    int ties = 0;
    for (const Candidate& candidate : candidates) {
      const PackedTriangle& tri = triangles_[candidate.slot];
      const std::optional<mpq_class> t = query.exactHit(tri.a, tri.b, tri.c);
      HSR_CHECK(t.has_value());
      if (!nearest || *t < *nearest) {
        nearest = t;
        winner = tri.id;
        ties = 1;
      } else if (*t == *nearest) {
        winner = std::min(winner, tri.id);
        ++ties;
      }
    }
    winnerT = nearest->get_d();
    result.ambiguous = ties > 1;
  }
  result.id = winner;
  result.distance = query.distance(winnerT);
  return result;
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
    const mpq_class ta = *query.exactHit(triangles_[a.slot].a, triangles_[a.slot].b, triangles_[a.slot].c);
    const mpq_class tb = *query.exactHit(triangles_[b.slot].a, triangles_[b.slot].b, triangles_[b.slot].c);
    if (ta != tb) return ta < tb;
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
  std::optional<ShearedRay<mpq_class>> exactShear;
  const RayBoxTest boxes(segment.origin, segment.direction);
  const auto meets = [&](const PackedTriangle& tri) {
    ++counters.triangleTests;
    const WoopTerms<double> terms = woopTerms(shear, tri.a, tri.b, tri.c);
    const WoopBounds bounds = woopBounds(shear, tri.a, tri.b, tri.c, terms);
    const double t = bounds.t;
    const Certainty hit = insideWithBounds(terms, bounds);
    if (hit == Certainty::no) return false;
    if (hit == Certainty::yes && t - bounds.tBound > tMin && t + bounds.tBound <= 1) return true;
    if (hit == Certainty::yes && (t + bounds.tBound <= tMin || t - bounds.tBound > 1)) return false;
    ++counters.exactTriangleTests;
    if (!exactShear) exactShear.emplace(segment);
    const WoopTerms<mpq_class> exact = woopTerms(*exactShear, tri.a, tri.b, tri.c);
    if (!inside(exact)) return false;
    const mpq_class exactT = exact.scaledT / exact.det;
    return exactT > mpq_class(tMin) && exactT <= 1;
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

ReferenceImage traceReference(const PreparedScene& scene, int threads, Stats& stats) {
  const SurfaceReference reference(scene, stats);
  const CameraTransform& camera = scene.camera();
  PhaseTimer timer(stats, "reference");
  ReferenceImage image;
  image.frame = Frame(scene.width(), scene.height());
  image.ambiguous.assign(image.frame.pixelCount(), 0);

  // One work item per row; each writes only its own pixels and counters.
  const auto rows = static_cast<std::size_t>(scene.height());
  std::vector<SurfaceReference::Counters> counters(rows);
  std::vector<std::int64_t> exactRays(rows, 0), ambiguousPixels(rows, 0);
  parallelFor(rows, threads, [&](std::size_t row, int) {
    // Counted on this thread's stack and stored once: neighbouring rows' counters share
    // cache lines, and other threads work on them.
    SurfaceReference::Counters rowCounters;
    std::int64_t rowExact = 0, rowAmbiguous = 0;
    for (int x = 0; x < scene.width(); ++x) {
      const std::size_t pixel = row * std::size_t(scene.width()) + std::size_t(x);
      const ReferenceHit hit = reference.trace(camera, camera.rayThroughPixel(conventions::pixelCenter(x), conventions::pixelCenter(int(row))), rowCounters);
      image.frame.ids[pixel] = hit.id;
      image.frame.depth[pixel] = hit.id == conventions::kBackgroundId ? std::numeric_limits<float>::infinity()
                                                                       : static_cast<float>(hit.distance);
      image.ambiguous[pixel] = hit.ambiguous;
      rowExact += hit.usedExact;
      rowAmbiguous += hit.ambiguous;
    }
    counters[row] = rowCounters;
    exactRays[row] = rowExact;
    ambiguousPixels[row] = rowAmbiguous;
  });
  SurfaceReference::Counters total;
  for (std::size_t row = 0; row < rows; ++row) {
    total.nodesVisited += counters[row].nodesVisited;
    total.triangleTests += counters[row].triangleTests;
    total.exactTriangleTests += counters[row].exactTriangleTests;
    total.exactComparisons += counters[row].exactComparisons;
    image.exactFallbacks += exactRays[row];
    image.ambiguousPixels += ambiguousPixels[row];
  }
  stats.add("reference rays", static_cast<std::int64_t>(image.frame.pixelCount()));
  stats.add("reference exact fall-backs", image.exactFallbacks);
  stats.add("reference ambiguous pixels", image.ambiguousPixels);
  stats.add("bvh nodes visited", total.nodesVisited);
  stats.add("ray-triangle tests", total.triangleTests);
  stats.add("exact ray-triangle tests", total.exactTriangleTests);
  stats.add("exact depth comparisons", total.exactComparisons);
  return image;
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
