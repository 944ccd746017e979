// Potentially visible sets: the two builds, the cache beside the scene, and the lookup
// (pvs.hpp has the method and its sources).
#include "algorithms/culling/cells/pvs.hpp"

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstring>
#include <fstream>
#include <sstream>

#include "renderer/image/frame.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr::culling::pvs {
namespace {

// ---------------------------------------------------------------------------------
// sampled: eye points in the cell, a cube map from each, traced exactly

// The Halton sequence's k-th value in base b (k >= 1): points that fill a box evenly
// however many are taken, the same on every machine.
double halton(std::uint32_t k, std::uint32_t base) {
  double value = 0, digit = 1.0 / base;
  for (; k > 0; k /= base, digit /= base) value += digit * (k % base);
  return value;
}

std::vector<std::uint8_t> sampledSet(const PreparedScene& scene, const SurfaceReference& reference, const Cell& cell,
                                     const Knobs& knobs, std::int64_t& rays) {
  std::vector<std::uint8_t> seen(scene.instances().size(), 0);
  // The six faces of a cube map: where each looks, and its up.
  const dvec3 faces[6][2] = {{{1, 0, 0}, {0, 1, 0}},  {{-1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 1, 0}},
                             {{0, 0, -1}, {0, 1, 0}}, {{0, 1, 0}, {0, 0, 1}},  {{0, -1, 0}, {0, 0, 1}}};
  std::vector<ReferenceHit> hits(std::size_t(knobs.resolution));
  SurfaceReference::Counters counters;
  for (int s = 1; s <= knobs.samples; ++s) {
    const dvec3 along(halton(std::uint32_t(s), 2), halton(std::uint32_t(s), 3), halton(std::uint32_t(s), 5));
    const dvec3 eye = cell.from + along * (cell.to - cell.from);
    for (const auto& [direction, up] : faces) {
      Camera camera = scene.scene().camera;
      camera.projection = Projection::perspective;
      camera.eye = eye, camera.target = eye + direction, camera.up = up, camera.fovYDegrees = 90;
      const CameraTransform transform(camera, knobs.resolution, knobs.resolution);
      for (int y = 0; y < knobs.resolution; ++y) {
        reference.traceRun(transform, y, 0, knobs.resolution, hits.data(), counters);
        for (const ReferenceHit& hit : hits)
          if (hit.id != 0) seen[&scene.instanceOf(hit.id - 1) - scene.instances().data()] = 1;
      }
      rays += std::int64_t(knobs.resolution) * knobs.resolution;
    }
  }
  return seen;
}

// ---------------------------------------------------------------------------------
// conservative: chains of portals a line can pass

// The planes that separate two convex polygons, facing the second: each through an
// edge of one and a corner of the other, with the first wholly on its back and the
// second wholly on its front (closed; not both in it). A line through a point of
// `first` and then a point of `second` goes from back to front, and stays in front
// beyond. `slack`: how far from the plane a corner still counts as on it.
std::vector<Plane> separatingPlanes(const cells::Polygon& first, const cells::Polygon& second, double slack) {
  // -1: wholly behind (some corner strictly), +1: wholly in front, 0: in the plane, 2: across it.
  const auto sideOf = [&](const Plane& plane, const cells::Polygon& polygon) {
    bool behind = false, front = false;
    for (const dvec3& p : polygon) {
      const double d = plane.distance(p);
      behind = behind || d < -slack, front = front || d > slack;
    }
    return behind && front ? 2 : behind ? -1 : front ? 1 : 0;
  };
  std::vector<Plane> planes;
  const auto tryPlane = [&](const dvec3& a, const dvec3& b, const dvec3& corner) {
    const dvec3 normal = glm::cross(b - a, corner - a);
    const double length = glm::length(normal);
    if (!(length > 0)) return;
    Plane plane{normal / length, -glm::dot(normal, a) / length};
    const int firstSide = sideOf(plane, first), secondSide = sideOf(plane, second);
    if (firstSide == 2 || secondSide == 2 || firstSide == secondSide) return;
    if (secondSide < 0 || firstSide > 0) plane = {-plane.normal, -plane.offset};  // face the second
    planes.push_back(plane);
  };
  for (const cells::Polygon* edges : {&first, &second}) {
    const cells::Polygon& corners = edges == &first ? second : first;
    for (std::size_t i = 0; i < edges->size(); ++i)
      for (const dvec3& corner : corners) tryPlane((*edges)[i], (*edges)[(i + 1) % edges->size()], corner);
  }
  return planes;
}

class ConservativeSearch {
 public:
  ConservativeSearch(const PreparedScene& scene, const cells::CellMap& map, std::uint32_t cell, std::int64_t maxChains)
      : scene_(scene), map_(map), home_(cell), maxChains_(maxChains), seen_(scene.instances().size(), 0), onChain_(map.size(), 0),
        origin_(scene.scene().cells[cell].from), onPlane_(map.slack(1e-9)), slack_(map.slack(1e-6)) {}

