// Pixels shared among the surfaces they show: an antialiasing algorithm's answer (the
// A-buffer's), and how well such shares match the exact ones (the reference traced at
// many samples per pixel), for it or for a supersampled z-buffer.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "renderer/util/memory.hpp"

namespace hsr {

// An antialiasing algorithm's answer (Visibility::coverage): each pixel's surfaces and
// their shares of its colour (coverage, times opacity and what nearer surfaces let
// through); the background takes the rest.
struct CoveredSurface {
  std::uint32_t triangle;  // global triangle index
  float share;
};
struct PixelCoverage {
  PixelBuffer<std::uint32_t> first;  // per pixel, into surfaces; one more entry than pixels
  std::vector<CoveredSurface, FirstTouchAllocator<CoveredSurface>> surfaces;
};

// Whether the pixel shows one surface and nothing else: one surface, taking all of it.
bool showsOneSurfaceWhole(const PixelCoverage& coverage, std::size_t pixel);

// Per pixel, what it shows and how much of it: (global triangle index + 1, 0 for the
// background; share of the pixel), the shares of a pixel adding up to 1.
struct PixelShares {
  std::vector<std::uint32_t> first;  // per pixel, into shares; one more entry than pixels
  std::vector<std::pair<std::uint32_t, double>> shares;
  // Exact shares only (traceExactShares): per pixel, 1 where a sample met two or more
  // triangles at exactly its nearest distance, so that its share could go to any of
  // them; empty when none did.
  std::vector<std::uint8_t> tied;
};

// An antialiasing algorithm's shares, the background's added where it takes some.
PixelShares sharesOf(const PixelCoverage& coverage);
// The shares the samples of a k-times finer id image give (width x height the coarse size).
PixelShares sharesOfSamples(std::span<const std::uint32_t> fineIds, int width, int height, int k);
// One pixel's shares from its samples' ids (sorted in place), appended to `shares` in the
// order of the ids: each id's share is the fraction of the samples that show it.
void appendSharesOfSamples(std::span<std::uint32_t> sampleIds, std::vector<std::pair<std::uint32_t, double>>& shares);

// The coverage error of a pixel: half the sum over everything either shows of the
// difference of their shares (the total variation distance: 0 when they agree, 1 when
// they show nothing in common).
double coverageDistance(const PixelShares& measured, const PixelShares& exact, std::size_t pixel);

// Pixels the exact shares mark tied are left out, as pixel error leaves out the
// reference's ambiguous pixels: no share there is wrong.
struct CoverageError {
  double mean = 0;              // over every pixel but the tied
  double meanOverMixed = 0;     // over the pixels the exact shares show more than one thing in (but the tied)
  std::int64_t mixedPixels = 0;
  std::int64_t tiedPixels = 0;
};
CoverageError coverageError(const PixelShares& measured, const PixelShares& exact);

}  // namespace hsr
