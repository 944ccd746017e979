// Portal culling, Luebke and Georges' traversal (portals.hpp has the steps).
#include "algorithms/culling/cells/portals.hpp"

#include <algorithm>
#include <optional>

#include "renderer/util/error.hpp"

namespace hsr::culling::portals {
namespace {

// What a chain of portals lets the eye see: a cone with its apex at the eye, as planes
// through it (coordinates relative to the eye, inside where distance >= 0).
struct View {
  // The rectangle in tangents of the view basis: a point p (relative to the eye) is at
  // x = (p . right) / (p . forward), y = (p . up) / (p . forward).
  double left, right, bottom, top;
  std::vector<Plane> outline;  // polygon narrowing: one plane per edge of the last portal's cut outline

  std::vector<Plane> planes(const CameraTransform& camera) const {
    const dvec3 &r = camera.right(), &u = camera.up(), &f = camera.forward();
    std::vector<Plane> all = {{r - left * f, 0}, {right * f - r, 0}, {u - bottom * f, 0}, {top * f - u, 0}};
    all.insert(all.end(), outline.begin(), outline.end());
    return all;
  }
};

// The search of one frame.
class Traversal {
 public:
  Traversal(const PreparedScene& scene, const cells::CellMap& map, const CameraTransform& camera, const Knobs& knobs)
      : scene_(scene), map_(map), camera_(camera), narrowing_(knobs.narrowing), maxPasses_(knobs.maxPasses), eye_(camera.camera().eye),
        reached_(map.size()), onChain_(map.size(), 0) {
    // Slack for every comparison (cells.hpp), with coordinates relative to the eye.
    slack_ = map.slack(1e-9);
  }

  // Steps 1 to 3 from each cell the eye is in (two or more on a shared face).
  void search(const std::vector<std::uint32_t>& eyeCells) {
    // The whole image: its corners' tangents, from the camera's own rays.
    const Ray low = camera_.rayThroughPixel(0, camera_.height()), high = camera_.rayThroughPixel(camera_.width(), 0);
    image_ = {tangentX(low.direction), tangentX(high.direction), tangentY(low.direction), tangentY(high.direction), {}};
    for (const std::uint32_t cell : eyeCells) {
      onChain_[cell] = 1;
      enter(cell, image_);
      onChain_[cell] = 0;
    }
  }

  std::vector<std::uint8_t> cellsReached() const {
    std::vector<std::uint8_t> cells(map_.size(), 0);
    for (std::uint32_t cell = 0; cell < map_.size(); ++cell) cells[cell] = !reached_[cell].empty();
    return cells;
  }

  // Step 4: the objects of the cells reached, each kept when a view that reached one of
  // its cells may contain its box.
  std::vector<std::uint8_t> objectsKept(Stats& stats) {
    std::vector<std::uint8_t> kept(scene_.instances().size(), 0);
    std::int64_t tested = 0;
    for (std::uint32_t cell = 0; cell < map_.size(); ++cell) {
      if (reached_[cell].empty()) continue;
      std::vector<std::vector<Plane>> views;
      for (const View& view : reached_[cell]) views.push_back(view.planes(camera_));
      for (const std::uint32_t object : map_.objects(cell)) {
        if (kept[object]) continue;
        ++tested;
        const Aabb& box = scene_.instances()[object].box;
        kept[object] = givenUp_ || std::any_of(views.begin(), views.end(), [&](const std::vector<Plane>& planes) {
                         return std::none_of(planes.begin(), planes.end(), [&](const Plane& plane) {
                           return cells::boxBehind(box.lo - eye_, box.hi - eye_, plane, slack_ * glm::length(plane.normal));
                         });
                       });
      }
    }
    stats.add("portals: objects tested", tested);
    return kept;
  }