  std::vector<std::uint8_t> run(std::int64_t& chains, std::int64_t& givenUp) {
    for (const std::uint32_t object : map_.objects(home_)) seen_[object] = 1;
    onChain_[home_] = 1;
    for (const cells::CellMap::Door& door : map_.doors(home_)) {
      const Portal& source = scene_.scene().portals[door.portal];
      const cells::Polygon polygon = local(source.polygon);
      follow(door.to, polygon, polygon, {localPlaneInto(source, home_)});
      if (givenUp_) break;
    }
    if (givenUp_) everythingConnected();
    chains += chains_;
    givenUp += givenUp_;
    return seen_;
  }

 private:
  // In cell `cell`, entered through `pass`, after crossing the planes `crossed` (the
  // first of them the source's): its objects, and the chains on.
  void follow(std::uint32_t cell, const cells::Polygon& source, const cells::Polygon& pass, const std::vector<Plane>& crossed) {
    if (++chains_ > maxChains_) {
      givenUp_ = true;
      return;
    }
    onChain_[cell] = 1;
    std::vector<Plane> bounds = crossed;
    if (crossed.size() > 1) {
      const std::vector<Plane> separators = separatingPlanes(source, pass, onPlane_);
      bounds.insert(bounds.end(), separators.begin(), separators.end());
    }
    for (const std::uint32_t object : map_.objects(cell)) {
      if (seen_[object]) continue;
      const Aabb& box = scene_.instances()[object].box;
      seen_[object] = std::none_of(bounds.begin(), bounds.end(),
                                   [&](const Plane& plane) { return cells::boxBehind(box.lo - origin_, box.hi - origin_, plane, slack_); });
    }
    for (const cells::CellMap::Door& door : map_.doors(cell)) {
      if (onChain_[door.to] || givenUp_) continue;
      const Portal& next = scene_.scene().portals[door.portal];
      // The next portal, where a line through the chain can meet it.
      cells::Polygon target = local(next.polygon);
      for (std::size_t b = 0; b < bounds.size() && !target.empty(); ++b) target = cells::clip(target, bounds[b], slack_);
      if (target.empty()) continue;
      // The source, where a line can leave it toward the next portal: on this side of its plane.
      const Plane into = localPlaneInto(next, cell);
      const cells::Polygon nearSource = cells::clip(source, {-into.normal, -into.offset}, slack_);
      if (nearSource.empty()) continue;
      std::vector<Plane> further = crossed;
      further.push_back(into);
      follow(door.to, nearSource, target, further);
    }
    onChain_[cell] = 0;
  }

  // Coordinates relative to a corner of the home cell, so that a level far from the
  // origin is searched with the precision of one near it.
  cells::Polygon local(const cells::Polygon& polygon) const {
    cells::Polygon moved;
    for (const dvec3& p : polygon) moved.push_back(p - origin_);
    return moved;
  }
  Plane localPlaneInto(const Portal& portal, std::uint32_t from) const {
    const Plane plane = map_.planeInto(portal, from);
    return {plane.normal, plane.distance(origin_)};
  }

