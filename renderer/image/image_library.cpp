#include "renderer/image/image_library.hpp"

#ifdef HSR_IMAGE_MODULE
#include <dlfcn.h>
#endif

#include <mutex>

#include "renderer/util/error.hpp"

namespace hsr {

const ImageLibrary& imageLibrary() {
#ifdef HSR_IMAGE_MODULE
  // The build compiles in where it put the module (HSR_IMAGE_MODULE, renderer/CMakeLists.txt).
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
#else
  // A build of the core alone (HSR_CORE_ONLY: another target) has no OpenImageIO.
  throw InputError("this build of hsr has no OpenImageIO, which EXR files, GIF steps, image comparison and contact sheets need");
#endif
}

}  // namespace hsr
