#include "renderer/steps/why.hpp"

#include <algorithm>
#include <numeric>

#include "renderer/util/error.hpp"

namespace hsr {

PixelWitness::PixelWitness(std::vector<Pixel> pixels, int width) : width_(width), pixels_(std::move(pixels)) {
  askedOrder_.resize(pixels_.size());
  std::iota(askedOrder_.begin(), askedOrder_.end(), std::size_t{0});
  std::sort(askedOrder_.begin(), askedOrder_.end(),
            [&](std::size_t a, std::size_t b) { return key(pixels_[a].x, pixels_[a].y) < key(pixels_[b].x, pixels_[b].y); });
  for (const std::size_t asked : askedOrder_) keys_.push_back(key(pixels_[asked].x, pixels_[asked].y));
  HSR_CHECK(std::adjacent_find(keys_.begin(), keys_.end()) == keys_.end());
  histories_.resize(keys_.size());
}

const std::vector<PixelEvent>& PixelWitness::history(std::size_t asked) const {
  const std::size_t place = std::size_t(std::find(askedOrder_.begin(), askedOrder_.end(), asked) - askedOrder_.begin());
  return histories_[place];
}

std::int64_t PixelWitness::events() const {
  std::int64_t total = 0;
  for (const auto& history : histories_) total += std::int64_t(history.size());
  return total;
}

}  // namespace hsr
