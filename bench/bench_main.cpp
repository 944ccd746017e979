// The main of every benchmark program here. Frames reuse freed memory as the hsr program
// does (renderer/util/memory.hpp): without it, each iteration would fault a frame's buffers in
// again, and the figures would measure the kernel's page clearing (on city, 60% of the
// geometry stage). The programs register their benchmarks with BENCHMARK, or, when the
// list is built from data, in a registration run before main.
#include <benchmark/benchmark.h>

#include "renderer/util/memory.hpp"

int main(int argc, char** argv) {
  hsr::keepFreedMemoryForReuse();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