  // hsr why: for each object asked about, the cells it lies in, which of them a chain of
  // portals reached, and what step 4 made of it (`kept`: objectsKept's answer).
  void explain(StageWitness& why, const std::vector<std::uint8_t>& kept) const {
    for (std::size_t i = 0; i < why.instances.size(); ++i) {
      const std::uint32_t object = why.instances[i];
      std::vector<std::uint32_t> lies, reached;  // its cells, and those of them reached
      for (std::uint32_t cell = 0; cell < map_.size(); ++cell) {
        const std::vector<std::uint32_t>& objects = map_.objects(cell);
        if (std::find(objects.begin(), objects.end(), object) == objects.end()) continue;
        lies.push_back(cell);
        if (!reached_[cell].empty()) reached.push_back(cell);
      }
      why.found[i] = lies.empty() ? "it lies in no cell of the level"
                     : reached.empty() ? "no chain of portals from the eye's cell reaches its " + cells::quotedCells(scene_, lies)
                     : givenUp_ ? "the search gave up after " + std::to_string(maxPasses_) + " portals, so every object of a cell it reached is kept, its " +
                                      cells::quotedCells(scene_, reached) + " among them"
                     : kept[object] ? "a chain of portals from the eye's cell reaches its " + cells::quotedCells(scene_, reached) +
                                          ", and its box lies within a view narrowed through the portals"
                                    : "a chain of portals reaches its " + cells::quotedCells(scene_, reached) +
                                          ", but its box lies outside every view narrowed through the portals";
    }
  }

  void count(Stats& stats) const {
    const std::vector<std::uint8_t> cells = cellsReached();
    stats.add("portals: cells visited", visits_);
    stats.add("portals: cells reached", std::count(cells.begin(), cells.end(), std::uint8_t(1)));
    stats.add("portals: portals passed", passes_);
    stats.add("portals: portals cut away", cutAway_);
    stats.add("portals: searches given up", givenUp_ ? 1 : 0);
  }

 private:
  double tangentX(const dvec3& p) const { return glm::dot(p, camera_.right()) / glm::dot(p, camera_.forward()); }
  double tangentY(const dvec3& p) const { return glm::dot(p, camera_.up()) / glm::dot(p, camera_.forward()); }

  void enter(std::uint32_t cell, const View& view) {
    ++visits_;
    reached_[cell].push_back(view);
    for (const cells::CellMap::Door& door : map_.doors(cell)) {
      if (onChain_[door.to] || givenUp_) continue;
      const Portal& portal = scene_.scene().portals[door.portal];
      // Step 2: the eye must be on this side of the portal's plane, or on it.
      const double eyeBeyond = map_.planeInto(portal, cell).distance(eye_);
      if (eyeBeyond > slack_) continue;
      std::optional<View> narrowed = narrow(view, portal, eyeBeyond >= -slack_);
      if (!narrowed) {
        ++cutAway_;
        continue;
      }
      if (++passes_ > maxPasses_) {
        giveUp();
        return;
      }
      // Step 3.
      onChain_[door.to] = 1;
      enter(door.to, *narrowed);
      onChain_[door.to] = 0;
    }
  }

  // The portal cut by the view; nothing when nothing of it is left, else the view
  // narrowed to what is.
  std::optional<View> narrow(const View& view, const Portal& portal, bool eyeOnPlane) const {
    cells::Polygon cut;
    for (const dvec3& corner : portal.polygon) cut.push_back(corner - eye_);
    for (const Plane& plane : view.planes(camera_)) {
      cut = cells::clip(cut, plane, slack_ * glm::length(plane.normal));
      if (cut.empty()) return std::nullopt;
    }
    if (eyeOnPlane) return view;
    // The eye is off the portal's plane, so every point of the cut portal is in front of
    // it and inside the image's cone: its tangents are finite.
    View narrowed = view;
    double left = view.right, right = view.left, bottom = view.top, top = view.bottom;
    for (const dvec3& p : cut) {
      left = std::min(left, tangentX(p)), right = std::max(right, tangentX(p));
      bottom = std::min(bottom, tangentY(p)), top = std::max(top, tangentY(p));
    }
    // Within the view's rectangle, and never inside out (a cut that rounding left a
    // hair outside keeps a rectangle of no width at the edge).
    narrowed.left = std::clamp(left, view.left, view.right), narrowed.right = std::clamp(right, narrowed.left, view.right);
    narrowed.bottom = std::clamp(bottom, view.bottom, view.top), narrowed.top = std::clamp(top, narrowed.bottom, view.top);
    if (narrowing_ == Narrowing::polygon) narrowed.outline = outlineOf(cut);
    return narrowed;
  }

