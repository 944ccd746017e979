// Scene: plain data loaded from a TOML file (format in scenes/README.md). Loading
// validates everything once; nothing downstream re-checks the user's input.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/scene/instancing.hpp"
#include "renderer/scene/mesh.hpp"

namespace hsr {

// The exact shape a procedural object's mesh tessellates, in object space, for
// algorithms that test points against it (ray casting's march). A mesh from a file has
// none. A grid or height field is a surface, not a solid: it stands for the solid
// beneath it (object-space y <= f(x, z) over its footprint).
struct Solid {
  enum class Kind { none, box, sphere, cylinder, cone, heightField } kind = Kind::none;
  dvec3 size{0};                 // box: edge lengths
  double radius = 0, height = 0;  // sphere (radius), cylinder and cone (both)
  dvec2 footprint{0};            // height field: extent in x and z, centered
  HeightFunction function;       // height field: f (a grid has amplitude 0)
  glm::ivec2 cells{0};           // height field: its grid's cells in x and z
};

struct SceneObject {
  std::string name;
  std::shared_ptr<const Mesh> mesh;
  Solid solid;
  Transform transform;
  vec3 color{0.8f};
  double opacity = 1;  // below 1 only in scenes that declare transparency
  // Blinn-Phong material (phong shading only): the specular highlight's weight and its
  // sharpness, the exponent of cos(normal, half-vector).
  double reflectivity = 0.4;
  double shininess = 32;
  Instancing instancing;
};

struct Light {
  std::string name;  // "light0", "light1"... unless the scene names it
  enum class Kind { directional, point } kind = Kind::directional;
  dvec3 direction{0, -1, 0};  // directional: the way the light travels
  dvec3 position{0};          // point
  double intensity = 1.0;
};

// Effects a scene declares; the renderer runs the passes these need and no others
// (the pipeline: the plan, and why each pass runs or does not).
enum class Shading {
  none,     // each object's own color: no normals, no lights
  flat,     // ambient + diffuse with the face normal: one color per triangle under a directional light
  lambert,  // ambient + diffuse with smooth corner normals
  phong,    // lambert + a Blinn-Phong specular highlight per material
};

struct ShadowSettings {
  int resolution = 1024;  // texels per side of each shadow map (a point light has six)
  // How far (in the map's texels, measured at the receiver) a point may lie behind the
  // depth the map stored and still count as lit: too little gives acne, too much lets
  // shadows come loose from their casters (peter-panning).
  double biasTexels = 1.5;
};

struct FogSettings {
  enum class Kind { linear, exponential } kind = Kind::linear;
  double start = 0, end = 100;  // linear: clear before start, fully fogged beyond end (view distance)
  double density = 0.05;        // exponential: the fraction left clear is exp(-density * distance)
  vec3 color{0};                // the background's, unless the scene gives one
};

struct OutlineSettings {
  vec3 color{0};
  double creaseDegrees = 30;  // feature edges: boundaries, silhouettes, and creases sharper than this
};

struct Effects {
  Shading shading = Shading::none;
  bool shadows = false;
  ShadowSettings shadow;
  // Objects with opacity below 1 blend over what lies behind them, which needs the
  // surfaces behind a pixel in back-to-front order (the painter, or the z-buffer's
  // sorted pass); the others refuse such scenes.
  bool transparency = false;
  bool fog = false;
  FogSettings fogSettings;
  bool outline = false;
  OutlineSettings outlineSettings;

  bool lit() const { return shading != Shading::none; }
  // Smooth corner normals: lambert and phong interpolate them; flat needs only face normals.
  bool smoothNormals() const { return shading == Shading::lambert || shading == Shading::phong; }
};

// A level divided into cells, for the culling stages portals and pvs
// (algorithms/culling/cells/): each cell an axis-aligned box, no two overlapping; a
// portal a convex polygon in the face two cells share, the only way a line of sight
// passes from one to the other. Whatever else bounds a cell is opaque, and nothing
// outside every cell can be seen from inside one: the level's author promises both, and
// the exact reference checks the promise in the tests.
struct Cell {
  std::string name;
  dvec3 from{0}, to{0};  // the box's low and high corners, from < to on every axis
  std::string where;     // "file:line:column: cells[i]", for messages about it later
};
struct Portal {
  std::uint32_t cells[2] = {0, 0};  // indices into Scene::cells; cells[0]'s box lies below the portal's plane
  int axis = 0;                     // the plane is coordinate `axis` == `at`
  double at = 0;
  std::vector<dvec3> polygon;       // convex, its corners in order
  std::string where;
};

struct Scene {
  std::filesystem::path file;
  int width = 640, height = 480;
  vec3 background{0};
  Camera camera;
  Effects effects;
  double ambient = 0.15;
  std::vector<Light> lights;
  std::vector<SceneObject> objects;
  std::vector<Cell> cells;  // empty: the scene is not divided (the stages portals and pvs refuse it)
  std::vector<Portal> portals;
};

// Limits checked on load (and by the CLI for --size).
inline constexpr int kMaxImageSide = 16384;
inline constexpr std::int64_t kMaxImagePixels = std::int64_t{256} << 20;
inline constexpr std::int64_t kMaxTriangles = std::int64_t{1} << 24;  // ids fit 24-bit RGB
inline constexpr int kMaxShadowMapSide = 8192;

// Throws InputError("file:line:column: key.path: what, expected ...") on any bad input.
Scene loadScene(const std::filesystem::path& file);
// The same for scene text already in memory, read as if it were `file`: messages name
// it, and model paths are relative to its folder.
Scene parseScene(const std::string& text, const std::filesystem::path& file);

// Throws InputError when width x height is outside the limits above; `where` names the source.
void checkImageSize(std::int64_t width, std::int64_t height, const std::string& where);
// "WIDTHxHEIGHT" within those limits; `where` names the option in the error.
std::pair<int, int> parseSize(const std::string& text, const std::string& where);

const char* shadingName(Shading shading);

// Every name a scene's effects list may hold, the shadings first (in Shading's order),
// each with what it asks for (hsr list prints them).
struct EffectName {
  const char* name;
  const char* summary;
};
const std::vector<EffectName>& effectNames();

}  // namespace hsr
