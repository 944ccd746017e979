// Deterministic parallel loops. Work items are claimed dynamically, but every item
// writes only its own output, so the result does not depend on the thread count or
// on which thread ran which item: that is how the renderer stays bit-identical.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace hsr {

// 0 means "all cores".
inline int resolveThreadCount(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// Calls body(item, worker) for item in [0, count), worker in [0, threads).
template <typename Body>
void parallelFor(std::size_t count, int threads, Body&& body) {
  const int workers = std::max(1, std::min<int>(resolveThreadCount(threads), static_cast<int>(count)));
  if (workers <= 1) {
    for (std::size_t item = 0; item < count; ++item) body(item, 0);
    return;
  }
  std::atomic<std::size_t> next{0};
  auto work = [&](int worker) {
    for (std::size_t item = next++; item < count; item = next++) body(item, worker);
  };
  std::vector<std::jthread> pool;
  for (int worker = 1; worker < workers; ++worker) pool.emplace_back(work, worker);
  work(0);
}

// Splits [0, count) into `parts` contiguous ranges, as even as possible.
inline std::pair<std::size_t, std::size_t> partRange(std::size_t count, std::size_t parts, std::size_t part) {
  return {count * part / parts, count * (part + 1) / parts};
}

}  // namespace hsr
