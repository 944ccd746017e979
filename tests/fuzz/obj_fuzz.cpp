// Fuzz target: the OBJ loader (renderer/obj). Whatever the bytes, parseObj returns a mesh
// every face of which names vertices that exist, or throws InputError; anything else (a
// crash, a hang, a sanitizer report, another exception) is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "renderer/error.hpp"
#include "renderer/obj.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const hsr::Mesh mesh = hsr::parseObj(text, "fuzz.obj");
    HSR_CHECK(!mesh.triangles.empty());
    for (const hsr::dvec3& position : mesh.positions)
      HSR_CHECK(std::isfinite(position.x) && std::isfinite(position.y) && std::isfinite(position.z));
    for (const hsr::Triangle& triangle : mesh.triangles)
      for (const std::uint32_t corner : triangle) HSR_CHECK(corner < mesh.positions.size());
    HSR_CHECK(mesh.cornerNormals.empty() || mesh.cornerNormals.size() == mesh.triangles.size());
  } catch (const hsr::InputError&) {
  }
  return 0;
}
