// Heap use of the hsr program, for the "peak memory" column of hsr compare and sweep.
// allocation_meter.cpp replaces the global operator new and delete of the program and
// keeps a running total of the bytes malloc handed out (malloc_usable_size), and its peak.
#pragma once

#include <cstdint>

namespace hsr::studies {

std::int64_t heapBytesInUse();
std::int64_t heapPeakBytes();
void resetHeapPeak();  // peak := bytes in use now

}  // namespace hsr::studies
