// Fuzz target: the OBJ loader (renderer/scene/obj). Whatever the bytes, parseObj returns a mesh
// every face of which names vertices that exist, or throws InputError; anything else (a
// crash, a hang, a sanitizer report, another exception) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "renderer/scene/obj.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    hsr::fuzz::checkLoadedMesh(hsr::parseObj(std::string(reinterpret_cast<const char*>(data), size), "fuzz.obj"));
  } catch (const hsr::InputError&) {
  }
  return 0;
}
