// Edge adjacency of a triangle mesh: every undirected edge with the triangles on its
// sides, and every vertex with the triangles around it. The line algorithms walk it;
// PreparedScene builds it on first use.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "renderer/util/math.hpp"

namespace hsr {

struct MeshEdge {
  static constexpr std::uint32_t kNoFace = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t a, b;          // vertex indices, a < b
  std::uint32_t faces[2];      // the first two triangles using it; faces[1] = kNoFace on a boundary
  std::uint32_t faceCount;     // how many triangles use it: 1 boundary, 2 manifold, more non-manifold
  bool consistent;             // the two faces run it in opposite directions (a coherent orientation)
};

// The triangles around each vertex, as compressed rows.
struct VertexTriangles {
  std::vector<std::uint32_t> first, triangles;  // vertex v: triangles[first[v] .. first[v + 1])
  std::span<const std::uint32_t> around(std::uint32_t vertex) const {
    return {triangles.data() + first[vertex], triangles.data() + first[vertex + 1]};
  }
};
// The same rows for any thread count.
VertexTriangles buildVertexTriangles(std::size_t vertexCount, std::span<const Triangle> triangles, int threads = 1);

struct EdgeAdjacency {
  std::vector<MeshEdge> edges;  // in order of first use (triangle by triangle, corner by corner)
  // edgesOf[3 t + k]: the edge of triangle t from corner k to corner k + 1.
  std::vector<std::uint32_t> edgesOf;
  VertexTriangles aroundVertex;
};
EdgeAdjacency buildEdgeAdjacency(std::size_t vertexCount, std::span<const Triangle> triangles);

}  // namespace hsr
