#include "renderer/scene/adjacency.hpp"

#include <algorithm>
#include <unordered_map>

#include "renderer/util/parallel.hpp"

namespace hsr {

EdgeAdjacency buildEdgeAdjacency(std::size_t vertexCount, std::span<const Triangle> triangles) {
  EdgeAdjacency adjacency;
  std::unordered_map<std::uint64_t, std::uint32_t> edgeOfKey;
  edgeOfKey.reserve(triangles.size() * 2);
  adjacency.edgesOf.resize(triangles.size() * 3);
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t from = triangles[t][k], to = triangles[t][(k + 1) % 3];
      const std::uint32_t a = std::min(from, to), b = std::max(from, to);
      const auto [slot, added] = edgeOfKey.try_emplace(std::uint64_t{a} << 32 | b, std::uint32_t(adjacency.edges.size()));
      if (added) {
        adjacency.edges.push_back({a, b, {t, MeshEdge::kNoFace}, 1, true});
      } else {
        MeshEdge& edge = adjacency.edges[slot->second];
        if (edge.faceCount == 1) {
          edge.faces[1] = t;
          // Coherently oriented neighbours run their shared edge in opposite directions.
          const Triangle& first = triangles[edge.faces[0]];
          int corner = 0;
          while (first[corner] != from) ++corner;
          edge.consistent = first[(corner + 1) % 3] != to;
        }
        ++edge.faceCount;
      }
      adjacency.edgesOf[3 * t + k] = slot->second;
    }
  }
  adjacency.aroundVertex = buildVertexTriangles(vertexCount, triangles);
  return adjacency;
}

// A counting sort of the triangles by vertex. On threads, each triangle claims its slot
// in a vertex's row with an atomic increment, so a row's order depends on the threads'
// timing; each row is then sorted, which gives the one-thread order (ascending triangle)
// back, and with it the same sums of neighbouring normals in the same order.
VertexTriangles buildVertexTriangles(std::size_t vertexCount, std::span<const Triangle> triangles, int threads) {
  constexpr std::size_t kChunk = 16384;
  auto atomicIncrement = [](std::uint32_t& value) { return __atomic_fetch_add(&value, 1u, __ATOMIC_RELAXED); };
  VertexTriangles rows;
  rows.first.assign(vertexCount + 1, 0);
  parallelForEach(triangles.size(), kChunk, threads, [&](std::size_t t) {
    for (std::uint32_t v : triangles[t]) atomicIncrement(rows.first[v + 1]);
  });
  for (std::size_t v = 0; v < vertexCount; ++v) rows.first[v + 1] += rows.first[v];
  rows.triangles.resize(triangles.size() * 3);
  std::vector<std::uint32_t> filled(rows.first.begin(), rows.first.end() - 1);
  parallelForEach(triangles.size(), kChunk, threads, [&](std::size_t t) {
    for (std::uint32_t v : triangles[t]) rows.triangles[atomicIncrement(filled[v])] = std::uint32_t(t);
  });
  parallelForEach(vertexCount, kChunk, threads, [&](std::size_t v) {
    std::sort(rows.triangles.begin() + rows.first[v], rows.triangles.begin() + rows.first[v + 1]);
  });
  return rows;
}

}  // namespace hsr
