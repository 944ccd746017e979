#include "renderer/util/memory.hpp"

#include <malloc.h>

namespace hsr {

void keepFreedMemoryForReuse() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest: blocks up to 32 MiB come from the heap
  mallopt(M_TRIM_THRESHOLD, 1 << 30);   // and stay there when freed
}

}  // namespace hsr
