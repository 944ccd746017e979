// The coverage error column of hsr compare and hsr sweep (studies/results.hpp) on a scene
// whose answer is known in closed form: one triangle whose right edge runs down the
// middle of a column of pixels. Each pixel of that column is half covered, exactly (the
// exact shares' 32 samples across it split 16 and 16), so whatever one sample per pixel
// shows there, it is half wrong: a one-sample algorithm's coverage error is 1/2 on each of
// those pixels and 0 elsewhere. The A-buffer's subsamples split evenly too: its error is 0.
#include <gtest/gtest.h>

#include "algorithms/registry.hpp"
#include "studies/results.hpp"
#include "test_support.hpp"

namespace hsr::studies {
namespace {

constexpr int kWidth = 24, kHeight = 12;
constexpr double kEdgeColumn = 10.5;  // pixel x of the triangle's right edge: the middle of column 10

Scene halfCoveredColumn() {
  const double edge = kEdgeColumn - kWidth / 2.0;  // pixelCamera: world x lands on pixel x + width / 2
  return test::sceneOf(test::pixelCamera(kHeight), kWidth, kHeight,
                       {test::triangleMesh({{edge, -1000, 0}, {edge, 1000, 0}, {-1000, 0, 0}})});
}

TEST(CoverageColumn, TheExactSharesSplitTheHalfCoveredColumnEvenlyAndTraceOnlyIt) {
  const Scene scene = halfCoveredColumn();
  const PreparedScene prepared(scene);
  Stats stats;
  const PixelShares shares = traceExactShares(prepared, kCoverageSamples, 1, stats);
  EXPECT_EQ(stats.counter("coverage reference pixels traced in full"), kHeight) << "the survey left the other pixels whole";
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t pixel = std::size_t(y) * kWidth + std::size_t(x);
      std::vector<std::pair<std::uint32_t, double>> expected;
      if (x < 10) expected = {{1, 1.0}};
      else if (x == 10) expected = {{0, 0.5}, {1, 0.5}};
      else expected = {{0, 1.0}};
      const std::vector<std::pair<std::uint32_t, double>> found(shares.shares.begin() + shares.first[pixel],
                                                                shares.shares.begin() + shares.first[pixel + 1]);
      EXPECT_EQ(found, expected) << "pixel " << x << ", " << y;
    }
}

// The survey looks past the image's sides too: an edge 1/16 of a pixel inside the left
// side, between the side and the survey's first points inside, still makes the pixels it
// crosses mixed (2 of each row's 32 points miss the triangle).
TEST(CoverageColumn, AnEdgeHuggingTheImagesSideIsSeen) {
  const double edge = 1.0 / 16 - kWidth / 2.0;
  const Scene scene = test::sceneOf(test::pixelCamera(kHeight), kWidth, kHeight,
                                    {test::triangleMesh({{edge, 1000, 0}, {edge, -1000, 0}, {1000, 0, 0}})});
  const PreparedScene prepared(scene);
  Stats stats;
  const PixelShares shares = traceExactShares(prepared, kCoverageSamples, 1, stats);
  for (int y = 0; y < kHeight; ++y) {
    const std::size_t pixel = std::size_t(y) * kWidth;
    const std::vector<std::pair<std::uint32_t, double>> found(shares.shares.begin() + shares.first[pixel],
                                                              shares.shares.begin() + shares.first[pixel + 1]);
    EXPECT_EQ(found, (std::vector<std::pair<std::uint32_t, double>>{{0, 2.0 / 32}, {1, 30.0 / 32}})) << "row " << y;
  }
}

TEST(CoverageColumn, OneSampleIsHalfWrongOnAHalfCoveredPixelAndTheABufferIsRight) {
  const Scene scene = halfCoveredColumn();
  const PreparedScene prepared(scene);
  Stats stats;
  Truth truth{traceReference(prepared, 1, stats), std::nullopt};
  addExactShares(truth, prepared, 1);
  ASSERT_TRUE(truth.shares);
  int judged = 0;
  for (const AlgorithmEntry& algorithm : algorithms()) {
    if (algorithm.kind != AlgorithmKind::surface) continue;
    const MeasuredConfiguration measured =
        measureConfiguration("half-covered column", prepared, truth, pipeline::configurationOf(algorithm, {}), 1, 1);
    const ResultRow& row = measured.row;
    ASSERT_TRUE(row.coverage) << algorithm.name;
    EXPECT_EQ(row.coverage->mixedPixels, kHeight) << algorithm.name;
    if (row.antialiased) {
      EXPECT_EQ(row.coverage->mean, 0) << algorithm.name << ": its subsamples split the column's pixels evenly too";
      EXPECT_STREQ(row.errorName(), "coverage error");
      EXPECT_EQ(row.errorValue(), row.coverage->mean) << "the headline of an antialiasing algorithm";
    } else {
      EXPECT_EQ(row.coverage->meanOverMixed, 0.5) << algorithm.name;
      EXPECT_DOUBLE_EQ(row.coverage->mean, 0.5 * kHeight / (kWidth * kHeight)) << algorithm.name;
      EXPECT_STREQ(row.errorName(), "pixel error");
    }
    ++judged;
  }
  EXPECT_GE(judged, 7) << "every surface algorithm, the A-buffer among them";
}

// Coplanar faces overlapping tie at every point of the overlap: those pixels are left out
// (as pixel error leaves out the ambiguous ones), and the A-buffer, whichever face it
// keeps there, is then wrong only where more than one thing shows.
TEST(CoverageColumn, TiesAreLeftOutAsAmbiguousPixelsAre) {
  const test::LoadedScene loaded(test::sourcePath("scenes/hard/coplanar.toml"), 96);
  Stats stats;
  Truth truth{traceReference(loaded.prepared, 2, stats), std::nullopt};
  addExactShares(truth, loaded.prepared, 2);  // every point of a tie is decided exactly: the slowest rays
  ASSERT_TRUE(truth.shares);
  ASSERT_FALSE(truth.shares->tied.empty());
  const MeasuredConfiguration measured =
      measureConfiguration("coplanar", loaded.prepared, truth, pipeline::configurationOf(findAlgorithm("abuffer"), {}), 1, 1);
  const CoverageError& error = *measured.row.coverage;
  EXPECT_GT(error.tiedPixels, truth.image.ambiguousPixels / 2) << "the overlaps' pixels";
  const double pixels = double(loaded.prepared.width()) * loaded.prepared.height() - double(error.tiedPixels);
  EXPECT_NEAR(error.mean * pixels, error.meanOverMixed * double(error.mixedPixels), 1e-9) << "no error outside the mixed pixels";
}

TEST(CoverageColumn, ATransparentSceneHasNoCoverageError) {
  Scene scene = halfCoveredColumn();
  scene.effects.transparency = true;
  const PreparedScene prepared(scene);
  Stats stats;
  Truth truth{traceReference(prepared, 1, stats), std::nullopt};
  addExactShares(truth, prepared, 1);
  EXPECT_FALSE(truth.shares) << "an A-buffer's shares there are of colour, not of coverage";
}

}  // namespace
}  // namespace hsr::studies
