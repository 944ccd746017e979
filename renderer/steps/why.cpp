#include "renderer/steps/why.hpp"

#include <algorithm>
#include <numeric>

#include "renderer/util/error.hpp"

namespace hsr {

PixelWitness::PixelWitness(std::vector<Pixel> pixels, int width) : width_(width), pixels_(std::move(pixels)) {
  std::vector<std::size_t> byKey(pixels_.size());
  std::iota(byKey.begin(), byKey.end(), std::size_t{0});
  std::sort(byKey.begin(), byKey.end(), [&](std::size_t a, std::size_t b) { return key(pixels_[a].x, pixels_[a].y) < key(pixels_[b].x, pixels_[b].y); });
  placeOfAsked_.resize(pixels_.size());
  for (std::size_t place = 0; place < byKey.size(); ++place) {
    keys_.push_back(key(pixels_[byKey[place]].x, pixels_[byKey[place]].y));
    placeOfAsked_[byKey[place]] = place;
  }
  HSR_CHECK(std::adjacent_find(keys_.begin(), keys_.end()) == keys_.end());
  histories_.resize(keys_.size());
}

const std::vector<PixelEvent>& PixelWitness::history(std::size_t asked) const { return histories_[placeOfAsked_[asked]]; }

std::int64_t PixelWitness::events() const {
  std::int64_t total = 0;
  for (const auto& history : histories_) total += std::int64_t(history.size());
  return total;
}

}  // namespace hsr