  // The give-up answer: every object of every cell the portals connect to this one.
  void everythingConnected() {
    const std::vector<std::uint8_t> connected = map_.connectedTo({home_});
    for (std::uint32_t cell = 0; cell < map_.size(); ++cell)
      if (connected[cell])
        for (const std::uint32_t object : map_.objects(cell)) seen_[object] = 1;
  }

  const PreparedScene& scene_;
  const cells::CellMap& map_;
  std::uint32_t home_;
  std::int64_t maxChains_;
  std::vector<std::uint8_t> seen_, onChain_;
  dvec3 origin_;
  // A corner this close to a plane is on it; and every cut keeps this much more than
  // the planes say, as the rounding of a separator's distances grows along a chain.
  // Both relative to the level's size, far below anything a pixel shows.
  double onPlane_, slack_;
  std::int64_t chains_ = 0;
  bool givenUp_ = false;
};

// "lamp, table, chair": the objects' names, the first `most` of them, then how many more.
constexpr std::size_t kObjectsNamed = 12;
std::string objectNames(const PreparedScene& scene, const std::vector<std::uint32_t>& objects, std::size_t most) {
  std::string names;
  for (std::size_t i = 0; i < std::min(most, objects.size()); ++i)
    names += (names.empty() ? "" : ", ") + scene.scene().objects[scene.instances()[objects[i]].object].name;
  if (objects.size() > most) names += " and " + std::to_string(objects.size() - most) + " more";
  return names.empty() ? "(none)" : names;
}

std::string settingsLine(const Knobs& knobs) {
  return knobs.build == Build::conservative
             ? "build conservative max-chains " + std::to_string(knobs.maxChains)
             : "build sampled samples " + std::to_string(knobs.samples) + " resolution " + std::to_string(knobs.resolution);
}

}  // namespace

VisibleSets build(const PreparedScene& scene, const cells::CellMap& map, const Knobs& knobs, int threads, Stats& stats) {
  const auto start = std::chrono::steady_clock::now();
  VisibleSets sets;
  sets.objects.resize(map.size());
  std::vector<std::int64_t> work(map.size(), 0), givenUp(map.size(), 0);
  std::optional<SurfaceReference> reference;
  if (knobs.build == Build::sampled) reference.emplace(scene, stats, ReferenceTraversal::packets);
  // One cell per task, each writing only its own set: the same sets for any thread count.
  parallelFor(map.size(), threads, [&](std::size_t cell, int) {
    const std::vector<std::uint8_t> seen =
        knobs.build == Build::sampled
            ? sampledSet(scene, *reference, scene.scene().cells[cell], knobs, work[cell])
            : ConservativeSearch(scene, map, std::uint32_t(cell), knobs.maxChains).run(work[cell], givenUp[cell]);
    for (std::uint32_t object = 0; object < seen.size(); ++object)
      if (seen[object]) sets.objects[cell].push_back(object);
  });
  for (std::size_t cell = 0; cell < map.size(); ++cell) sets.work += work[cell], sets.cellsGivenUp += givenUp[cell];
  sets.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.add(knobs.build == Build::sampled ? "pvs: rays traced" : "pvs: chains followed", sets.work);
  stats.add("pvs: cells given up", sets.cellsGivenUp);
  std::int64_t total = 0;
  for (const auto& set : sets.objects) total += std::int64_t(set.size());
  stats.add("pvs: objects in all sets", total);
  stats.addSeconds("pvs build", sets.seconds);
  return sets;
}

