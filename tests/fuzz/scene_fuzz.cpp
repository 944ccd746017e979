// Fuzz target: the scene loader and validator (renderer/scene/scene, with the OBJ loader for
// the models a scene names). Whatever the bytes, parseScene returns a scene that keeps
// every promise of checkLoadedScene, or throws InputError; anything else is a bug.
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (const auto scene = hsr::fuzz::sceneOf(data, size)) hsr::fuzz::checkLoadedScene(*scene);
  return 0;
}