  // The cone over a convex polygon seen from the eye (the origin): a plane through the
  // eye and each edge, turned so that the polygon is inside.
  static std::vector<Plane> outlineOf(const cells::Polygon& polygon) {
    dvec3 center(0);
    for (const dvec3& p : polygon) center += p / double(polygon.size());
    std::vector<Plane> planes;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const dvec3 normal = glm::cross(polygon[i], polygon[(i + 1) % polygon.size()]);
      const double length = glm::length(normal);
      // An edge of no length (two corners the cut made at one point) bounds nothing.
      if (!(length > 1e-12 * glm::length(polygon[i]) * glm::length(polygon[(i + 1) % polygon.size()]))) continue;
      planes.push_back({normal / length, 0});
    }
    // The corners go around one way seen from the eye: the center is inside all the
    // planes or outside all of them.
    double inside = 0;
    for (const Plane& plane : planes) inside += plane.distance(center);
    if (inside < 0)
      for (Plane& plane : planes) plane.normal = -plane.normal;
    return planes;
  }

  // Too many chains: every cell connected to the eye's by portals, every object in them.
  void giveUp() {
    givenUp_ = true;
    std::vector<std::uint32_t> reached;
    for (std::uint32_t cell = 0; cell < map_.size(); ++cell)
      if (!reached_[cell].empty()) reached.push_back(cell);
    const std::vector<std::uint8_t> connected = map_.connectedTo(reached);
    for (std::uint32_t cell = 0; cell < map_.size(); ++cell)
      if (connected[cell] && reached_[cell].empty()) reached_[cell].push_back(image_);
  }

  const PreparedScene& scene_;
  const cells::CellMap& map_;
  const CameraTransform& camera_;
  Narrowing narrowing_;
  std::int64_t maxPasses_;
  dvec3 eye_;
  double slack_ = 0;
  View image_{};
  std::vector<std::vector<View>> reached_;  // per cell, the views it was reached with
  std::vector<std::uint8_t> onChain_;
  std::int64_t visits_ = 0, passes_ = 0, cutAway_ = 0;
  bool givenUp_ = false;
};

// Steps 1 to 3.
Traversal searched(const PreparedScene& scene, const cells::CellMap& map, const CameraTransform& camera, const Knobs& knobs,
                   Stats& stats) {
  if (!camera.perspective())
    throw InputError("--cull portals: the camera of " + scene.scene().file.string() +
                     " is orthographic; expected a perspective camera (the view is narrowed from the eye)");
  Traversal traversal(scene, map, camera, knobs);
  traversal.search(map.cellsAt(camera.camera().eye, "--cull portals"));
  traversal.count(stats);
  return traversal;
}

}  // namespace

std::vector<std::uint8_t> cellsReached(const PreparedScene& scene, const cells::CellMap& map, const CameraTransform& camera,
                                       const Knobs& knobs, Stats& stats) {
  return searched(scene, map, camera, knobs, stats).cellsReached();
}

VisibleSet cull(const PreparedScene& scene, const cells::CellMap& map, const CameraTransform& camera, const Knobs& knobs,
                const VisibleSet& in, Stats& stats, StageWitness* why) {
  Traversal traversal = searched(scene, map, camera, knobs, stats);
  const std::vector<std::uint8_t> kept = traversal.objectsKept(stats);
  if (why) [[unlikely]]
    traversal.explain(*why, kept);
  std::int64_t objectsKept = 0;
  VisibleSet out = keepObjects(scene, in, [&](std::uint32_t object) { return kept[object] ? (++objectsKept, true) : false; });
  stats.add("portals: objects kept", objectsKept);
  return out;
}

StageEntry stage() {
  StageEntry entry = stageEntry("portals", "draw only the cells a chain of portals from the eye's cell reaches (scenes with [[cells]])",
                                knobTable());
  entry.needsCells = true;
  entry.mayDropVisible = [](const KnobValues&) { return false; };
  entry.run = [](const KnobValues& knobs, const StageInput& input) {
    std::optional<cells::CellMap> local;
    const cells::CellMap& map = cells::remembered(input, local, [&] { return cells::CellMap(input.scene, "--cull portals"); });
    return cull(input.scene, map, input.camera, knobs.as<Knobs>(), input.in, input.stats, input.why);
  };
  return entry;
}

}  // namespace hsr::culling::portals