std::string fingerprint(const PreparedScene& scene) {
  // FNV-1a over the bits of every number the sets depend on.
  std::uint64_t hash = 1469598103934665603ull;
  const auto add = [&](double value) {
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (int byte = 0; byte < 8; ++byte) hash = (hash ^ ((bits >> (8 * byte)) & 0xff)) * 1099511628211ull;
  };
  const auto addPoint = [&](const dvec3& p) { add(p.x), add(p.y), add(p.z); };
  for (const Instance& instance : scene.instances()) addPoint(instance.box.lo), addPoint(instance.box.hi);
  for (const Cell& cell : scene.scene().cells) addPoint(cell.from), addPoint(cell.to);
  for (const Portal& portal : scene.scene().portals) {
    add(portal.cells[0]), add(portal.cells[1]);
    for (const dvec3& corner : portal.polygon) addPoint(corner);
  }
  add(scene.scene().camera.near), add(scene.scene().camera.far);
  char text[17];
  std::snprintf(text, sizeof text, "%016" PRIx64, hash);
  return text;
}

void writeCache(const std::filesystem::path& path, const PreparedScene& scene, const Knobs& knobs, const VisibleSets& sets) {
  std::ostringstream text;
  text << "hsr pvs 1\nfingerprint " << fingerprint(scene) << "\n" << settingsLine(knobs) << "\nseconds " << sets.seconds << "\nwork "
       << sets.work << "\ngiven-up " << sets.cellsGivenUp << "\ncells " << sets.objects.size() << "\n";
  // Each cell's line ends with a comment naming the cell and its objects, for a reader.
  for (std::size_t cell = 0; cell < sets.objects.size(); ++cell) {
    text << "cell " << cell << ":";
    for (const std::uint32_t object : sets.objects[cell]) text << " " << object;
    text << "  # " << scene.scene().cells[cell].name << ": " << objectNames(scene, sets.objects[cell], sets.objects[cell].size()) << "\n";
  }
  OutputFiles files;
  files.addText(path, text.str());
  files.commit();
}

VisibleSets readCache(const std::filesystem::path& path, const PreparedScene& scene, const Knobs& knobs) {
  std::ifstream file(path);
  if (!file) throw InputError(path.string() + ": cannot open the visible-set cache; expected a file hsr pvs build --out wrote");
  int lineNumber = 0;
  std::string line;
  const auto next = [&](const std::string& expected) {
    ++lineNumber;
    if (!std::getline(file, line))
      throw InputError(path.string() + ":" + std::to_string(lineNumber) + ": the file ends early; expected " + expected +
                       " (rebuild it with hsr pvs build)");
    return line;
  };
  const auto fail = [&](const std::string& expected) {
    throw InputError(path.string() + ":" + std::to_string(lineNumber) + ": '" + line + "' is not a visible-set cache line; expected " +
                     expected + " (rebuild it with hsr pvs build)");
  };
  if (next("hsr pvs 1") != "hsr pvs 1") fail("hsr pvs 1");
  if (next("fingerprint HASH").rfind("fingerprint ", 0) != 0) fail("fingerprint HASH");
  if (line != "fingerprint " + fingerprint(scene))
    throw InputError(path.string() + ":2: built for another level (its fingerprint differs from this scene's); expected a cache "
                     "of this scene (rebuild it with hsr pvs build)");
  if (next("build ...") != settingsLine(knobs))
    throw InputError(path.string() + ":3: '" + line + "' was built with other settings; expected '" + settingsLine(knobs) +
                     "' (give the stage the settings it was built with, or rebuild it with hsr pvs build)");
  VisibleSets sets;
  long long work = 0, givenUp = 0;
  std::size_t cells = 0;
  if (std::sscanf(next("seconds S").c_str(), "seconds %lf", &sets.seconds) != 1) fail("seconds S");
  if (std::sscanf(next("work N").c_str(), "work %lld", &work) != 1) fail("work N");
  if (std::sscanf(next("given-up N").c_str(), "given-up %lld", &givenUp) != 1) fail("given-up N");
  if (std::sscanf(next("cells N").c_str(), "cells %zu", &cells) != 1 || cells != scene.scene().cells.size())
    fail("cells " + std::to_string(scene.scene().cells.size()));
  sets.work = work, sets.cellsGivenUp = givenUp;
  sets.objects.resize(cells);
  for (std::size_t cell = 0; cell < cells; ++cell) {
    const std::string expected = "cell " + std::to_string(cell) + ": OBJECT...";
    std::string content = next(expected);
    content = content.substr(0, content.find('#'));  // the names after '#' are for a reader
    std::istringstream items(content);
    std::string word, label;
    if (!(items >> word >> label) || word != "cell" || label != std::to_string(cell) + ":") fail(expected);
    long long object;
    while (items >> object) {
      if (object < 0 || std::size_t(object) >= scene.instances().size()) fail(expected + " with objects below " + std::to_string(scene.instances().size()));
      sets.objects[cell].push_back(std::uint32_t(object));
    }
    if (!items.eof()) fail(expected);
  }
  return sets;
}

