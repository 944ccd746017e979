#include "renderer/raster/coverage.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace hsr {

bool showsOneSurfaceWhole(const PixelCoverage& coverage, std::size_t pixel) {
  return coverage.first[pixel + 1] - coverage.first[pixel] == 1 && coverage.surfaces[coverage.first[pixel]].share >= 1;
}

PixelShares sharesOf(const PixelCoverage& coverage) {
  PixelShares shares;
  shares.first.push_back(0);
  for (std::size_t p = 0; p + 1 < coverage.first.size(); ++p) {
    double total = 0;
    for (std::uint32_t s = coverage.first[p]; s < coverage.first[p + 1]; ++s) {
      shares.shares.emplace_back(coverage.surfaces[s].triangle + 1, coverage.surfaces[s].share);
      total += coverage.surfaces[s].share;
    }
    if (total < 1 - 1e-6) shares.shares.emplace_back(0, 1 - total);  // float shares: a remainder below that is their rounding
    shares.first.push_back(static_cast<std::uint32_t>(shares.shares.size()));
  }
  return shares;
}

void appendSharesOfSamples(std::span<std::uint32_t> sampleIds, std::vector<std::pair<std::uint32_t, double>>& shares) {
  std::sort(sampleIds.begin(), sampleIds.end());
  const double perSample = 1.0 / double(sampleIds.size());
  for (std::size_t i = 0; i < sampleIds.size();) {
    std::size_t same = i;
    while (same < sampleIds.size() && sampleIds[same] == sampleIds[i]) ++same;
    shares.emplace_back(sampleIds[i], double(same - i) * perSample);
    i = same;
  }
}

PixelShares sharesOfSamples(std::span<const std::uint32_t> fineIds, int width, int height, int k) {
  PixelShares result;
  result.first.reserve(std::size_t(width) * std::size_t(height) + 1);
  result.first.push_back(0);
  std::vector<std::uint32_t> samples(std::size_t(k) * std::size_t(k));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      for (int sy = 0; sy < k; ++sy)
        for (int sx = 0; sx < k; ++sx)
          samples[std::size_t(sy * k + sx)] = fineIds[std::size_t(y * k + sy) * std::size_t(width * k) + std::size_t(x * k + sx)];
      appendSharesOfSamples(samples, result.shares);
      result.first.push_back(static_cast<std::uint32_t>(result.shares.size()));
    }
  return result;
}

double coverageDistance(const PixelShares& measured, const PixelShares& exact, std::size_t pixel) {
  std::map<std::uint32_t, double> difference;
  for (std::uint32_t s = measured.first[pixel]; s < measured.first[pixel + 1]; ++s) difference[measured.shares[s].first] += measured.shares[s].second;
  for (std::uint32_t s = exact.first[pixel]; s < exact.first[pixel + 1]; ++s) difference[exact.shares[s].first] -= exact.shares[s].second;
  double sum = 0;
  for (const auto& [id, d] : difference) sum += std::abs(d);
  return sum / 2;
}

CoverageError coverageError(const PixelShares& measured, const PixelShares& exact) {
  CoverageError error;
  const std::size_t pixels = exact.first.size() - 1;
  double mixedSum = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    if (!exact.tied.empty() && exact.tied[p]) {
      ++error.tiedPixels;
      continue;
    }
    const double distance = coverageDistance(measured, exact, p);
    error.mean += distance;
    if (exact.first[p + 1] - exact.first[p] > 1) mixedSum += distance, ++error.mixedPixels;
  }
  error.mean /= double(std::max<std::int64_t>(std::int64_t(pixels) - error.tiedPixels, 1));
  error.meanOverMixed = error.mixedPixels ? mixedSum / double(error.mixedPixels) : 0;
  return error;
}

}  // namespace hsr
