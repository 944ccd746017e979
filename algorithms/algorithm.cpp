#include "algorithms/algorithm.hpp"

#include "renderer/lines/line_errors.hpp"
#include "renderer/reference/line_reference.hpp"

namespace hsr {

const char* algorithmKindName(AlgorithmKind kind) {
  switch (kind) {
    case AlgorithmKind::surface: return "surface";
    case AlgorithmKind::line: return "line";
    case AlgorithmKind::reference: return "reference";
  }
  return "?";
}

void setRefusal(AlgorithmEntry& entry, std::string (*refusal)(const PreparedScene&)) {
  entry.refusal = [refusal](const PreparedScene& scene, const KnobValues&) { return refusal(scene); };
}

LineJudgement judgedByLineReference(const PreparedScene& scene, const KnobValues&, const LineSet& lines, int threads, Stats& stats) {
  const std::vector<EdgeVisibility> exact = traceLineReference(scene, lines.edges, threads, stats);
  return LineJudgement{lineError(edgeVisibility(lines), exact), lineErrorMap(lines, exact), drawingOf(lines, exact)};
}

}  // namespace hsr
