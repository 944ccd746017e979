#include "renderer/util/memory.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace hsr {

// glibc's allocator is the one that returns freed memory to the kernel eagerly (header);
// other C libraries keep their own policies, and the bits do not depend on either.
void keepFreedMemoryForReuse() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest: blocks up to 32 MiB come from the heap
  mallopt(M_TRIM_THRESHOLD, 1 << 30);   // and stay there when freed
#endif
}

}  // namespace hsr
