// What a render decided on the way (hsr render --explain), read back from its counters.
#include <cstdio>
#include <string>
#include <vector>

#include "pipeline/pipeline.hpp"

namespace hsr::pipeline {
namespace {

std::string count(std::size_t n, const std::string& what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); }

std::string formatted(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

}  // namespace

std::vector<std::string> decisionsTaken(const Stats& stats) {
  std::vector<std::string> decisions;
  const auto counted = [&](const char* name) { return stats.counter(name); };
  const auto say = [&](bool ran, const std::string& yes, const std::string& no) { decisions.push_back(ran ? yes : no); };
  const auto n = [](std::int64_t value) { return std::to_string(value); };
  if (counted("triangles in") > 0)
    say(counted("triangles clipped") > 0,
        "clipping: " + n(counted("triangles clipped")) + " triangles cross the near plane or the guard band, and only they were clipped",
        "clipping: no triangle crosses the near plane or the guard band (every vertex's outcode checked first): nothing clipped");
  if (counted("newell pairs tested") > 0)
    say(counted("newell splits") > 0, "Newell: " + n(counted("newell splits")) + " splits, each where a cycle was found",
        "Newell: no cycle found among " + n(counted("newell pairs tested")) + " overlapping pairs: nothing split");
  if (counted("bsp nodes") > 0) decisions.push_back("BSP: " + n(counted("bsp splits")) + " splits while building " + n(counted("bsp nodes")) + " nodes");
  if (counted("reference rays") > 0)
    say(counted("reference exact fall-backs") > 0,
        "exact fall-back: " + n(counted("reference exact fall-backs")) + " of " + n(counted("reference rays")) +
            " rays where the double-precision filter could not decide",
        "exact fall-back: none; the double-precision filter decided every ray");
  if (counted("reference rays") > 0)
    say(counted("reference tiles proved") > 0,
        "tiles proved: " + n(counted("reference rays proved")) + " of " + n(counted("reference rays")) + " rays answered by " +
            n(counted("reference tiles proved")) + " proofs that a tile shows one triangle whole, or nothing; the rest searched ray by ray",
        "tiles proved: none; every ray searched (a tile is proved only with packets, and where it shows one triangle whole, or nothing)");
  if (counted("predicate evaluations") > 0)
    decisions.push_back("exact predicates: " + n(counted("predicate exact fall-backs")) + " of " + n(counted("predicate evaluations")) +
                        " evaluations fell back to exact arithmetic");
  if (counted("occlusion: estimated depth complexity x100") > 0 || counted("occlusion: skipped, below min-depth-complexity") > 0) {
    const std::string estimate = formatted(double(counted("occlusion: estimated depth complexity x100")) / 100);
    say(counted("occlusion: skipped, below min-depth-complexity") == 0,
        "occlusion culling: the objects' boxes cover the view " + estimate + " times over, at least min-depth-complexity: it runs",
        "occlusion culling: skipped; the objects' boxes cover the view only " + estimate + " times over, below min-depth-complexity");
  }
  if (counted("occlusion: occludees tested") > 0)
    decisions.push_back("occlusion culling: " + n(counted("occlusion: occluders rasterized")) + " occluders drawn, " +
                        n(counted("occlusion: occludees culled")) + " of " + n(counted("occlusion: occludees tested")) + " objects culled");
  if (counted("depth buffer bytes") > 0)
    say(counted(kDistancesDecodedCounter) > 0,
        "distances: the depth buffer decoded to view distances at " + n(counted(kDistancesDecodedCounter)) + " pixels",
        "distances: none decoded; nothing read them, and the depth buffer stayed as its format stored it");
  say(counted("normals computed") > 0,
      "normals: " + n(counted("normals computed")) + " corner normals computed, for the " + n(counted("shading set-ups")) +
          " triangles shading set up",
      "normals: none computed");
  if (counted("shadow maps rendered") > 0)
    decisions.push_back("shadows: " + count(std::size_t(counted("shadow maps rendered")), "map view") + ", " +
                        n(counted("shadow lookups")) + " lookups, " + n(counted("shadowed lookups")) + " in shadow");
  if (counted("specular terms") > 0) decisions.push_back("specular: " + n(counted("specular terms")) + " highlight terms");
  if (counted("blended writes") > 0) decisions.push_back("transparency: " + n(counted("blended writes")) + " blended writes");
  if (counted("fog blends") > 0) decisions.push_back("fog: " + n(counted("fog blends")) + " pixels blended");
  if (counted("outline edges") > 0)
    decisions.push_back("outline: " + n(counted("outline edges")) + " feature edges, " + n(counted("outline pixels")) + " pixels drawn");
  return decisions;
}

}  // namespace hsr::pipeline
