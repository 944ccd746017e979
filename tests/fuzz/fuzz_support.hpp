// What the fuzz targets share: how fuzz input becomes a scene, and the promises a loaded
// mesh and a loaded scene keep whatever text they came from.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "renderer/scene/mesh.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/util/error.hpp"

namespace hsr::fuzz {

// The input is read as if it were scenes/fuzz.toml, so that the seed corpus (the shipped
// scenes and the hard cases, tests/fuzz/corpus/) finds the models it names.
inline std::optional<Scene> sceneOf(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path kFile = std::filesystem::path(HSR_SOURCE_DIR) / "scenes" / "fuzz.toml";
  try {
    return parseScene(std::string(reinterpret_cast<const char*>(data), size), kFile);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

inline bool finite(const dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The OBJ loader's and the primitives' promises (renderer/scene/obj.hpp, renderer/scene/mesh.hpp):
// triangles, each naming vertices that exist, at finite positions, and corner normals
// for every triangle or none.
inline void checkLoadedMesh(const Mesh& mesh) {
  HSR_CHECK(!mesh.triangles.empty());
  for (const dvec3& position : mesh.positions) HSR_CHECK(finite(position));
  for (const Triangle& triangle : mesh.triangles)
    for (const std::uint32_t corner : triangle) HSR_CHECK(corner < mesh.positions.size());
  HSR_CHECK(mesh.cornerNormals.empty() || mesh.cornerNormals.size() == mesh.triangles.size());
}

// The loader's promises (renderer/scene/scene.hpp): everything it accepts is in range.
inline std::int64_t checkLoadedScene(const Scene& scene) {
  HSR_CHECK(scene.width >= 1 && scene.height >= 1 && scene.width <= kMaxImageSide && scene.height <= kMaxImageSide);
  HSR_CHECK(std::int64_t{scene.width} * scene.height <= kMaxImagePixels);
  HSR_CHECK(!scene.objects.empty());
  HSR_CHECK(!scene.effects.lit() || !scene.lights.empty());
  HSR_CHECK(finite(scene.camera.eye) && finite(scene.camera.target) && finite(scene.camera.up));
  HSR_CHECK(scene.camera.near > 0 && scene.camera.near < scene.camera.far);
  std::int64_t triangles = 0;
  for (const SceneObject& object : scene.objects) {
    HSR_CHECK(object.mesh);
    checkLoadedMesh(*object.mesh);
    HSR_CHECK(object.opacity >= 0 && object.opacity <= 1);
    triangles += std::int64_t(object.mesh->triangles.size()) * std::int64_t(object.instancing.copyCount());
  }
  HSR_CHECK(triangles < kMaxTriangles);
  return triangles;
}

}  // namespace hsr::fuzz
