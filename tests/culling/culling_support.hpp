// What the culling tests share: running a pipeline, drawing what it kept, and judging it
// against the exact reference.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "algorithms/culling/culling.hpp"
#include "algorithms/zbuffer/zbuffer.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/util/error.hpp"
#include "test_support.hpp"

namespace hsr {

inline VisibleSet cull(const PreparedScene& scene, const std::string& pipeline, Stats& stats, int threads = 2) {
  return culling::runPipeline(scene, culling::parsePipeline(pipeline), threads, stats);
}

inline VisibleSet cull(const PreparedScene& scene, const std::string& pipeline) {
  Stats stats;
  return cull(scene, pipeline, stats);
}

// The one-line error parsing `text` as a --cull pipeline gives, or "(no error)".
inline std::string pipelineError(const std::string& text) {
  try {
    culling::parsePipeline(text);
  } catch (const InputError& error) {
    return std::string(error.what());
  }
  return std::string("(no error)");
}

inline std::vector<std::uint8_t> keptMask(const VisibleSet& set, std::size_t triangles) {
  std::vector<std::uint8_t> kept(triangles, 0);
  for (const std::uint32_t t : set.triangles) kept[t] = 1;
  return kept;
}

inline Frame renderKept(const PreparedScene& scene, const VisibleSet& kept, zbuffer::Knobs knobs = {}) {
  Stats stats;
  return test::visibilityOf(scene, knobs, 1, stats, &kept);
}

// A scene with its exact reference and the triangles the reference shows.
struct Judged {
  test::LoadedScene loaded;
  ReferenceImage truth;
  std::vector<std::uint8_t> visible;
  explicit Judged(const std::filesystem::path& file, int width = 0) : loaded(file, width) { retrace(); }
  // After the scene (its camera) changed.
  void retrace() {
    Stats stats;
    truth = traceReference(loaded.prepared, 2, stats);
    visible = visibleTriangles(truth, loaded.prepared.triangleCount());
  }
  std::int64_t falseCulls(const VisibleSet& kept) const {
    return cullingError(keptMask(kept, loaded.prepared.triangleCount()), visible).falseCulls;
  }
  // The objects the reference shows that `kept` has none of the triangles of.
  std::int64_t objectsFalselyCulled(const VisibleSet& kept) const {
    const PreparedScene& scene = loaded.prepared;
    return cullingError(objectsWithAny(scene, keptMask(kept, scene.triangleCount())), objectsWithAny(scene, visible)).falseCulls;
  }
};

}  // namespace hsr
