// Every frame allocates and frees buffers of the same, frame-sized shapes (clip-space
// vertices, screen triangles, depth buffers: about 25 MB for dragons at 1280x720).
// By default glibc maps blocks above 128 KiB freshly and unmaps them on free, and
// returns the top of the heap to the kernel, so each frame faults every page in
// again: about 6,000 page faults, half the geometry stage's time. Programs that render
// repeatedly (hsr, the benchmarks) call this once at start, so freed memory is kept
// for the next frame instead.
#pragma once

namespace hsr {

void keepFreedMemoryForReuse();

}  // namespace hsr
