// Every frame allocates and frees buffers of the same, frame-sized shapes (clip-space
// vertices, screen triangles, depth buffers: about 25 MB for dragons at 1280x720).
// By default glibc maps blocks above 128 KiB freshly and unmaps them on free, and
// returns the top of the heap to the kernel, so each frame faults every page in
// again: about 6,000 page faults, half the geometry stage's time. Programs that render
// repeatedly (hsr, the benchmarks) call this once at start, so freed memory is kept
// for the next frame instead.
#pragma once

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace hsr {

void keepFreedMemoryForReuse();

// An array of `count` values left uninitialized, for a buffer every value of which is
// written before it is read (std::make_unique_for_overwrite, which not every standard
// library has yet).
template <typename T>
std::unique_ptr<T[]> uninitializedArray(std::size_t count) {
  return std::unique_ptr<T[]>(new T[count]);
}

// An allocator whose containers leave the values they make without arguments (resize,
// the size constructor) uninitialized when T is trivial, as `new T[count]` does: for a
// buffer whose first writes are done on the threads that will use it. A fresh page is
// given to the thread that first touches it, and on one thread the first touch of a
// 1920x1080 frame's 25 MB is a pass's largest serial part (see Frame's constructor).
template <typename T>
struct FirstTouchAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = FirstTouchAllocator<U>;
  };
  FirstTouchAllocator() = default;
  template <typename U>
  FirstTouchAllocator(const FirstTouchAllocator<U>&) noexcept {}

  template <typename U, typename... Arguments>
  void construct(U* at, Arguments&&... arguments) {
    if constexpr (sizeof...(Arguments) == 0)
      ::new (static_cast<void*>(at)) U;  // default-initialized: left as it is for a trivial U
    else
      ::new (static_cast<void*>(at)) U(std::forward<Arguments>(arguments)...);
  }
};

// A frame-sized buffer of pixels, made without a fill (FirstTouchAllocator).
template <typename T>
using PixelBuffer = std::vector<T, FirstTouchAllocator<T>>;

// The bits of `from` read as a To (std::bit_cast, which not every standard library has
// yet; the compilers' builtin under it is in GCC 11 and Clang 9 on).
template <typename To, typename From>
constexpr To bitCast(const From& from) noexcept {
  static_assert(sizeof(To) == sizeof(From), "a bit cast keeps the size");
  return __builtin_bit_cast(To, from);
}

}  // namespace hsr
