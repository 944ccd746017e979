// Cells and portals (Scene::cells, Scene::portals in renderer/scene/scene.hpp) as the stages
// portals (portals.hpp) and pvs (pvs.hpp) use them: which objects each cell holds, which
// portals lead out of it, where the eye is, and the one geometric operation both stages
// are made of, cutting a convex polygon by a plane.
//
// The level's promise (scene.hpp): a cell's boundary is opaque except where a portal
// opens it, and nothing outside every cell can be seen from inside one. So a line of
// sight from the eye to anything it sees runs through a chain of cells, each entered
// through a portal of the one before; and since cells are convex boxes, it passes each
// cell at most once and crosses each portal's plane once, from the cell it leaves to the
// cell it enters. Both stages search for such chains; they differ in where the line may
// start (the eye, or anywhere in the eye's cell) and in when they search (every frame,
// or once per level).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "algorithms/culling/culling.hpp"
#include "renderer/geometry/camera.hpp"
#include "renderer/scene/prepare.hpp"

namespace hsr::culling::cells {

// A convex polygon, its corners in order.
using Polygon = std::vector<dvec3>;

// The part of a convex polygon where plane.distance(p) >= -slack (Sutherland and Hodgman's
// step for one plane): the corners inside, and a new corner where an edge crosses the
// plane. `slack` keeps what rounding might put just outside, so a cut never loses a
// line of sight. Empty when nothing is inside.
Polygon clip(const Polygon& polygon, const Plane& plane, double slack);

// A box against a plane: true when even its corner farthest along the normal is more
// than `slack` behind it.
bool boxBehind(const dvec3& lo, const dvec3& hi, const Plane& plane, double slack);

// The cells of a prepared scene, with what each holds and where its portals lead.
class CellMap {
 public:
  // Each cell holds every object whose box meets the cell's box, touching included (a
  // wall between two rooms is in both). Throws InputError for a scene without cells and
  // for a cell that holds no object (a mistake in the level: a room nobody furnished is
  // still floored and walled).
  CellMap(const PreparedScene& scene, const std::string& where);

  struct Door {
    std::uint32_t portal;  // index into Scene::portals
    std::uint32_t to;      // the cell on its other side
  };
  std::size_t size() const { return objects_.size(); }
  const std::vector<std::uint32_t>& objects(std::uint32_t cell) const { return objects_[cell]; }
  const std::vector<Door>& doors(std::uint32_t cell) const { return doors_[cell]; }

  // The cells whose box holds the point, boundary included (two or more on a shared
  // face). Throws InputError naming `where` when it lies in none: the stages cannot know
  // what an eye outside the level sees.
  std::vector<std::uint32_t> cellsAt(const dvec3& point, const std::string& where) const;

  // Per cell, 1 when portals connect it to one of `from` (each of `from` included):
  // where the stages' searches fall back to when they give up.
  std::vector<std::uint8_t> connectedTo(const std::vector<std::uint32_t>& from) const;

  // The plane of a portal, facing the cell a line of sight enters when it crosses from
  // `from` (positive distances on the far side).
  Plane planeInto(const Portal& portal, std::uint32_t from) const;

  // The slack of the stages' comparisons: `fraction` of the level's size (the diagonal
  // of the box around its cells), plus what subtracting two points as far from the
  // origin as the level reaches can round off (450 units in the last place of the
  // largest coordinate). Far above the rounding of any distance the stages compute,
  // relative to a point in the level; far below anything a pixel shows.
  double slack(double fraction) const { return fraction * size_ + 0x1p-43 * magnitude_; }

 private:
  const Scene* scene_;
  std::vector<std::vector<std::uint32_t>> objects_;
  std::vector<std::vector<Door>> doors_;
  double size_ = 0, magnitude_ = 0;
};

// Cells as hsr why names them: `cell "hall"`, or `cells "hall", "kitchen"`.
std::string quotedCells(const PreparedScene& scene, const std::vector<std::uint32_t>& cells);

// What a cell stage builds for a scene (its map, its visible sets), built once for a walk:
// kept in the stage's slot of the walk's memory and rebuilt only for another scene; for
// a single frame (no slot), built into `local`.
template <typename Built, typename Build>
const Built& remembered(const StageInput& input, std::optional<Built>& local, Build&& build) {
  struct Memory : StageMemory {
    const PreparedScene* scene = nullptr;
    std::optional<Built> built;
  };
  if (!input.memory) return local.emplace(build());
  auto* memory = dynamic_cast<Memory*>(input.memory->get());
  if (!memory || memory->scene != &input.scene) {
    auto fresh = std::make_unique<Memory>();
    fresh->scene = &input.scene;
    fresh->built.emplace(build());
    memory = fresh.get();
    *input.memory = std::move(fresh);
  }
  return *memory->built;
}

}  // namespace hsr::culling::cells
