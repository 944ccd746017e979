#include "renderer/shading/shading.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>

#include "renderer/util/conventions.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/parallel.hpp"
#include "renderer/util/portable_math.hpp"

namespace hsr {

dvec3 towardLight(const Light& light, const dvec3& point) {
  return light.kind == Light::Kind::directional ? -light.direction : glm::normalize(light.position - point);
}

ShadingCounts& ShadingCounts::operator+=(const ShadingCounts& other) {
  invocations += other.invocations;
  specularTerms += other.specularTerms;
  shadowLookups += other.shadowLookups;
  shadowedLookups += other.shadowedLookups;
  return *this;
}

void ShadingCounts::addTo(Stats& stats) const {
  stats.add("shading invocations", invocations);
  if (specularTerms) stats.add("specular terms", specularTerms);
  if (shadowLookups) stats.add("shadow lookups", shadowLookups);
  if (shadowedLookups) stats.add("shadowed lookups", shadowedLookups);
}

template <class Real>
PixelShader<Real>::PixelShader(const PreparedScene& scene, const CameraTransform& camera, const ShadowTest* shadows)
    : scene_(scene), camera_(camera), shadows_(scene.scene().effects.shadows ? shadows : nullptr), slotOf_(scene.triangleCount(), 0) {
  const Scene& description = scene.scene();
  HSR_CHECK(!description.effects.shadows || shadows);
  smooth_ = description.effects.smoothNormals();
  lit_ = description.effects.lit();
  specular_ = description.effects.shading == Shading::phong;
  ambient_ = Real(description.ambient);
  // The eye rays every set-up samples its planes at, the same for every triangle.
  const double samples[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  for (int s = 0; s < 3; ++s) {
    sampleRays_[s] = camera.rayThroughPixel(samples[s][0], samples[s][1]);
    sampleRays_[s].origin -= camera.camera().eye;
  }
  for (const Light& light : description.lights) {
    lights_.push_back({light.kind == Light::Kind::directional, Vec(-light.direction), Vec(light.position - camera.camera().eye),
                       Real(light.intensity)});
  }
}

template <class Real>
typename PixelShader<Real>::TriangleSetUp PixelShader<Real>::makeSetUp(std::uint32_t triangle, const VertexTriangles* around,
                                                                        std::int64_t& fromMesh) const {
  const dvec3 eye = camera_.camera().eye;
  const Triangle& t = scene_.triangles()[triangle];
  dvec3 corner[3];
  for (int k = 0; k < 3; ++k) corner[k] = scene_.positions()[t[std::size_t(k)]] - eye;
  const dvec3 face = scene_.faceNormal(triangle);
  // Corner k's weight at a pixel is the eye ray's triple product with the edge opposite
  // k, (d . ((V_k+1 - o) x (V_k+2 - o))). Lit from both sides, a surface seen from behind
  // shades as its front would: which side a pixel's eye ray sees is the sign of
  // face . -d. Both are linear in the pixel coordinates under both projections, so their
  // values on the three sample rays give their planes.
  dvec3 weights[3];
  double facing[3];
  for (int s = 0; s < 3; ++s) {
    const Ray& ray = sampleRays_[s];
    for (int k = 0; k < 3; ++k)
      weights[s][k] = glm::dot(ray.direction, glm::cross(corner[(k + 1) % 3] - ray.origin, corner[(k + 2) % 3] - ray.origin));
    facing[s] = -glm::dot(face, ray.direction);
  }
  TriangleSetUp setUp;
  setUp.weightsAt0 = weights[0];
  setUp.weightsPerX = weights[1] - weights[0];
  setUp.weightsPerY = weights[2] - weights[0];
  setUp.facingAt0 = Real(facing[0]);
  setUp.facingPerX = Real(facing[1] - facing[0]);
  setUp.facingPerY = Real(facing[2] - facing[0]);
  for (int k = 0; k < 3; ++k) setUp.corner[k] = Vec(corner[k]);
  setUp.face = Vec(face);
  if (around) {
    std::array<dvec3, 3> normals;
    fromMesh += scene_.cornerNormals(triangle, *around, normals);
    for (int k = 0; k < 3; ++k) setUp.normal[k] = Vec(normals[std::size_t(k)]);
  }

  const Instance& instance = scene_.instanceOf(triangle);
  const SceneObject& material = scene_.scene().objects[instance.object];
  setUp.color = Vec(instance.color);
  setUp.reflectivity = Real(material.reflectivity);
  setUp.shininess = Real(material.shininess);
  setUp.triangle = triangle;
  return setUp;
}

template <class Real>
void PixelShader<Real>::setUpClaimed(const std::vector<std::uint32_t>& claimed, int threads, Stats& stats) {
  const std::size_t first = setUps_.size();
  for (std::size_t i = 0; i < claimed.size(); ++i) slotOf_[claimed[i]] = static_cast<std::uint32_t>(first + i + 1);
  setUps_.resize(first + claimed.size());
  const VertexTriangles* around = smooth_ ? &scene_.trianglesAroundVertices(stats, threads) : nullptr;
  constexpr std::size_t kChunk = 256;
  const std::size_t chunks = (claimed.size() + kChunk - 1) / kChunk;
  std::vector<std::int64_t> fromMesh(chunks, 0);
  parallelFor(chunks, threads, [&](std::size_t chunk, int) {
    for (std::size_t i = chunk * kChunk; i < std::min(claimed.size(), (chunk + 1) * kChunk); ++i)
      setUps_[first + i] = makeSetUp(claimed[i], around, fromMesh[chunk]);
  });
  stats.add("shading set-ups", static_cast<std::int64_t>(claimed.size()));
  if (!smooth_) return;
  std::int64_t given = 0;
  for (const std::int64_t chunk : fromMesh) given += chunk;
  if (given > 0) stats.add("normals from the mesh", given);
  if (3 * std::int64_t(claimed.size()) > given) stats.add("normals computed", 3 * std::int64_t(claimed.size()) - given);
}

template <class Real>
void PixelShader<Real>::setUp(std::span<const std::uint32_t> triangles, int threads, Stats& stats) {
  std::vector<std::uint32_t> claimed;
  for (const std::uint32_t triangle : triangles)
    if (slotOf_[triangle] == 0) {
      slotOf_[triangle] = 1;  // claimed; setUpClaimed gives it its slot
      claimed.push_back(triangle);
    }
  setUpClaimed(claimed, threads, stats);
}

template <class Real>
void PixelShader<Real>::setUpShownIn(const Frame& frame, int threads, Stats& stats) {
  // Rows in parallel; each triangle claimed by whichever row meets it first. Which row
  // that is changes only where its set-up is stored, never what it holds.
  const auto rows = static_cast<std::size_t>(frame.height);
  std::vector<std::vector<std::uint32_t>> claimedIn(rows);
  parallelFor(rows, threads, [&](std::size_t row, int) {
    std::uint32_t previous = conventions::kBackgroundId;
    for (std::size_t pixel = row * std::size_t(frame.width); pixel < (row + 1) * std::size_t(frame.width); ++pixel) {
      const std::uint32_t id = frame.ids[pixel];
      if (id == previous || id == conventions::kBackgroundId) continue;
      previous = id;
      if (claimFlag(slotOf_[id - 1])) claimedIn[row].push_back(id - 1);
    }
  });
  std::vector<std::uint32_t> claimed;
  for (const auto& row : claimedIn) claimed.insert(claimed.end(), row.begin(), row.end());
  setUpClaimed(claimed, threads, stats);
}

template <class Real>
void PixelShader<Real>::interpolateRun(const TriangleSetUp& setUp, int y, int firstX, int count, RunPoints& points) const {
  // Step 1: barycentrics. The weights at the run's first pixel in double, then stepped
  // along the row in Real: the step's rounding grows with the run's length only.
  const dvec3 first = setUp.weightsAt0 + conventions::pixelCenter(firstX) * setUp.weightsPerX +
                      conventions::pixelCenter(y) * setUp.weightsPerY;
  const Vec start(first), step(setUp.weightsPerX);
  Real* const b0 = points.b0;
  Real* const b1 = points.b1;
  Real* const b2 = points.b2;
  for (int i = 0; i < count; ++i) {
    const Real w0 = start.x + Real(i) * step.x, w1 = start.y + Real(i) * step.y, w2 = start.z + Real(i) * step.z;
    // A pixel center may sit a hair outside the triangle (it was covered after snapping
    // to 1/256 pixel; the ray march's triangle may not cover it at all): each weight,
    // over the three's sum, is clamped to [0, 1], which clamps the point to the
    // triangle; done before the division (to between 0 and the sum), so that one
    // division normalizes what is left. Seen edge-on the weights nearly cancel, but
    // the clamped ones still name a point of the triangle, as good as any other there;
    // only when none is left (all zero) does the centroid serve.
    const Real sum = w0 + w1 + w2, low = std::min(sum, Real(0)), high = std::max(sum, Real(0));
    const Real c0 = std::min(std::max(w0, low), high), c1 = std::min(std::max(w1, low), high), c2 = std::min(std::max(w2, low), high);
    const Real total = c0 + c1 + c2;
    const bool none = !(std::abs(total) > 0);
    const Real normalize = none ? Real(1) / 3 : 1 / total;
    b0[i] = none ? normalize : c0 * normalize, b1[i] = none ? normalize : c1 * normalize, b2[i] = none ? normalize : c2 * normalize;
  }
  // Step 2: the normal, interpolated (Phong shading) or the face's (flat), turned
  // toward the side the pixel's ray sees.
  const Vec n0 = setUp.normal[0], n1 = setUp.normal[1], n2 = setUp.normal[2], face = setUp.face;
  const Real facingStart = setUp.facingAt0 + Real(conventions::pixelCenter(firstX)) * setUp.facingPerX +
                           Real(conventions::pixelCenter(y)) * setUp.facingPerY;
  const auto side = [&](int i) { return facingStart + Real(i) * setUp.facingPerX < 0 ? Real(-1) : Real(1); };
  if (!smooth_) {
    for (int i = 0; i < count; ++i) points.nx[i] = side(i) * face.x, points.ny[i] = side(i) * face.y, points.nz[i] = side(i) * face.z;
    return;
  }
  for (int i = 0; i < count; ++i) {
    const Real sx = b0[i] * n0.x + b1[i] * n1.x + b2[i] * n2.x, sy = b0[i] * n0.y + b1[i] * n1.y + b2[i] * n2.y,
               sz = b0[i] * n0.z + b1[i] * n1.z + b2[i] * n2.z;
    const Real length = std::sqrt(sx * sx + sy * sy + sz * sz);
    // Corner normals that cancel (a fold) leave no direction: the face's serves.
    const bool none = !(length > 0);
    const Real inverse = side(i) / (none ? Real(1) : length);
    points.nx[i] = none ? side(i) * face.x : sx * inverse;
    points.ny[i] = none ? side(i) * face.y : sy * inverse;
    points.nz[i] = none ? side(i) * face.z : sz * inverse;
  }
}

template <class Real>
typename PixelShader<Real>::Vec PixelShader<Real>::RunPoints::position(const TriangleSetUp& setUp, int i) const {
  return b0[i] * setUp.corner[0] + b1[i] * setUp.corner[1] + b2[i] * setUp.corner[2];
}

template <class Real>
typename PixelShader<Real>::Vec PixelShader<Real>::toViewer(const Vec& position) const {
  return camera_.perspective() ? -glm::normalize(position) : Vec(-camera_.forward());
}

template <class Real>
void PixelShader<Real>::shadeRun(const TriangleSetUp& setUp, int y, int firstX, int count, RunColors& colors,
                                 ShadingCounts& counts) const {
  HSR_CHECK(count >= 1 && count <= kRun);
  counts.invocations += count;
  if (!lit_) {
    std::fill_n(colors.r, count, setUp.color.x);
    std::fill_n(colors.g, count, setUp.color.y);
    std::fill_n(colors.b, count, setUp.color.z);
    return;
  }
  RunPoints points;
  interpolateRun(setUp, y, firstX, count, points);
  // Phong's model (1975) with Blinn's half-vector (1977): ambient, plus per light that
  // reaches the point Lambert's cosine law and a white highlight.
  Real diffuse[kRun], highlight[kRun];
  std::fill_n(diffuse, count, ambient_);
  std::fill_n(highlight, count, Real(0));
  for (std::size_t light = 0; light < lights_.size(); ++light) {
    const LightSource& source = lights_[light];
    if (source.directional && !shadows_ && !specular_) {
      // The common case, one loop without branches: the cosine law, nothing behind the surface.
      const Vec toLight = source.towardLight;
      for (int i = 0; i < count; ++i)
        diffuse[i] += source.intensity * std::max(Real(0), points.nx[i] * toLight.x + points.ny[i] * toLight.y + points.nz[i] * toLight.z);
      continue;
    }
    for (int i = 0; i < count; ++i) {
      const Vec normal(points.nx[i], points.ny[i], points.nz[i]), position = points.position(setUp, i);
      const Vec toLight = source.directional ? source.towardLight : glm::normalize(source.position - position);
      const Real cosine = glm::dot(normal, toLight);
      if (cosine <= 0) continue;  // the light is behind the surface: no shadow test needed
      if (shadows_) {
        ++counts.shadowLookups;
        if (shadows_->shadowed(light, camera_.camera().eye + dvec3(position), setUp.triangle)) {
          ++counts.shadowedLookups;
          continue;
        }
      }
      diffuse[i] += source.intensity * cosine;
      if (specular_) {
        ++counts.specularTerms;
        const Vec half = glm::normalize(toLight + toViewer(position));
        highlight[i] += source.intensity * setUp.reflectivity * Real(portable::pow(double(std::max(Real(0), glm::dot(normal, half))), double(setUp.shininess)));
      }
    }
  }
  for (int i = 0; i < count; ++i) {
    colors.r[i] = setUp.color.x * diffuse[i] + highlight[i];
    colors.g[i] = setUp.color.y * diffuse[i] + highlight[i];
    colors.b[i] = setUp.color.z * diffuse[i] + highlight[i];
  }
}

template <class Real>
typename PixelShader<Real>::Color PixelShader<Real>::shade(std::uint32_t triangle, int x, int y, ShadingCounts& counts) const {
  RunColors colors;
  shadeRun(setUpOf(triangle), y, x, 1, colors, counts);
  return colors.at(0);
}

template <class Real>
SurfacePoint PixelShader<Real>::surfacePoint(std::uint32_t triangle, int x, int y) const {
  RunPoints points;
  const TriangleSetUp& setUp = setUpOf(triangle);
  interpolateRun(setUp, y, x, 1, points);
  const Vec normal(points.nx[0], points.ny[0], points.nz[0]), position = points.position(setUp, 0);
  return {camera_.camera().eye + dvec3(position), dvec3(normal), dvec3(toViewer(position))};
}

template <class Real>
void shadeFrame(const PreparedScene& scene, Frame& frame, PixelShader<Real>& shader, int threads, Stats& stats) {
  PhaseTimer timer(stats, "shading");
  shader.setUpShownIn(frame, threads, stats);
  // Each pixel's four bytes are written as one 32-bit store (R first in memory).
  static_assert(std::endian::native == std::endian::little);
  const auto rgbaWord = [](std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    return std::uint32_t(r) | std::uint32_t(g) << 8 | std::uint32_t(b) << 16 | std::uint32_t(255) << 24;
  };
  const glm::dvec3& backgroundColor = scene.scene().background;
  const std::uint32_t background =
      rgbaWord(channelByte(backgroundColor.x), channelByte(backgroundColor.y), channelByte(backgroundColor.z));
  std::vector<ShadingCounts> counts(static_cast<std::size_t>(frame.height));
  parallelFor(static_cast<std::size_t>(frame.height), threads, [&](std::size_t row, int) {
    const std::uint32_t* const ids = frame.ids.data() + row * std::size_t(frame.width);
    std::uint8_t* const rgba = frame.color.data() + 4 * row * std::size_t(frame.width);
    ShadingCounts rowCounts;
    // Run by run of pixels showing one triangle, which share its set-up.
    constexpr int kBatch = PixelShader<Real>::kRun;
    typename PixelShader<Real>::RunColors colors;
    for (int runStart = 0, runEnd; runStart < frame.width; runStart = runEnd) {
      const std::uint32_t id = ids[runStart];
      for (runEnd = runStart + 1; runEnd < frame.width && ids[runEnd] == id;) ++runEnd;
      if (id == conventions::kBackgroundId) {
        for (int x = runStart; x < runEnd; ++x) std::memcpy(rgba + 4 * x, &background, 4);
        continue;
      }
      const auto& setUp = shader.setUpOf(id - 1);
      for (int batchStart = runStart; batchStart < runEnd; batchStart += kBatch) {
        const int count = std::min(kBatch, runEnd - batchStart);
        shader.shadeRun(setUp, static_cast<int>(row), batchStart, count, colors, rowCounts);
        std::uint8_t* const pixels = rgba + 4 * batchStart;
        for (int i = 0; i < count; ++i) {
          const std::uint32_t word = rgbaWord(channelByte(colors.r[i]), channelByte(colors.g[i]), channelByte(colors.b[i]));
          std::memcpy(pixels + 4 * i, &word, 4);
        }
      }
    }
    counts[row] = rowCounts;
  });
  ShadingCounts total;
  for (const ShadingCounts& row : counts) total += row;
  total.addTo(stats);
}

template class PixelShader<float>;
template class PixelShader<double>;
template void shadeFrame(const PreparedScene&, Frame&, PixelShader<float>&, int, Stats&);
template void shadeFrame(const PreparedScene&, Frame&, PixelShader<double>&, int, Stats&);

}  // namespace hsr
