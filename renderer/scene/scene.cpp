#include "renderer/scene/scene.hpp"
#include "renderer/scene/triangle_file.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <toml++/toml.h>

#include "renderer/scene/obj.hpp"
#include "renderer/scene/toml_text.hpp"
#include "renderer/scene/toml_reader.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/portable_math.hpp"

namespace hsr {
namespace {

void readImage(TableReader& image, Scene& scene) {
  scene.width = image.integer("width", 640, 1, kMaxImageSide);
  scene.height = image.integer("height", 480, 1, kMaxImageSide);
  scene.background = image.color("background", vec3(0));
  image.finish({"width", "height", "background"});
  checkImageSize(scene.width, scene.height, image.file().string() + ": image");
}

// (cos, sin) of an angle in degrees, exact at multiples of 90 (so a view from straight
// above has no stray horizontal component).
dvec2 unitCircleDegrees(double degrees) {
  const double quarterTurns = degrees / 90;
  if (quarterTurns == std::round(quarterTurns)) {
    constexpr dvec2 kQuarter[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    return kQuarter[((static_cast<int>(quarterTurns) % 4) + 4) % 4];
  }
  const double radians = glm::radians(degrees);
  return {portable::cos(radians), portable::sin(radians)};
}

void readCamera(TableReader& camera, Scene& scene) {
  Camera& c = scene.camera;
  const std::string type = camera.choice("type", "perspective", {"perspective", "orthographic"});
  c.projection = type == "perspective" ? Projection::perspective : Projection::orthographic;
  c.target = camera.vector3("target", std::nullopt, -kMaxCoordinate, kMaxCoordinate);
  std::vector<std::string> keys = {"type", "target", "near", "far", c.projection == Projection::perspective ? "fov_y" : "height"};
  if (camera.has("azimuth") || camera.has("elevation") || camera.has("distance")) {
    // The eye on a sphere around the target, as plots of z = f(x, y) are viewed: azimuth
    // 0 puts it on the +z side, growing toward +x; elevation 90 looks straight down.
    // Up is where the elevation grows, so a view from straight above has one too.
    if (camera.has("eye")) camera.fail(camera.find("eye"), "eye", "give either eye or azimuth, elevation and distance, not both");
    if (camera.has("up")) camera.fail(camera.find("up"), "up", "is implied by azimuth and elevation; leave it out");
    const double azimuth = camera.number("azimuth", std::nullopt, -360, 360);
    const double elevation = camera.number("elevation", std::nullopt, -90, 90);
    const double distance = camera.number("distance", std::nullopt, 1e-9, kMaxCoordinate);
    const dvec2 a = unitCircleDegrees(azimuth), e = unitCircleDegrees(elevation);  // (cos, sin)
    c.eye = c.target + distance * dvec3(e.x * a.y, e.y, e.x * a.x);
    c.up = dvec3(-e.y * a.y, e.x, -e.y * a.x);
    keys.insert(keys.end(), {"azimuth", "elevation", "distance"});
  } else {
    c.eye = camera.vector3("eye", std::nullopt, -kMaxCoordinate, kMaxCoordinate);
    c.up = camera.vector3("up", dvec3(0, 1, 0), -kMaxCoordinate, kMaxCoordinate);
    keys.insert(keys.end(), {"eye", "up"});
  }
  c.near = camera.number("near", 0.1, 1e-9, kMaxCoordinate);
  c.far = camera.number("far", 1000.0, 1e-9, kMaxCoordinate);
  if (c.projection == Projection::perspective)
    c.fovYDegrees = camera.number("fov_y", 45.0, 0.01, 179.0);
  else
    c.orthoHeight = camera.number("height", std::nullopt, 1e-9, kMaxCoordinate);
  camera.finish(keys);
  if (const CameraProblem problem = cameraProblem(c)) camera.fail(nullptr, problem.key, problem.must);
}

void readLight(TableReader& light, Scene& scene) {
  Light result;
  result.name = light.has("name") ? light.string("name") : "light" + std::to_string(scene.lights.size());
  const std::string type = light.choice("type", "directional", {"directional", "point"});
  if (type == "directional") {
    result.kind = Light::Kind::directional;
    result.direction = light.vector3("direction", std::nullopt, -kMaxCoordinate, kMaxCoordinate);
    if (glm::length(result.direction) == 0) light.fail(nullptr, "direction", "must not be zero");
    result.direction = glm::normalize(result.direction);
  } else {
    result.kind = Light::Kind::point;
    result.position = light.vector3("position", std::nullopt, -kMaxCoordinate, kMaxCoordinate);
  }
  result.intensity = light.number("intensity", 1.0, 0.0, 1e6);
  light.finish({"name", "type", type == "directional" ? "direction" : "position", "intensity"});
  scene.lights.push_back(result);
}

Instancing readInstancing(TableReader& copies) {
  Instancing result;
  const std::string kind = copies.choice("kind", std::nullopt, {"grid", "ring", "scatter", "area"});
  if (kind == "grid") {
    result.kind = Instancing::Kind::grid;
    result.gridCount = glm::ivec3(copies.vector3("count", std::nullopt, 1, 1000));
    result.gridSpacing = copies.vector3("spacing", std::nullopt, -kMaxCoordinate, kMaxCoordinate);
    copies.finish({"kind", "count", "spacing"});
    return result;
  }
  result.count = copies.integer("count", std::nullopt, 1, 1000000);
  if (kind == "area") {
    result.kind = Instancing::Kind::area;
    result.from = copies.vector3("from", std::nullopt, -kMaxCoordinate, kMaxCoordinate);
    result.to = copies.vector3("to", std::nullopt, -kMaxCoordinate, kMaxCoordinate);
    result.seed = static_cast<std::uint64_t>(copies.integer("seed", 1, 0, 2147483647));
    result.minScales = copies.vector3("min_scale", dvec3(1), 1e-6, 1e6);
    result.maxScales = copies.vector3("max_scale", result.minScales, 1e-6, 1e6);
    copies.finish({"kind", "count", "from", "to", "seed", "min_scale", "max_scale"});
    for (int axis = 0; axis < 3; ++axis) {
      if (result.from[axis] > result.to[axis]) copies.fail(nullptr, "from", "must not exceed `to` on any axis");
      if (result.minScales[axis] > result.maxScales[axis])
        copies.fail(nullptr, "min_scale", "must not exceed max_scale on any axis");
    }
    return result;
  }
  result.center = copies.vector3("center", dvec3(0), -kMaxCoordinate, kMaxCoordinate);
  if (kind == "ring") {
    result.kind = Instancing::Kind::ring;
    result.radius = copies.number("radius", std::nullopt, 0, kMaxCoordinate);
    copies.finish({"kind", "count", "center", "radius"});
    return result;
  }
  result.kind = Instancing::Kind::scatter;
  result.innerRadius = copies.number("inner_radius", 0.0, 0, kMaxCoordinate);
  result.radius = copies.number("radius", std::nullopt, 0, kMaxCoordinate);
  result.seed = static_cast<std::uint64_t>(copies.integer("seed", 1, 0, 2147483647));
  result.minScale = copies.number("min_scale", 1.0, 1e-6, 1e6);
  result.maxScale = copies.number("max_scale", result.minScale, result.minScale, 1e6);
  copies.finish({"kind", "count", "center", "radius", "inner_radius", "seed", "min_scale", "max_scale"});
  if (result.innerRadius > result.radius) copies.fail(nullptr, "inner_radius", "must not exceed radius");
  return result;
}

std::shared_ptr<const Mesh> readShape(TableReader& object, std::vector<std::string>& keys,
                                      std::map<std::filesystem::path, std::shared_ptr<const Mesh>>& meshCache, Solid& solid) {
  const std::string shape =
      object.choice("shape", std::nullopt, {"mesh", "box", "sphere", "cylinder", "cone", "grid", "heightfield"});
  const auto segments = [&](const std::string& key, int fallback, int min) {
    keys.push_back(key);
    return object.integer(key, fallback, min, 4096);
  };
  const auto positive = [&](const std::string& key, double fallback) {
    keys.push_back(key);
    return object.number(key, fallback, 1e-9, kMaxCoordinate);
  };
  const auto size2 = [&]() {
    keys.push_back("size");
    const toml::node* node = object.find("size");
    if (!node) return dvec2(2, 2);
    const toml::array* array = node->as_array();
    if (!array || array->size() != 2 || !array->get(0)->is_number() || !array->get(1)->is_number() ||
        !(*array->get(0)->value<double>() > 0) || !(*array->get(1)->value<double>() > 0))
      object.fail(node, "size", "expected an array of 2 positive numbers [x, z], got " + TableReader::describe(*node));
    return dvec2(*array->get(0)->value<double>(), *array->get(1)->value<double>());
  };
  const auto segments2 = [&](int fallback) {
    keys.push_back("segments");
    const toml::node* node = object.find("segments");
    if (!node) return glm::ivec2(fallback);
    const toml::array* array = node->as_array();
    const auto valid = [&](std::size_t i) {
      const auto value = integerOf(*array->get(i));
      return value && *value >= 1 && *value <= 4096;
    };
    if (!array || array->size() != 2 || !valid(0) || !valid(1))
      object.fail(node, "segments", "expected an array of 2 integers in [1, 4096], got " + TableReader::describe(*node));
    return glm::ivec2(*array->get(0)->value<int>(), *array->get(1)->value<int>());
  };

  if (shape == "mesh") {
    keys.push_back("file");
    const std::filesystem::path path = object.file().parent_path() / object.string("file");
    auto& cached = meshCache[path.lexically_normal()];
    if (!cached) {
      try {
        cached = std::make_shared<const Mesh>(loadObj(path));
      } catch (const InputError& error) {
        object.fail(object.find("file"), "file", error.what());
      }
    }
    return cached;
  }
  if (shape == "box") {
    keys.push_back("size");
    solid.kind = Solid::Kind::box;
    solid.size = object.vector3("size", dvec3(1), 1e-9, kMaxCoordinate, true);
    return std::make_shared<const Mesh>(makeBox(solid.size));
  }
  if (shape == "sphere") {
    solid.kind = Solid::Kind::sphere;
    solid.radius = positive("radius", 1.0);
    const int around = segments("segments", 32, 3);
    return std::make_shared<const Mesh>(makeSphere(solid.radius, around, segments("rings", 16, 2)));
  }
  if (shape == "cylinder" || shape == "cone") {
    solid.kind = shape == "cylinder" ? Solid::Kind::cylinder : Solid::Kind::cone;
    solid.radius = positive("radius", 0.5);
    solid.height = positive("height", 1.0);
    const int around = segments("segments", 32, 3);
    return std::make_shared<const Mesh>(shape == "cylinder" ? makeCylinder(solid.radius, solid.height, around)
                                                            : makeCone(solid.radius, solid.height, around));
  }
  solid.kind = Solid::Kind::heightField;
  solid.footprint = size2();
  const glm::ivec2 cells = segments2(shape == "grid" ? 1 : 64);
  solid.cells = cells;
  if (shape == "grid") {
    solid.function = {"waves", 0.0, 1.0};
    return std::make_shared<const Mesh>(makeGrid(solid.footprint, cells.x, cells.y));
  }
  keys.insert(keys.end(), {"function", "amplitude", "frequency"});
  solid.function.name = object.choice("function", std::nullopt, heightFunctionNames());
  solid.function.amplitude = object.number("amplitude", 1.0, -kMaxCoordinate, kMaxCoordinate);
  solid.function.frequency = object.number("frequency", 1.0, -kMaxCoordinate, kMaxCoordinate);
  return std::make_shared<const Mesh>(makeHeightField(solid.footprint, cells.x, cells.y, solid.function));
}

void readObject(TableReader& object, Scene& scene,
                std::map<std::filesystem::path, std::shared_ptr<const Mesh>>& meshCache) {
  SceneObject result;
  std::vector<std::string> keys = {"name",      "shape",  "color", "opacity", "reflectivity", "shininess",
                                   "translate", "rotate", "scale", "copies"};
  result.name = object.has("name") ? object.string("name") : "object" + std::to_string(scene.objects.size());
  result.mesh = readShape(object, keys, meshCache, result.solid);
  result.color = object.color("color", vec3(0.8f));
  result.opacity = object.number("opacity", 1.0, 0.0, 1.0);
  if (result.opacity < 1 && !scene.effects.transparency)
    object.fail(object.find("opacity"), "opacity", "an opacity below 1 needs \"transparency\" in the scene's effects");
  for (const char* key : {"reflectivity", "shininess"})
    if (object.has(key) && scene.effects.shading != Shading::phong)
      object.fail(object.find(key), key, "a material's highlight needs \"phong\" in the scene's effects");
  result.reflectivity = object.number("reflectivity", 0.4, 0.0, 1.0);
  result.shininess = object.number("shininess", 32.0, 1.0, 10000.0);
  result.transform.translate = object.vector3("translate", dvec3(0), -kMaxCoordinate, kMaxCoordinate);
  result.transform.rotateDegrees = object.vector3("rotate", dvec3(0), -36000, 36000);
  result.transform.scale = object.vector3("scale", dvec3(1), 1e-9, kMaxCoordinate, true);
  if (const toml::table* copies = object.table("copies")) {
    TableReader reader(*copies, object.keyPath("copies"), object.file());
    result.instancing = readInstancing(reader);
  }
  object.finish(keys);
  scene.objects.push_back(std::move(result));
}

// The effects list, and the settings tables of the effects that have them; a table
// for an effect the list does not name is an error (it would be silently ignored).
void readEffects(TableReader& reader, Scene& scene) {
  Effects& effects = scene.effects;
  std::vector<std::string> known;
  for (const EffectName& effect : effectNames()) known.push_back(effect.name);
  const std::vector<std::string> shadings(known.begin(), known.begin() + 4);
  std::set<std::string> listed;
  if (const toml::array* list = reader.array("effects"))
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::node* node = list->get(i);
      const auto name = node->value<std::string>();
      const std::string key = "effects[" + std::to_string(i) + "]";
      if (!name || std::find(known.begin(), known.end(), *name) == known.end())
        reader.fail(node, key, "expected one of " + TableReader::join(known) + ", got " + TableReader::describe(*node));
      if (!listed.insert(*name).second) reader.fail(node, key, *name + " is listed twice");
      const auto shading = std::find(shadings.begin(), shadings.end(), *name);
      if (shading == shadings.end()) continue;
      if (std::any_of(shadings.begin(), shadings.end(), [&](const std::string& other) { return other != *name && listed.count(other); }))
        reader.fail(node, key, "only one shading effect (" + TableReader::join(shadings) + ") may be listed");
      effects.shading = static_cast<Shading>(shading - shadings.begin());
    }
  effects.shadows = listed.count("shadows") > 0;
  effects.transparency = listed.count("transparency") > 0;
  effects.fog = listed.count("fog") > 0;
  effects.outline = listed.count("outline") > 0;
  if (effects.shadows && !effects.lit())
    reader.fail(reader.find("effects"), "effects", "shadows need a lit shading effect (flat, lambert or phong) to darken");

  const auto settings = [&](const std::string& effect) -> std::optional<TableReader> {
    const toml::table* table = reader.table(effect);
    if (!table) return std::nullopt;
    if (!listed.count(effect)) reader.fail(table, effect, "settings for an effect the scene does not list; add \"" + effect + "\" to effects");
    return TableReader(*table, effect, reader.file());
  };
  if (auto shadows = settings("shadows")) {
    effects.shadow.resolution = shadows->integer("resolution", effects.shadow.resolution, 1, kMaxShadowMapSide);
    effects.shadow.biasTexels = shadows->number("bias", effects.shadow.biasTexels, 0.0, 1e6);
    shadows->finish({"resolution", "bias"});
  }
  effects.fogSettings.color = scene.background;
  effects.fogSettings.end = scene.camera.far;
  if (auto fog = settings("fog")) {
    FogSettings& f = effects.fogSettings;
    const std::string kind = fog->choice("kind", "linear", {"linear", "exponential"});
    f.kind = kind == "linear" ? FogSettings::Kind::linear : FogSettings::Kind::exponential;
    if (f.kind == FogSettings::Kind::linear) {
      f.start = fog->number("start", 0.0, 0.0, kMaxCoordinate);
      f.end = fog->number("end", scene.camera.far, 0.0, kMaxCoordinate);
      if (!(f.end > f.start)) fog->fail(fog->find("end"), "end", "must be greater than start");
    } else {
      f.density = fog->number("density", f.density, 0.0, kMaxCoordinate);
    }
    f.color = fog->color("color", f.color);
    if (f.kind == FogSettings::Kind::linear)
      fog->finish({"kind", "start", "end", "color"});
    else
      fog->finish({"kind", "density", "color"});
  }
  if (auto outline = settings("outline")) {
    effects.outlineSettings.color = outline->color("color", effects.outlineSettings.color);
    effects.outlineSettings.creaseDegrees = outline->number("crease_angle", effects.outlineSettings.creaseDegrees, 0.0, 180.0);
    outline->finish({"color", "crease_angle"});
  }
}

// "(1, 2.5, -3)", for messages.
std::string pointText(const dvec3& p) {
  std::ostringstream text;
  text << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return text.str();
}

void readCell(TableReader& cell, std::size_t index, Scene& scene) {
  Cell result;
  const toml::source_region source = cell.find("name") ? cell.find("name")->source() : toml::source_region{};
  result.name = cell.string("name");
  if (result.name.empty()) cell.fail(cell.find("name"), "name", "must not be empty");
  for (const Cell& other : scene.cells)
    if (other.name == result.name) cell.fail(cell.find("name"), "name", "\"" + result.name + "\" names two cells; expected each name once");
  result.from = cell.vector3("from", std::nullopt, -kMaxCoordinate, kMaxCoordinate);
  result.to = cell.vector3("to", std::nullopt, -kMaxCoordinate, kMaxCoordinate);
  cell.finish({"name", "from", "to"});
  for (int axis = 0; axis < 3; ++axis)
    if (!(result.from[axis] < result.to[axis])) cell.fail(cell.find("to"), "to", "must exceed from on every axis (a cell is a box with volume)");
  // Cells must not overlap: a point in two would be in two places of the level at once.
  for (const Cell& other : scene.cells) {
    bool overlap = true;
    for (int axis = 0; axis < 3; ++axis) overlap = overlap && result.from[axis] < other.to[axis] && other.from[axis] < result.to[axis];
    if (overlap) cell.fail(cell.find("from"), "from", "cell \"" + result.name + "\" overlaps cell \"" + other.name + "\"; expected cells that at most touch");
  }
  result.where = cell.file().string() + ":" + std::to_string(source.begin.line) + ":" + std::to_string(source.begin.column) +
                 ": cells[" + std::to_string(index) + "] \"" + result.name + "\"";
  scene.cells.push_back(std::move(result));
}

// The polygon of a portal: its corners, or an axis-aligned rectangle by two corners.
std::vector<dvec3> readPortalPolygon(TableReader& portal) {
  if (portal.has("polygon")) {
    if (portal.has("from") || portal.has("to"))
      portal.fail(portal.find("from") ? portal.find("from") : portal.find("to"), "from", "give either polygon or from and to, not both");
    const toml::array* corners = portal.array("polygon");
    std::vector<dvec3> polygon;
    for (std::size_t i = 0; i < corners->size(); ++i) {
      const toml::array* corner = corners->get(i)->as_array();
      const auto isCoordinate = [&](std::size_t axis) {
        const toml::node* node = corner->get(axis);
        return node->is_number() && std::abs(*node->value<double>()) <= kMaxCoordinate;
      };
      if (!corner || corner->size() != 3 || !isCoordinate(0) || !isCoordinate(1) || !isCoordinate(2))
        portal.fail(corners->get(i), "polygon[" + std::to_string(i) + "]",
                    "expected an array of 3 numbers in [-1e12, 1e12], got " + TableReader::describe(*corners->get(i)));
      polygon.emplace_back(*corner->get(0)->value<double>(), *corner->get(1)->value<double>(), *corner->get(2)->value<double>());
    }
    if (polygon.size() < 3) portal.fail(portal.find("polygon"), "polygon", "expected at least 3 corners, got " + std::to_string(polygon.size()));
    return polygon;
  }
  const dvec3 from = portal.vector3("from", std::nullopt, -kMaxCoordinate, kMaxCoordinate);
  const dvec3 to = portal.vector3("to", std::nullopt, -kMaxCoordinate, kMaxCoordinate);
  int flat = -1, flats = 0;
  for (int axis = 0; axis < 3; ++axis)
    if (from[axis] == to[axis]) flat = axis, ++flats;
  if (flats != 1)
    portal.fail(portal.find("to"), "to", "expected a rectangle: from and to equal on exactly one axis (the portal's plane), got " +
                                             std::to_string(flats));
  const int u = (flat + 1) % 3, v = (flat + 2) % 3;
  std::vector<dvec3> polygon(4, from);
  polygon[1][u] = to[u];
  polygon[2][u] = to[u], polygon[2][v] = to[v];
  polygon[3][v] = to[v];
  return polygon;
}

// A portal joins two cells through the face they share: its plane is that face's, its
// corners lie within it, and it is convex with an area (a line of sight crosses it once).
void readPortal(TableReader& portal, std::size_t index, Scene& scene) {
  Portal result;
  const toml::array* names = portal.array("cells");
  const auto cellIndex = [&](std::size_t i) -> std::uint32_t {
    const auto name = names->get(i)->value<std::string>();
    for (std::size_t c = 0; name && c < scene.cells.size(); ++c)
      if (scene.cells[c].name == *name) return static_cast<std::uint32_t>(c);
    portal.fail(names->get(i), "cells[" + std::to_string(i) + "]",
                name ? "no cell is named \"" + *name + "\"; expected the name of a [[cells]] table" : "expected a cell's name");
  };
  if (!names || names->size() != 2) portal.fail(portal.find("cells"), "cells", "missing; expected the names of the 2 cells it joins");
  std::uint32_t a = cellIndex(0), b = cellIndex(1);
  if (a == b) portal.fail(names, "cells", "joins cell \"" + scene.cells[a].name + "\" to itself; expected two different cells");
  result.polygon = readPortalPolygon(portal);
  portal.finish({"cells", "polygon", "from", "to"});
  // The face the two boxes share: touching on one axis, overlapping with area on the others.
  const Cell* first = &scene.cells[a];
  const Cell* second = &scene.cells[b];
  int axis = -1;
  for (int k = 0; k < 3; ++k) {
    if (first->to[k] == second->from[k]) axis = k;
    if (second->to[k] == first->from[k]) axis = k, std::swap(a, b), std::swap(first, second);
    if (axis >= 0) break;
  }
  dvec3 lo = glm::max(first->from, second->from), hi = glm::min(first->to, second->to);
  bool share = axis >= 0;
  for (int k = 0; share && k < 3; ++k) share = k == axis || lo[k] < hi[k];
  if (!share)
    portal.fail(names, "cells", "cells \"" + first->name + "\" and \"" + second->name +
                                    "\" share no face; a portal joins two cells whose boxes touch along a face");
  result.cells[0] = a, result.cells[1] = b;
  result.axis = axis;
  result.at = first->to[axis];
  lo[axis] = hi[axis] = result.at;
  // Corners written as decimals may miss the face by a rounding: within 1e-9 of the
  // level's size they are moved onto it, beyond that they are refused.
  const double tolerance = 1e-9 * std::max({1.0, glm::length(glm::abs(first->from) + glm::abs(second->to))});
  const char* axes = "xyz";
  for (std::size_t i = 0; i < result.polygon.size(); ++i) {
    dvec3& corner = result.polygon[i];
    for (int k = 0; k < 3; ++k) {
      if (corner[k] < lo[k] - tolerance || corner[k] > hi[k] + tolerance) {
        std::ostringstream expected;
        expected << axes[axis] << " = " << result.at << " and the other coordinates within the face, " << pointText(lo) << " to "
                 << pointText(hi);
        portal.fail(portal.find(portal.has("polygon") ? "polygon" : "from"), portal.has("polygon") ? "polygon" : "from",
                    "corner " + std::to_string(i) + " " + pointText(corner) + " is not on the boundary of cells \"" + first->name +
                        "\" and \"" + second->name + "\"; expected " + expected.str());
      }
      corner[k] = std::clamp(corner[k], lo[k], hi[k]);
    }
  }
  // Convex, with an area: every corner on the inner side of every edge (or on it),
  // in the plane's own coordinates. (Equal turns alone would pass a star.)
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const std::size_t n = result.polygon.size();
  const auto cross = [&](const dvec3& p, const dvec3& q, const dvec3& r) {
    return (q[u] - p[u]) * (r[v] - p[v]) - (q[v] - p[v]) * (r[u] - p[u]);
  };
  double area = 0;
  for (std::size_t i = 0; i < n; ++i) area += cross(result.polygon[0], result.polygon[i], result.polygon[(i + 1) % n]);
  const char* key = portal.has("polygon") ? "polygon" : "from";
  if (area == 0) portal.fail(portal.find(key), key, "the portal has no area; expected a polygon that opens a way between its cells");
  for (std::size_t i = 0; i < n; ++i)
    for (const dvec3& corner : result.polygon)
      if (cross(result.polygon[i], result.polygon[(i + 1) % n], corner) * area < 0)
        portal.fail(portal.find(key), key, "the polygon is not convex; expected its corners in order around a convex polygon");
  const toml::source_region source = names->source();
  result.where = portal.file().string() + ":" + std::to_string(source.begin.line) + ":" + std::to_string(source.begin.column) +
                 ": portals[" + std::to_string(index) + "]";
  scene.portals.push_back(std::move(result));
}

}  // namespace

const std::vector<EffectName>& effectNames() {
  static const std::vector<EffectName> names = {
      {"none", "shading: each object's own color (the default)"},
      {"flat", "shading: ambient + diffuse with the face normal, one color per triangle under a directional light"},
      {"lambert", "shading: ambient + diffuse with smooth corner normals"},
      {"phong", "shading: lambert + a Blinn-Phong highlight (per object: reflectivity, shininess)"},
      {"shadows", "a shadow map per light view, from the z-buffer ([shadows]: resolution, bias)"},
      {"transparency", "objects may set opacity < 1, blended back to front (painter, or the z-buffer's sorted pass)"},
      {"fog", "colors blended toward the fog by view distance ([fog]: kind, start, end, density, color)"},
      {"outline", "feature edges drawn over the image ([outline]: color, crease_angle)"},
  };
  return names;
}

const char* shadingName(Shading shading) {
  switch (shading) {
    case Shading::none: return "none";
    case Shading::flat: return "flat";
    case Shading::phong: return "phong";
    case Shading::lambert: return "lambert";
  }
  return "?";
}

void checkImageSize(std::int64_t width, std::int64_t height, const std::string& where) {
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide || width * height > kMaxImagePixels)
    throw InputError(where + ": image size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is out of range; expected 1 to " + std::to_string(kMaxImageSide) +
                     " pixels per side and at most 256 Mpixel");
}

