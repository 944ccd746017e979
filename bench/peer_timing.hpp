// Timing for the peer programs (mesa_peer, embree_peer): runs interleaved by hand, so
// both sides see the same machine load, summarized by median, min and max.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace hsr::bench {

struct Timing {
  std::vector<double> milliseconds;
  double median() {
    std::sort(milliseconds.begin(), milliseconds.end());
    return milliseconds[milliseconds.size() / 2];
  }
  double min() { return *std::min_element(milliseconds.begin(), milliseconds.end()); }
  double max() { return *std::max_element(milliseconds.begin(), milliseconds.end()); }
};

template <typename Work>
double millisecondsOf(Work&& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace hsr::bench