VisibleSet cull(const PreparedScene& scene, const cells::CellMap& map, const VisibleSets& sets, const CameraTransform& camera,
                const VisibleSet& in, Stats& stats, StageWitness* why) {
  std::vector<std::uint8_t> inSet(scene.instances().size(), 0);
  std::string cellNames;
  const std::vector<std::uint32_t> eyeCells = map.cellsAt(camera.camera().eye, "--cull pvs");
  for (const std::uint32_t cell : eyeCells) {
    cellNames += (cellNames.empty() ? "" : ", ") + scene.scene().cells[cell].name;
    for (const std::uint32_t object : sets.objects[cell]) inSet[object] = 1;
  }
  std::vector<std::uint32_t> objects;
  for (std::uint32_t object = 0; object < inSet.size(); ++object)
    if (inSet[object]) objects.push_back(object);
  stats.add("pvs: objects in the set", std::int64_t(objects.size()));
  stats.note("pvs: the eye's cells", cellNames);
  stats.note("pvs: the set", objectNames(scene, objects, kObjectsNamed));
  if (why) [[unlikely]] {
    const std::string quoted = cells::quotedCells(scene, eyeCells);  // the eye's, on a shared face two or more
    for (std::size_t i = 0; i < why->instances.size(); ++i)
      why->found[i] = std::string(inSet[why->instances[i]] ? "it is in" : "it is not in") + " the potentially visible set of the eye's " + quoted +
                      (inSet[why->instances[i]] ? "" : ", which holds every object some eye there may see");
  }
  return keepObjects(scene, in, [&](std::uint32_t object) { return inSet[object] != 0; });
}

StageEntry stage() {
  StageEntry entry = stageEntry("pvs", "draw only the eye's cell's potentially visible set, built once per level (scenes with [[cells]])",
                                knobTable());
  entry.needsCells = true;
  entry.mayDropVisible = [](const KnobValues& knobs) { return knobs.as<Knobs>().build == Build::sampled; };
  entry.conflict = [](const KnobValues& values) {
    const Knobs& knobs = values.as<Knobs>();
    const Knobs defaults;
    if (knobs.build == Build::conservative && (knobs.samples != defaults.samples || knobs.resolution != defaults.resolution))
      return std::string("samples and resolution set how build=sampled samples; expected build=sampled with them");
    if (knobs.build == Build::sampled && knobs.maxChains != defaults.maxChains)
      return std::string("max-chains bounds the conservative build's search; expected build=conservative with it");
    return std::string();
  };
  entry.run = [](const KnobValues& values, const StageInput& input) {
    const Knobs& knobs = values.as<Knobs>();
    struct Built {
      cells::CellMap map;
      VisibleSets sets;
    };
    std::optional<Built> local;
    const Built& built = cells::remembered(input, local, [&] {
      cells::CellMap map(input.scene, "--cull pvs");
      input.stats.add(knobs.cache.empty() ? "pvs: built now" : "pvs: read from the cache");
      VisibleSets sets = knobs.cache.empty() ? build(input.scene, map, knobs, input.threads, input.stats)
                                             : readCache(knobs.cache, input.scene, knobs);
      return Built{std::move(map), std::move(sets)};
    });
    return cull(input.scene, built.map, built.sets, input.camera, input.in, input.stats, input.why);
  };
  return entry;
}

}  // namespace hsr::culling::pvs
