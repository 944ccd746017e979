// Cells, portals and potentially visible sets (algorithms/culling/cells/): the portal
// traversal against lines of sight walked cell by cell, both stages against the exact
// reference along walks through the shipped levels, the two PVS builds against each
// other, the cache, and the level's validation.
#include <gtest/gtest.h>

#include <fstream>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>

#include "algorithms/culling/cells/portals.hpp"
#include "algorithms/culling/cells/pvs.hpp"
#include "culling/culling_support.hpp"

namespace hsr {
namespace {

using culling::cells::CellMap;
using culling::portals::Narrowing;

const std::filesystem::path kRooms = test::sourcePath("scenes/hard/portal_rooms.toml");
const std::filesystem::path kIndoor = test::sourcePath("scenes/study/indoor.toml");
const std::filesystem::path kCorridors = test::sourcePath("scenes/study/corridors.toml");
const std::filesystem::path kRow = test::sourcePath("scenes/hard/portal_row.toml");
const std::filesystem::path kCastle = test::sourcePath("scenes/study/castle.toml");

// The brute force the traversal is checked against: a line of sight through every point
// of a fine grid over the image, walked from the eye's cell to the next through the
// portal its exit point lies in, until it leaves a cell through a wall. The cells any
// line enters.
std::vector<std::uint8_t> cellsLinesReach(const PreparedScene& scene, const CellMap& map, int raysPerPixelSide) {
  const CameraTransform camera = scene.camera();
  const Scene& level = scene.scene();
  std::vector<std::uint8_t> reached(map.size(), 0);
  const std::uint32_t start = map.cellsAt(camera.camera().eye, "test").front();
  const int width = camera.width() * raysPerPixelSide, height = camera.height() * raysPerPixelSide;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Ray ray = camera.rayThroughPixel((x + 0.5) / raysPerPixelSide, (y + 0.5) / raysPerPixelSide);
      std::uint32_t cell = start;
      reached[cell] = 1;
      // A line passes each convex cell once: at most as many steps as cells.
      for (std::size_t step = 0; step < map.size(); ++step) {
        // Where the line leaves the cell's box: the nearest of the three far sides.
        const Cell& box = level.cells[cell];
        double leave = std::numeric_limits<double>::infinity();
        int axis = 0;
        for (int k = 0; k < 3; ++k) {
          if (ray.direction[k] == 0) continue;
          const double t = ((ray.direction[k] > 0 ? box.to[k] : box.from[k]) - ray.origin[k]) / ray.direction[k];
          if (t < leave) leave = t, axis = k;
        }
        const dvec3 exit = ray.origin + leave * ray.direction;
        // Through a portal on that side, or into a wall.
        std::optional<std::uint32_t> next;
        for (const CellMap::Door& door : map.doors(cell)) {
          const Portal& portal = level.portals[door.portal];
          if (portal.axis != axis || map.planeInto(portal, cell).normal[axis] * ray.direction[axis] <= 0) continue;
          const int u = (axis + 1) % 3, v = (axis + 2) % 3;
          bool inside = true;
          for (std::size_t i = 0; i < portal.polygon.size() && inside; ++i) {
            const dvec3 &p = portal.polygon[i], &q = portal.polygon[(i + 1) % portal.polygon.size()];
            const dvec3& r = portal.polygon[(i + 2) % portal.polygon.size()];
            const double side = (q[u] - p[u]) * (exit[v] - p[v]) - (q[v] - p[v]) * (exit[u] - p[u]);
            const double turn = (q[u] - p[u]) * (r[v] - p[v]) - (q[v] - p[v]) * (r[u] - p[u]);
            inside = side * turn >= 0;
          }
          if (inside) next = door.to;
        }
        if (!next) break;
        cell = *next;
        reached[cell] = 1;
      }
    }
  return reached;
}

// Eyes all over the middle room of portal_rooms, each turned to eight headings.
std::vector<Camera> roomEyes(const Camera& base) {
  std::vector<Camera> eyes;
  for (const dvec2 at : {dvec2(1.5, 2.2), dvec2(-2.4, -2.5), dvec2(2.6, -0.4), dvec2(0, 0), dvec2(-2.9, 2.9)})
    for (int heading = 0; heading < 8; ++heading) {
      Camera camera = base;
      camera.eye = dvec3(at.x, 1.6, at.y);
      const double angle = heading * 0.785398163397448 + 0.3;
      camera.target = camera.eye + dvec3(std::cos(angle), -0.1, std::sin(angle));
      eyes.push_back(camera);
    }
  return eyes;
}

TEST(Portals, TraversalReachesExactlyTheCellsLinesOfSightReach) {
  test::LoadedScene loaded(kRooms);
  const CellMap map(loaded.prepared, "test");
  int narrower = 0;  // views where polygon narrowing keeps fewer objects than rect
  for (const Camera& camera : roomEyes(loaded.scene.camera)) {
    loaded.scene.camera = camera;
    Stats stats;
    const auto polygon = culling::portals::cellsReached(loaded.prepared, map, loaded.prepared.camera(), {0, Narrowing::polygon}, stats);
    const auto rect = culling::portals::cellsReached(loaded.prepared, map, loaded.prepared.camera(), {0, Narrowing::rect}, stats);
    const auto lines = cellsLinesReach(loaded.prepared, map, 3);
    // Never fewer than the lines reach (that would cull what is seen); by polygon, no
    // more either: every cell it reaches, some line reaches.
    EXPECT_EQ(polygon, lines) << "eye " << camera.eye.x << " " << camera.eye.z << " toward " << camera.target.x << " " << camera.target.z;
    for (std::size_t cell = 0; cell < map.size(); ++cell) EXPECT_GE(rect[cell], polygon[cell]) << cell;
    narrower += cull(loaded.prepared, "portals:narrowing=polygon").triangles.size() < cull(loaded.prepared, "portals").triangles.size();
  }
  // The doors are off centre: somewhere the rectangle of a door seen at an angle takes
  // in an object the door itself does not show.
  EXPECT_GT(narrower, 0);
}

// Positions of a walk through a level, and the exact reference's verdict at each.
struct WalkCase {
  std::filesystem::path level;
  std::vector<std::pair<dvec3, dvec3>> views;  // eye, target
};

std::vector<WalkCase> walks() {
  return {{kIndoor,
           {{{-28, 1.6, 0}, {0, 1.6, 0}},      // down the hall
            {{-5, 1.6, 0.5}, {-4, 1.6, 4}},    // toward a door at an angle
            {{5, 1.6, 2}, {5, 1.6, 8}},        // in a doorway
            {{5, 1.6, 6}, {-30, 1.6, 6}},      // along the row of rooms, five doors in a row
            {{-24, 1.6, -7}, {-10, 1.6, 0}},   // from a room's corner toward the hall
            {{20, 1.6, 6}, {20, 1.6, 6.5}}}},  // standing on a portal between two rooms
          {kCorridors,
           {{{-30, 1.6, 2}, {0, 1.6, 2}},
            {{-40, 1.6, 4}, {-40, 1.6, -30}},
            {{12, 1.6, -20}, {20, 1.6, -36}},
            {{42, 1.6, 20}, {-40, 1.6, 22}}}},
          {kCastle,
           {{{0, 14, 62}, {0, 2, 10}},         // the third-person camera, in the sky
            {{0, 1.7, 25}, {0, 1.7, 0}},       // in the middle courtyard, toward the keep
            {{-20, 1.7, 28.5}, {20, 1.7, 28.5}},  // through the gaps at the inner walls' ends
            {{0, 1.7, 60}, {0, 5, 0}},         // outside, toward the castle
            {{20, 12, 0}, {-20, 0, 0}}}}};     // above the walls, looking down into the courtyards
}

TEST(Portals, NeverCullAnObjectTheReferenceSees) {
  for (const WalkCase& walk : walks()) {
    Judged judged(walk.level, 320);
    for (const auto& [eye, target] : walk.views) {
      judged.loaded.scene.camera.eye = eye, judged.loaded.scene.camera.target = target;
      judged.retrace();
      Stats rectStats, polygonStats;
      const VisibleSet rect = cull(judged.loaded.prepared, "portals", rectStats);
      const VisibleSet polygon = cull(judged.loaded.prepared, "portals:narrowing=polygon", polygonStats);
      const VisibleSet pvs = cull(judged.loaded.prepared, "pvs");
      const std::string where = walk.level.filename().string() + " eye " + std::to_string(eye.x) + " " + std::to_string(eye.z);
      EXPECT_EQ(judged.objectsFalselyCulled(rect), 0) << where;
      EXPECT_EQ(judged.objectsFalselyCulled(polygon), 0) << where;
      EXPECT_EQ(judged.objectsFalselyCulled(pvs), 0) << where;
      // Polygon narrowing keeps a subset of what rect keeps.
      EXPECT_TRUE(std::includes(rect.triangles.begin(), rect.triangles.end(), polygon.triangles.begin(), polygon.triangles.end())) << where;
      // And both cull something: a level seen from inside hides most of itself.
      EXPECT_LT(rectStats.counter("portals: objects kept"), std::int64_t(judged.loaded.prepared.instances().size()) / 2) << where;
    }
  }
}

TEST(Portals, AndPvsKeepTheSameObjectsFarFromTheOrigin) {
  // The indoor level moved a million units on every axis: its objects (as the scene's
  // copies), its cells and portals, and the eye along with it.
  const dvec3 offset(1e6, 1e6, -1e6);
  const WalkCase indoor = walks().front();
  for (const auto& [eye, target] : indoor.views) {
    test::LoadedScene near(kIndoor);
    near.scene.camera.eye = eye, near.scene.camera.target = target;
    Scene far = near.scene;
    for (Cell& cell : far.cells) cell.from += offset, cell.to += offset;
    for (Portal& portal : far.portals) {
      portal.at += offset[portal.axis];
      for (dvec3& corner : portal.polygon) corner += offset;
    }
    far.camera.eye += offset, far.camera.target += offset;
    const PreparedScene moved(far, {glm::translate(dmat4(1), offset)});
    for (const std::string pipeline : {"portals", "portals:narrowing=polygon", "pvs"})
      EXPECT_EQ(culling::instancesIn(moved, cull(moved, pipeline)), culling::instancesIn(near.prepared, cull(near.prepared, pipeline)))
          << pipeline << " at eye " << eye.x << " " << eye.z;
  }
}

TEST(Portals, GivingUpKeepsEveryCellConnectedToTheEyes) {
  test::LoadedScene loaded(kRooms);
  Stats full, givenUp;
  const VisibleSet searched = cull(loaded.prepared, "portals", full);
  const VisibleSet everything = cull(loaded.prepared, "portals:max-passes=1", givenUp);
  EXPECT_EQ(full.counter("portals: searches given up"), 0);
  EXPECT_EQ(givenUp.counter("portals: searches given up"), 1);
  // The nine rooms are all connected: every object, where the search kept a few.
  EXPECT_EQ(everything.triangles, VisibleSet::everything(loaded.prepared).triangles);
  EXPECT_LT(searched.triangles.size(), everything.triangles.size());
}

TEST(Portals, SameObjectsAndCountersOnOneAndTwoThreads) {
  test::LoadedScene loaded(kIndoor);
  Stats one, two;
  const VisibleSet a = cull(loaded.prepared, "frustum,portals:narrowing=polygon", one, 1);
  const VisibleSet b = cull(loaded.prepared, "frustum,portals:narrowing=polygon", two, 2);
  EXPECT_EQ(a.triangles, b.triangles);
  for (const std::string& counter : one.counterNames()) EXPECT_EQ(one.counter(counter), two.counter(counter)) << counter;
}

culling::pvs::Knobs sampledKnobs(int samples, int resolution) {
  culling::pvs::Knobs knobs;
  knobs.build = culling::pvs::Build::sampled, knobs.samples = samples, knobs.resolution = resolution;
  return knobs;
}

TEST(Pvs, ConservativeHoldsEveryObjectSeenFromDenseEyesInEachCell) {
  for (const auto& level : {kRooms, kIndoor}) {
    test::LoadedScene loaded(level);
    const CellMap map(loaded.prepared, "test");
    Stats stats;
    const auto conservative = culling::pvs::build(loaded.prepared, map, {}, 2, stats);
    const auto sampled = culling::pvs::build(loaded.prepared, map, sampledKnobs(64, 48), 2, stats);
    EXPECT_EQ(conservative.cellsGivenUp, 0);
    for (std::size_t cell = 0; cell < map.size(); ++cell) {
      const auto& wide = conservative.objects[cell];
      const auto& seen = sampled.objects[cell];
      EXPECT_TRUE(std::includes(wide.begin(), wide.end(), seen.begin(), seen.end())) << level << " cell " << loaded.scene.cells[cell].name;
      // And it is a real restriction: no cell's set is the whole level.
      EXPECT_LT(wide.size(), loaded.prepared.instances().size()) << loaded.scene.cells[cell].name;
    }
  }
}

TEST(Pvs, SampledWithEnoughSamplesEqualsConservativeInARowOfRooms) {
  test::LoadedScene loaded(kRow);
  const CellMap map(loaded.prepared, "test");
  Stats stats;
  const auto conservative = culling::pvs::build(loaded.prepared, map, {}, 2, stats);
  const auto few = culling::pvs::build(loaded.prepared, map, sampledKnobs(1, 8), 2, stats);
  const auto many = culling::pvs::build(loaded.prepared, map, sampledKnobs(256, 64), 2, stats);
  EXPECT_EQ(many.objects, conservative.objects);
  // With one eye point a cell and coarse rays, something seen from elsewhere is missing.
  std::size_t fewTotal = 0, manyTotal = 0;
  for (std::size_t cell = 0; cell < map.size(); ++cell) fewTotal += few.objects[cell].size(), manyTotal += many.objects[cell].size();
  EXPECT_LT(fewTotal, manyTotal);
}

TEST(Pvs, AConservativeSearchThatGivesUpTakesEveryConnectedObject) {
  test::LoadedScene loaded(kRooms);
  const CellMap map(loaded.prepared, "test");
  culling::pvs::Knobs bounded;
  bounded.maxChains = 1;  // every one of the nine rooms has more than one chain out
  Stats stats;
  const auto full = culling::pvs::build(loaded.prepared, map, {}, 1, stats);
  const auto givenUp = culling::pvs::build(loaded.prepared, map, bounded, 1, stats);
  EXPECT_EQ(full.cellsGivenUp, 0);
  EXPECT_EQ(givenUp.cellsGivenUp, 9);
  std::vector<std::uint32_t> all(loaded.prepared.instances().size());
  std::iota(all.begin(), all.end(), 0u);
  for (std::size_t cell = 0; cell < map.size(); ++cell) {
    EXPECT_EQ(givenUp.objects[cell], all) << loaded.scene.cells[cell].name;
    EXPECT_LT(full.objects[cell].size(), all.size()) << loaded.scene.cells[cell].name;
  }
}

TEST(Pvs, SameSetsOnOneAndTwoThreads) {
  test::LoadedScene loaded(kIndoor);
  const CellMap map(loaded.prepared, "test");
  Stats stats;
  EXPECT_EQ(culling::pvs::build(loaded.prepared, map, sampledKnobs(4, 16), 1, stats).objects,
            culling::pvs::build(loaded.prepared, map, sampledKnobs(4, 16), 2, stats).objects);
  EXPECT_EQ(culling::pvs::build(loaded.prepared, map, {}, 1, stats).objects, culling::pvs::build(loaded.prepared, map, {}, 2, stats).objects);
}

// A copy of portal_rooms in the test output folder, so that it can be changed there.
std::filesystem::path roomsCopy(const std::string& name) {
  const auto copy = test::outputPath(name);
  std::filesystem::copy_file(kRooms, copy, std::filesystem::copy_options::overwrite_existing);
  return copy;
}

// What reading a cache says, or "(read)".
std::string cacheError(const std::filesystem::path& cache, const PreparedScene& scene, const culling::pvs::Knobs& knobs) {
  try {
    culling::pvs::readCache(cache, scene, knobs);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(read)";
}

TEST(Pvs, TheCacheIsReadWhenGivenAndRefusedWhenItDoesNotFit) {
  const auto file = roomsCopy("pvs_cache_rooms.toml");
  test::LoadedScene loaded(file);
  const culling::pvs::Knobs knobs = sampledKnobs(2, 8);
  const auto cache = test::outputPath("pvs_cache_rooms.pvs");
  Stats built;
  const VisibleSet first = cull(loaded.prepared, "pvs:build=sampled:samples=2:resolution=8", built);
  EXPECT_EQ(built.counter("pvs: built now"), 1);
  const CellMap map(loaded.prepared, "test");
  culling::pvs::writeCache(cache, loaded.prepared, knobs, culling::pvs::build(loaded.prepared, map, knobs, 1, built));
  Stats read;
  EXPECT_EQ(cull(loaded.prepared, "pvs:build=sampled:samples=2:resolution=8:cache=" + cache.string(), read).triangles, first.triangles);
  EXPECT_EQ(read.counter("pvs: read from the cache"), 1);
  EXPECT_EQ(read.counter("pvs: built now"), 0);
  // The file names each cell and its objects for a reader; --stats names the eye's cells and the set.
  const std::string text = readInputFile(cache, "visible-set cache");
  EXPECT_NE(text.find("  # " + loaded.scene.cells[0].name + ": "), std::string::npos) << text;
  EXPECT_FALSE(read.noteOf("pvs: the eye's cells").empty());
  EXPECT_NE(read.noteOf("pvs: the set").find(loaded.scene.objects[0].name), std::string::npos) << read.noteOf("pvs: the set");
  // Other settings than the file was built with: refused, naming both.
  EXPECT_NE(cacheError(cache, loaded.prepared, sampledKnobs(4, 8)).find(":3: 'build sampled samples 2 resolution 8' was built with other settings"),
            std::string::npos) << cacheError(cache, loaded.prepared, sampledKnobs(4, 8));
  // The same file, another level: a pillar moved.
  std::ofstream(file, std::ios::app) << "\n[[objects]]\nshape = \"box\"\ntranslate = [1, 0.5, 1]\n";
  test::LoadedScene changed(file);
  EXPECT_NE(cacheError(cache, changed.prepared, knobs).find(":2: built for another level"), std::string::npos)
      << cacheError(cache, changed.prepared, knobs);
  // A missing file, and a file that is not a cache, are refused, naming the file and its line.
  EXPECT_NE(cacheError(test::outputPath("no-such.pvs"), changed.prepared, knobs).find("no-such.pvs: cannot open the visible-set cache"),
            std::string::npos);
  std::ofstream(cache) << "hsr pvs 1\nfingerprint " << culling::pvs::fingerprint(changed.prepared) << "\nbuild sampled samples 2 resolution 8\nseconds x\n";
  EXPECT_EQ(pipelineError("pvs"), "(no error)");
  EXPECT_NE(cacheError(cache, changed.prepared, knobs).find("pvs_cache_rooms.pvs:4: 'seconds x' is not a visible-set cache line; expected seconds S"),
            std::string::npos) << cacheError(cache, changed.prepared, knobs);
}

TEST(Pvs, AWalkBuildsTheSetsOnce) {
  test::LoadedScene loaded(kRooms);
  const culling::Pipeline pipeline = culling::parsePipeline("pvs:build=sampled:samples=2:resolution=8");
  std::vector<std::unique_ptr<culling::StageMemory>> memory;
  Frame last(loaded.prepared.width(), loaded.prepared.height());
  Stats stats;
  for (const Camera& camera : roomEyes(loaded.scene.camera)) {
    loaded.scene.camera = camera;
    const culling::PreviousFrame previous{camera, &last, &memory};
    culling::runPipeline(loaded.prepared, pipeline, 1, stats, &previous);
  }
  EXPECT_EQ(stats.counter("pvs: built now"), 1);
}

// The level's own mistakes, each refused on load with file:line:column and what was expected.
std::string levelError(const std::string& cellsAndPortals) {
  const auto file = test::outputPath("cells_error.toml");
  std::ofstream(file) << "[camera]\neye = [1, 1, 1]\ntarget = [0, 1, 0]\n[[objects]]\nshape = \"box\"\nsize = [4, 2, 2]\n"
                      << "[[cells]]\nname = \"a\"\nfrom = [-2, 0, -1]\nto = [0, 2, 1]\n[[cells]]\nname = \"b\"\nfrom = [0, 0, -1]\nto = [2, 2, 1]\n"
                      << cellsAndPortals;
  try {
    loadScene(file);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(loaded without error)";
}

TEST(Cells, ALevelsMistakesAreRefusedWithWhereAndWhat) {
  const std::string portal = "[[portals]]\ncells = [\"a\", \"b\"]\n";
  EXPECT_EQ(levelError(portal + "from = [0, 0, -0.5]\nto = [0, 1, 0.5]\n"), "(loaded without error)");
  EXPECT_NE(levelError(portal + "from = [0.5, 0, -0.5]\nto = [0.5, 1, 0.5]\n")
                .find("cells_error.toml:17:8: portals[0].from: corner 0 (0.5, 0, -0.5) is not on the boundary of cells \"a\" and \"b\"; "
                      "expected x = 0 and the other coordinates within the face"),
            std::string::npos)
      << levelError(portal + "from = [0.5, 0, -0.5]\nto = [0.5, 1, 0.5]\n");
  EXPECT_NE(levelError(portal + "from = [0, 0, -0.5]\nto = [0, 3, 0.5]\n").find("is not on the boundary of cells"), std::string::npos);
  EXPECT_NE(levelError("[[portals]]\ncells = [\"a\", \"a\"]\nfrom = [0, 0, 0]\nto = [0, 1, 1]\n")
                .find("portals[0].cells: joins cell \"a\" to itself; expected two different cells"),
            std::string::npos);
  EXPECT_NE(levelError("[[portals]]\ncells = [\"a\", \"c\"]\nfrom = [0, 0, 0]\nto = [0, 1, 1]\n")
                .find("portals[0].cells[1]: no cell is named \"c\""),
            std::string::npos);
  EXPECT_NE(levelError("[[cells]]\nname = \"c\"\nfrom = [1, 0, 0]\nto = [3, 1, 1]\n").find("cell \"c\" overlaps cell \"b\""), std::string::npos);
  EXPECT_NE(levelError("[[cells]]\nname = \"a\"\nfrom = [5, 0, 0]\nto = [6, 1, 1]\n").find("\"a\" names two cells"), std::string::npos);
  EXPECT_NE(levelError("[[cells]]\nname = \"c\"\nfrom = [5, 0, 0]\nto = [5, 1, 1]\n").find("must exceed from on every axis"), std::string::npos);
  EXPECT_NE(levelError("[[cells]]\nname = \"c\"\nfrom = [5, 0, 0]\nto = [6, 1, 1]\n[[portals]]\ncells = [\"a\", \"c\"]\nfrom = [0, 0, 0]\nto = [0, 1, 1]\n")
                .find("cells \"a\" and \"c\" share no face"),
            std::string::npos);
  EXPECT_NE(levelError(portal + "polygon = [[0, 0, 0], [0, 1, 0], [0, 0.2, 0.2], [0, 0, 1]]\n").find("the polygon is not convex"), std::string::npos);
  EXPECT_NE(levelError(portal + "polygon = [[0, 0, 0], [0, 1, 0], [0, 0.5, 0]]\n").find("the portal has no area"), std::string::npos);
  EXPECT_NE(levelError(portal + "from = [0, 0, 0]\nto = [0, 1, 0]\n").find("from and to equal on exactly one axis"), std::string::npos);
}

}  // namespace
}  // namespace hsr
