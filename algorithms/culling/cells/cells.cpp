// Cells and portals: the map both cell stages read (cells.hpp).
#include "algorithms/culling/cells/cells.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "renderer/util/error.hpp"

namespace hsr::culling::cells {

Polygon clip(const Polygon& polygon, const Plane& plane, double slack) {
  Polygon inside;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const dvec3& p = polygon[i];
    const dvec3& q = polygon[(i + 1) % polygon.size()];
    const double dp = plane.distance(p) + slack, dq = plane.distance(q) + slack;
    if (dp >= 0) inside.push_back(p);
    // The edge crosses the plane: its crossing is a corner of what is inside.
    if ((dp >= 0) != (dq >= 0)) inside.push_back(p + (q - p) * (dp / (dp - dq)));
  }
  return inside;
}

bool boxBehind(const dvec3& lo, const dvec3& hi, const Plane& plane, double slack) {
  const dvec3 farthest(plane.normal.x > 0 ? hi.x : lo.x, plane.normal.y > 0 ? hi.y : lo.y, plane.normal.z > 0 ? hi.z : lo.z);
  return plane.distance(farthest) < -slack;
}

CellMap::CellMap(const PreparedScene& scene, const std::string& where) : scene_(&scene.scene()) {
  const std::vector<Cell>& cells = scene_->cells;
  if (cells.empty())
    throw InputError(where + ": " + scene_->file.string() +
                     " has no cells; expected [[cells]] and [[portals]] tables dividing the level (scenes/README.md)");
  objects_.resize(cells.size());
  doors_.resize(cells.size());
  Aabb level;
  for (std::uint32_t c = 0; c < cells.size(); ++c) {
    const Cell& cell = cells[c];
    level.grow(cell.from), level.grow(cell.to);
    magnitude_ = std::max({magnitude_, glm::length(glm::abs(cell.from)), glm::length(glm::abs(cell.to))});
    for (std::uint32_t i = 0; i < scene.instances().size(); ++i) {
      const Aabb& box = scene.instances()[i].box;
      if (glm::all(glm::lessThanEqual(box.lo, cell.to)) && glm::all(glm::lessThanEqual(cell.from, box.hi))) objects_[c].push_back(i);
    }
    if (objects_[c].empty())
      throw InputError(cell.where + ": no object meets this cell; expected every cell to hold at least one object (its floor, its walls)");
  }
  size_ = glm::length(level.hi - level.lo);
  for (std::uint32_t p = 0; p < scene_->portals.size(); ++p) {
    const Portal& portal = scene_->portals[p];
    doors_[portal.cells[0]].push_back({p, portal.cells[1]});
    doors_[portal.cells[1]].push_back({p, portal.cells[0]});
  }
}

std::vector<std::uint32_t> CellMap::cellsAt(const dvec3& point, const std::string& where) const {
  std::vector<std::uint32_t> found;
  for (std::uint32_t c = 0; c < scene_->cells.size(); ++c) {
    const Cell& cell = scene_->cells[c];
    if (glm::all(glm::lessThanEqual(cell.from, point)) && glm::all(glm::lessThanEqual(point, cell.to))) found.push_back(c);
  }
  if (found.empty()) {
    std::ostringstream text;
    text << where << ": the eye (" << point.x << ", " << point.y << ", " << point.z << ") is in no cell of " << scene_->file.string()
         << "; expected it inside one of its " << scene_->cells.size() << " cells";
    throw InputError(text.str());
  }
  return found;
}

std::vector<std::uint8_t> CellMap::connectedTo(const std::vector<std::uint32_t>& from) const {
  std::vector<std::uint8_t> connected(size(), 0);
  std::vector<std::uint32_t> frontier = from;
  for (const std::uint32_t cell : from) connected[cell] = 1;
  while (!frontier.empty()) {
    const std::uint32_t cell = frontier.back();
    frontier.pop_back();
    for (const Door& door : doors(cell))
      if (!connected[door.to]) connected[door.to] = 1, frontier.push_back(door.to);
  }
  return connected;
}

Plane CellMap::planeInto(const Portal& portal, std::uint32_t from) const {
  // cells[0] lies below the plane: leaving it, a line goes up the portal's axis.
  const double sign = from == portal.cells[0] ? 1 : -1;
  Plane plane;
  plane.normal[portal.axis] = sign;
  plane.offset = -sign * portal.at;
  return plane;
}

std::string quotedCells(const PreparedScene& scene, const std::vector<std::uint32_t>& cells) {
  std::string text = cells.size() == 1 ? "cell " : "cells ";
  for (std::size_t k = 0; k < cells.size(); ++k) text += (k ? ", \"" : "\"") + scene.scene().cells[cells[k]].name + "\"";
  return text;
}

}  // namespace hsr::culling::cells
