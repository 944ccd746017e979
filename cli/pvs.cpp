// hsr pvs build: a level's potentially visible sets, built and cached beside the scene
// (the stage pvs reads the cache; algorithms/culling/cells/pvs.hpp).
#include <algorithm>
#include <cstdio>

#include "algorithms/culling/cells/pvs.hpp"
#include "cli/commands.hpp"
#include "renderer/scene/scene.hpp"
#include "studies/common.hpp"

namespace hsr::cli {

int pvsBuild(const PvsOptions& options) {
  // The settings as the stage spells them, so that they are checked as --cull pvs checks them.
  std::string spelled = "pvs:build=" + options.build;
  if (!options.samples.empty()) spelled += ":samples=" + options.samples;
  if (!options.resolution.empty()) spelled += ":resolution=" + options.resolution;
  const culling::Pipeline pipeline = culling::parsePipeline(spelled, "hsr pvs build");
  const culling::pvs::Knobs& knobs = pipeline.front().knobs.as<culling::pvs::Knobs>();
  const Scene scene = loadScene(studies::sceneFile(options.scene));
  const PreparedScene prepared(scene);
  const culling::cells::CellMap map(prepared, "hsr pvs build");
  Stats stats;
  const culling::pvs::VisibleSets sets = culling::pvs::build(prepared, map, knobs, options.threads, stats);
  const std::filesystem::path path = options.out;
  culling::pvs::writeCache(path, prepared, knobs, sets);
  std::size_t total = 0, largest = 0;
  for (const auto& set : sets.objects) total += set.size(), largest = std::max(largest, set.size());
  std::printf("%s: %zu cells, %s visible sets built in %.3f s (%lld %s): %.1f objects a cell on average, at most %zu, of %zu\n",
              path.string().c_str(), sets.objects.size(), options.build.c_str(), sets.seconds, static_cast<long long>(sets.work),
              knobs.build == culling::pvs::Build::sampled ? "rays" : "portal chains", double(total) / double(sets.objects.size()), largest,
              prepared.instances().size());
  std::printf("render with it: hsr render %s --cull pvs:cache=%s%s\n", options.scene.c_str(), path.string().c_str(),
              knobs.build == culling::pvs::Build::sampled ? (":build=sampled:samples=" + std::to_string(knobs.samples) +
                                                             ":resolution=" + std::to_string(knobs.resolution)).c_str()
                                                          : "");
  if (sets.cellsGivenUp > 0)
    std::printf("%lld cells had more portal chains than the search follows; each holds every object connected to it\n",
                static_cast<long long>(sets.cellsGivenUp));
  return 0;
}

}  // namespace hsr::cli