std::pair<int, int> parseSize(const std::string& text, const std::string& where) {
  std::smatch match;
  if (!std::regex_match(text, match, std::regex(R"((\d{1,9})x(\d{1,9}))")))
    throw InputError(where + " " + text + ": expected WIDTHxHEIGHT, e.g. 1280x720");
  const long long width = std::stoll(match[1]), height = std::stoll(match[2]);
  checkImageSize(width, height, where + " " + text);
  return {static_cast<int>(width), static_cast<int>(height)};
}

Scene loadScene(const std::filesystem::path& file) {
  if (file.extension() == ".tri") return parseTriangleFile(readInputFile(file, "triangle"), file);
  return parseScene(readInputFile(file, "scene"), file);
}

Scene parseScene(const std::string& text, const std::filesystem::path& file) {
  const toml::table root = parseTomlText(text, file.string());

  Scene scene;
  scene.file = file;
  TableReader reader(root, "", file);
  const std::vector<std::string> kTopLevel = {"image", "camera", "effects", "shadows", "fog",  "outline",
                                              "ambient", "lights", "objects", "cells", "portals"};
  reader.rejectUnknown(kTopLevel);
  static const toml::table kNoTable;
  const toml::table* imageTable = reader.table("image");
  TableReader image(imageTable ? *imageTable : kNoTable, "image", file);
  readImage(image, scene);
  const toml::table* camera = reader.table("camera");
  if (!camera) reader.fail(nullptr, "camera", "missing; expected a [camera] table");
  TableReader cameraReader(*camera, "camera", file);
  readCamera(cameraReader, scene);

  readEffects(reader, scene);
  scene.ambient = reader.number("ambient", 0.15, 0.0, 1.0);

  if (const toml::array* lights = reader.array("lights"))
    for (std::size_t i = 0; i < lights->size(); ++i) {
      const toml::table* light = lights->get(i)->as_table();
      if (!light) reader.fail(lights->get(i), "lights", "expected [[lights]] tables");
      TableReader lightReader(*light, "lights[" + std::to_string(i) + "]", file);
      readLight(lightReader, scene);
    }
  if (scene.effects.lit() && scene.lights.empty())
    reader.fail(nullptr, "effects", std::string(shadingName(scene.effects.shading)) + " shading needs at least one [[lights]] table");

  const toml::array* objects = reader.array("objects");
  if (!objects || objects->empty()) reader.fail(nullptr, "objects", "missing; expected at least one [[objects]] table");
  std::map<std::filesystem::path, std::shared_ptr<const Mesh>> meshCache;
  std::int64_t triangles = 0;
  for (std::size_t i = 0; i < objects->size(); ++i) {
    const toml::table* object = objects->get(i)->as_table();
    if (!object) reader.fail(objects->get(i), "objects", "expected [[objects]] tables");
    TableReader objectReader(*object, "objects[" + std::to_string(i) + "]", file);
    readObject(objectReader, scene, meshCache);
    const SceneObject& added = scene.objects.back();
    triangles += static_cast<std::int64_t>(added.mesh->triangles.size()) * static_cast<std::int64_t>(added.instancing.copyCount());
    if (triangles >= kMaxTriangles)
      objectReader.fail(nullptr, "copies", "the scene exceeds " + std::to_string(kMaxTriangles - 1) +
                                                " triangles (the id image holds 24 bits)");
  }
  if (const toml::array* cells = reader.array("cells"))
    for (std::size_t i = 0; i < cells->size(); ++i) {
      const toml::table* cell = cells->get(i)->as_table();
      if (!cell) reader.fail(cells->get(i), "cells", "expected [[cells]] tables");
      TableReader cellReader(*cell, "cells[" + std::to_string(i) + "]", file);
      readCell(cellReader, i, scene);
    }
  if (const toml::array* portals = reader.array("portals")) {
    if (scene.cells.empty()) reader.fail(portals, "portals", "portals without cells; expected [[cells]] tables for them to join");
    for (std::size_t i = 0; i < portals->size(); ++i) {
      const toml::table* portal = portals->get(i)->as_table();
      if (!portal) reader.fail(portals->get(i), "portals", "expected [[portals]] tables");
      TableReader portalReader(*portal, "portals[" + std::to_string(i) + "]", file);
      readPortal(portalReader, i, scene);
    }
  }
  reader.finish(kTopLevel);
  return scene;
}

}  // namespace hsr
