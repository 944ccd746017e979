#include "renderer/util/memory.hpp"

#if defined(__GLIBC__) && defined(__linux__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#endif

namespace hsr {

#if defined(__GLIBC__) && defined(__linux__)
namespace {

// Asks for huge pages (2 MiB) in the heap's next `reserve` bytes: on the virtual
// machines this suite is measured on, first touching a 4 KiB page costs about 12
// microseconds, so a 1920x1080 frame's buffers (25 MB) took 75 ms to touch on one
// thread, more than the z-buffer's whole pass; on huge pages they take a few. Linux
// gives huge pages only where a program asks for them (transparent_hugepage=madvise,
// Debian's default), so the heap is grown once by `reserve`, marked, and given back to
// malloc: its pages are touched (and so backed) only when used, as before.
void askForHugePagesInTheHeap(std::size_t reserve) {
  constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;
  const auto heapEndBefore = reinterpret_cast<std::uintptr_t>(sbrk(0));
  mallopt(M_TOP_PAD, int(reserve));  // the next growth of the heap takes this much more
  void* volatile growth = std::malloc(kHugePage);  // volatile: a malloc only freed again may be left out
  mallopt(M_TOP_PAD, 128 << 10);  // glibc's default again
  const auto heapEnd = reinterpret_cast<std::uintptr_t>(sbrk(0));
  // Only where the heap grew (another allocator, a sanitizer's, may not use it at all).
  const auto begin = (heapEndBefore + kHugePage - 1) & ~(kHugePage - 1), end = heapEnd & ~(kHugePage - 1);
  if (heapEnd - heapEndBefore >= reserve / 2 && end > begin)
    madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // a hint: refused, it changes nothing
  std::free(growth);
}

}  // namespace
#endif

// glibc's allocator is the one that returns freed memory to the kernel eagerly (header);
// other C libraries keep their own policies, and the bits do not depend on either.
void keepFreedMemoryForReuse() {
#if defined(__GLIBC__) && defined(__linux__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest: blocks up to 32 MiB come from the heap
  mallopt(M_TRIM_THRESHOLD, 1 << 30);   // and stay there when freed
  askForHugePagesInTheHeap(std::size_t(768) << 20);
#endif
}

}  // namespace hsr
