// Procedural primitives and shipped models are closed and wound outward.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numbers>

#include "renderer/scene/adjacency.hpp"
#include "renderer/scene/mesh.hpp"
#include "renderer/scene/obj.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

// Every directed edge appears once and its reverse once: closed, consistently wound.
bool closedAndConsistent(const Mesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) return false;
  }
  return true;
}

TEST(Mesh, ClosedPrimitivesAreWatertightAndWoundOutward) {
  const std::pair<const char*, Mesh> solids[] = {
      {"box", makeBox({1, 2, 3})},
      {"sphere", makeSphere(1, 24, 12)},
      {"cylinder", makeCylinder(1, 2, 16)},
      {"cone", makeCone(1, 2, 16)},
  };
  for (const auto& [name, mesh] : solids) {
    EXPECT_TRUE(closedAndConsistent(mesh)) << name;
    EXPECT_GT(signedVolume(mesh), 0) << name;
  }
  EXPECT_NEAR(signedVolume(makeBox({1, 2, 3})), 6.0, 1e-12);
  EXPECT_NEAR(signedVolume(makeSphere(1, 256, 128)), 4.0 / 3 * std::numbers::pi, 2e-3);
  EXPECT_NEAR(signedVolume(makeCylinder(1, 2, 512)), 2 * std::numbers::pi, 1e-3);
}

TEST(Mesh, GridAndHeightFieldFaceUp) {
  const Mesh grid = makeGrid({2, 2}, 3, 4);
  EXPECT_EQ(grid.triangles.size(), 24u);
  for (const Triangle& t : grid.triangles) {
    const dvec3 n = glm::cross(grid.positions[t[1]] - grid.positions[t[0]], grid.positions[t[2]] - grid.positions[t[0]]);
    EXPECT_GT(n.y, 0);
  }
  HeightFunction gauss{"gauss", 2.0, 1.0};
  const Mesh hill = makeHeightField({4, 4}, 2, 2, gauss);
  EXPECT_DOUBLE_EQ(hill.positions[4].y, 2.0);  // the center vertex: amplitude * exp(0)
}

TEST(Mesh, ShippedModelsAreClosedAndOutward) {
  for (const char* name : {"models/bunny.obj", "models/counter.obj", "models/tree.obj"}) {
    const Mesh mesh = loadObj(test::sourcePath(name));
    EXPECT_GT(signedVolume(mesh), 0) << name;
  }
  EXPECT_TRUE(closedAndConsistent(loadObj(test::sourcePath("models/bunny.obj"))));
  EXPECT_EQ(loadObj(test::sourcePath("models/dragon_100k.obj")).triangles.size(), 99784u);
}

// The rows of triangles around each vertex are built on threads, each triangle claiming
// its slot as the threads race; every row still lists its triangles in ascending order,
// every triangle of the vertex once, whatever the thread count.
TEST(Mesh, TheTrianglesAroundEachVertexAreTheSameRowsOnAnyNumberOfThreads) {
  const Mesh mesh = loadObj(test::sourcePath("models/dragon_100k.obj"));
  const VertexTriangles one = buildVertexTriangles(mesh.positions.size(), mesh.triangles, 1);
  std::vector<std::uint32_t> uses(mesh.positions.size(), 0);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t) ++uses[v];
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
    const std::span<const std::uint32_t> row = one.around(v);
    ASSERT_EQ(row.size(), uses[v]) << "vertex " << v;
    ASSERT_TRUE(std::is_sorted(row.begin(), row.end())) << "vertex " << v;
    for (std::uint32_t t : row) ASSERT_NE(std::find(mesh.triangles[t].begin(), mesh.triangles[t].end(), v), mesh.triangles[t].end());
  }
  for (int threads : {2, 3, 4}) {
    const VertexTriangles many = buildVertexTriangles(mesh.positions.size(), mesh.triangles, threads);
    EXPECT_EQ(many.first, one.first) << threads << " threads";
    EXPECT_EQ(many.triangles, one.triangles) << threads << " threads";
  }
}

}  // namespace
}  // namespace hsr
