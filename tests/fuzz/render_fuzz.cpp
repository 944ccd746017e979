// Fuzz target: the whole path a student's scene takes, load -> prepare -> render, for
// every algorithm in the registry, each variant, and the culling stages before every
// algorithm that takes them. The image is shrunk to a few hundred pixels and the shadow
// maps to 64 texels a side, and scenes of more than kMaxTriangles triangles are skipped,
// so that each input takes milliseconds: the fuzzer is after crashes, hangs and sanitizer
// reports, which do not need big images. A refusal or an InputError is a correct answer;
// an id outside the scene, a wrong-sized frame or any crash is a bug.
#include <algorithm>

#include "algorithms/culling/culling.hpp"
#include "algorithms/registry.hpp"
#include "pipeline/pipeline.hpp"
#include "renderer/scene/prepare.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace hsr::fuzz {
namespace {

constexpr std::int64_t kMaxTriangles = 1000;

void checkFrame(const PreparedScene& prepared, const Frame& frame, int width, int height) {
  HSR_CHECK(frame.width == width && frame.height == height);
  HSR_CHECK(frame.ids.size() == std::size_t(width) * std::size_t(height));
  for (const std::uint32_t id : frame.ids) HSR_CHECK(id <= prepared.triangleCount());
}

// Each value of the algorithm's variant knob (or just the defaults when it has none).
std::vector<KnobValues> variantsOf(const AlgorithmEntry& algorithm) {
  const KnobSpec* variant = findKnob(algorithm, "variant");
  if (!variant) return {resolveKnobs(algorithm, {})};
  std::vector<KnobValues> all;
  for (const std::string& choice : variant->choices) all.push_back(resolveKnobs(algorithm, {{"variant", choice}}));
  return all;
}

void renderEveryWay(const PreparedScene& prepared, int width, int height) {
  const culling::Pipeline everyStage = culling::parsePipeline("backface,frustum,occlusion");
  for (const AlgorithmEntry& algorithm : algorithms())
    for (const KnobValues& knobs : variantsOf(algorithm)) {
      pipeline::Configuration configuration{&algorithm, knobs};
      if (!pipeline::refusal(prepared, configuration).empty()) continue;
      Stats stats;
      const pipeline::Rendered rendered = pipeline::render(prepared, configuration, 1, stats);
      checkFrame(prepared, rendered.frame, width, height);
      if (algorithm.kind == AlgorithmKind::line) algorithm.judgeLines(prepared, knobs, rendered.drawing, 1, stats);
      if (algorithm.takesTriangleSubsets) {
        configuration.culling = everyStage;
        checkFrame(prepared, pipeline::render(prepared, configuration, 1, stats).frame, width, height);
      }
    }
}

}  // namespace
}  // namespace hsr::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hsr;
  std::optional<Scene> scene = fuzz::sceneOf(data, size);
  if (!scene || fuzz::checkLoadedScene(*scene) > fuzz::kMaxTriangles) return 0;
  scene->width = std::min(scene->width, 24);
  scene->height = std::min(scene->height, 16);
  scene->effects.shadow.resolution = std::min(scene->effects.shadow.resolution, 64);
  try {
    const PreparedScene prepared(*scene);
    fuzz::renderEveryWay(prepared, scene->width, scene->height);
  } catch (const InputError&) {
  }
  return 0;
}
