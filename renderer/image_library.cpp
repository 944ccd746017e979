#include "renderer/image_library.hpp"

#include <dlfcn.h>

#include <mutex>

#include "renderer/error.hpp"

namespace hsr {

const ImageLibrary& imageLibrary() {
  // The build compiles in where it put the module (HSR_IMAGE_MODULE, CMakeLists.txt).
  static const ImageLibrary* library = nullptr;
  static std::once_flag loaded;
  std::call_once(loaded, [] {
    void* module = dlopen(HSR_IMAGE_MODULE, RTLD_LAZY | RTLD_LOCAL);
    const auto entry = module ? reinterpret_cast<const ImageLibrary* (*)()>(dlsym(module, "hsrImageLibrary")) : nullptr;
    if (entry) library = entry();
  });
  if (!library)
    throw InputError(std::string(HSR_IMAGE_MODULE) +
                     ": cannot load the OpenImageIO module, which EXR files, image comparison and contact sheets need "
                     "(rebuild with bash scripts/build.sh)");
  return *library;
}

}  // namespace hsr
