// The A-buffer: its coverage masks take the samples a z-buffer supersampled k x k takes;
// against the exact shares (the reference traced at 32 x 32 samples per pixel) its error
// shrinks as the mask grows; transparency comes out the same whatever the order the
// surfaces are submitted in, and matches the exact blend inside surfaces; its id image
// differs from the reference only at pixels more than one thing shows; the same bits on
// any thread count.
#include <gtest/gtest.h>

#include <memory>

#include "renderer/raster/coverage.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

abuffer::Knobs withMask(abuffer::Mask mask, abuffer::Depth depth = abuffer::Depth::subsample) {
  abuffer::Knobs knobs;
  knobs.mask = mask;
  knobs.depth = depth;
  return knobs;
}

struct Answer {
  Visibility visibility;
  Stats stats;
};

Answer resolved(const PreparedScene& scene, abuffer::Mask mask, int threads = 1, abuffer::Depth depth = abuffer::Depth::subsample) {
  Answer answer{{Frame(scene.width(), scene.height()), std::nullopt}, {}};
  test::algorithmOf(abuffer::Knobs{}).visibility({scene, scene.camera(), nullptr, threads, answer.stats},
                                                  test::valuesOf(withMask(mask, depth)), answer.visibility);
  return answer;
}

// The scene at k times its size: its pixel centers are the subsamples of the original.
std::unique_ptr<PreparedScene> finer(const test::LoadedScene& loaded, int k) {
  auto fine = std::make_unique<PreparedScene>(loaded.scene);
  fine->setSize(loaded.prepared.width() * k, loaded.prepared.height() * k);
  return fine;
}

constexpr int kExactSamples = 32;

// The exact shares, as hsr compare and sweep measure coverage error against them: the
// reference at 32 x 32 samples, traced only where a survey finds more than one thing.
PixelShares exactShares(const test::LoadedScene& loaded) {
  Stats stats;
  return traceExactShares(loaded.prepared, kExactSamples, 2, stats);
}

// The same with no survey: every sample of every pixel traced, as a 32 times finer image.
PixelShares everySampleTraced(const test::LoadedScene& loaded) {
  return test::everyPointTraced(loaded.scene, loaded.prepared.width(), loaded.prepared.height(), kExactSamples, 2);
}

// The survey and its proof leave whole only pixels the full trace finds whole: the same
// shares, pixel for pixel, with fewer rays (in all, under half on these small images;
// mixed pixels are fewer, in proportion, at larger sizes).
TEST(ABuffer, TheExactSharesAreEverySampleTracedWithFewerRays) {
  std::int64_t surveyedRays = 0, everySampleRays = 0;
  // The smallest features, then the cases the proof's geometry is hardest on: triangles
  // through the near plane, far planes, coordinates far from the origin, faces through
  // each other and coplanar, and orthographic views (grazing, a huge triangle, shared edges).
  for (const char* name :
       {"scenes/hard/subpixel_strips.toml", "scenes/hard/slivers.toml", "scenes/bunny.toml", "scenes/hard/crossing_blinds.toml",
        "scenes/counters.toml", "scenes/hard/near_plane.toml", "scenes/hard/far_planes.toml", "scenes/hard/large_coordinates.toml",
        "scenes/hard/interpenetrating.toml", "scenes/hard/coplanar.toml", "scenes/hard/grazing.toml", "scenes/hard/huge_triangle.toml",
        "scenes/hard/shared_edges.toml"}) {
    const test::LoadedScene loaded(test::sourcePath(name), 48);
    Stats stats;
    const PixelShares surveyed = traceExactShares(loaded.prepared, kExactSamples, 2, stats);
    const PixelShares full = everySampleTraced(loaded);
    EXPECT_EQ(surveyed.first, full.first) << name;
    EXPECT_EQ(surveyed.shares, full.shares) << name;
    const std::int64_t everySample = std::int64_t(loaded.prepared.width()) * loaded.prepared.height() * kExactSamples * kExactSamples;
    std::printf("%s: %lld of %lld pixels traced in full, %.1f%% of the rays\n", name,
                static_cast<long long>(stats.counter("coverage reference pixels traced in full")),
                static_cast<long long>(loaded.prepared.width()) * loaded.prepared.height(),
                100.0 * double(stats.counter("coverage reference rays")) / double(everySample));
    surveyedRays += stats.counter("coverage reference rays");
    everySampleRays += everySample;
  }
  EXPECT_LT(surveyedRays, everySampleRays / 2);
}

constexpr abuffer::Mask kMasks[] = {abuffer::Mask::twoByTwo, abuffer::Mask::fourByFour, abuffer::Mask::eightByEight};

// Ordered at each subsample (the default), the shares are exactly what a z-buffer sampling
// each subsample on its own finds there, at every pixel: the masks cover the same
// subsamples, and the order is the same comparison.
TEST(ABuffer, TheSharesAreWhatAZBufferSupersampledAtTheSameSubsamplesFinds) {
  for (const char* name : {"scenes/blocks.toml", "scenes/cube.toml", "scenes/hard/cyclic_overlap.toml", "scenes/hard/slivers.toml",
                           "scenes/hard/crossing_blinds.toml", "scenes/hard/interpenetrating.toml"}) {
    const test::LoadedScene loaded(test::sourcePath(name), 96);
    for (const abuffer::Mask mask : kMasks) {
      const int k = static_cast<int>(mask);
      const Answer answer = resolved(loaded.prepared, mask);
      const PixelShares supersampled = sharesOfSamples(test::sampledOneByOne(*finer(loaded, k)).ids, loaded.prepared.width(),
                                                       loaded.prepared.height(), k);
      EXPECT_EQ(coverageError(sharesOf(*answer.visibility.coverage), supersampled).mean, 0) << name << " " << k << "x" << k;
    }
  }
}

// With depth=center (Carpenter's one depth per fragment) the fragments are ordered by
// their depths at the pixel's center, where the supersampled z-buffer compares at each
// subsample: they differ along the crossings of the blinds, and only at pixels where more
// than one thing shows.
TEST(ABuffer, OrderedAtThePixelsCenterTheSharesAreWrongOnlyWhereMoreThanOneThingShows) {
  const test::LoadedScene loaded(test::sourcePath("scenes/hard/crossing_blinds.toml"), 160);
  const Answer answer = resolved(loaded.prepared, abuffer::Mask::fourByFour, 1, abuffer::Depth::center);
  const PixelShares mine = sharesOf(*answer.visibility.coverage);
  const PixelShares supersampled = sharesOfSamples(test::sampledOneByOne(*finer(loaded, 4)).ids, 160, loaded.prepared.height(), 4);
  std::int64_t differing = 0;
  for (std::size_t p = 0; p < loaded.prepared.width() * std::size_t(loaded.prepared.height()); ++p)
    if (coverageDistance(mine, supersampled, p) > 0) {
      ++differing;
      EXPECT_GT(supersampled.first[p + 1] - supersampled.first[p], 1u) << "pixel " << p << " differs but shows one surface";
    }
  EXPECT_GT(differing, 0);
  EXPECT_LT(differing, loaded.prepared.width() * loaded.prepared.height() / 20);
}

// The accuracy the mask buys, against the exact shares: one sample per pixel (the
// z-buffer, every pixel all or nothing), then 2 x 2, 4 x 4, 8 x 8, each better over the
// pixels where more than one thing shows, by at least a third at each step (an edge's
// error falls as 1/k with a k x k grid: measured, blocks 0.098, 0.039, 0.014; counters
// 0.249, 0.129, 0.061).
TEST(ABuffer, TheErrorAgainstTheExactSharesShrinksAsTheMaskGrows) {
  for (const char* name : {"scenes/blocks.toml", "scenes/counters.toml"}) {
    const test::LoadedScene loaded(test::sourcePath(name), 80);
    const PixelShares exact = exactShares(loaded);
    double previous = coverageError(sharesOfSamples(test::sampledOneByOne(loaded.prepared).ids, loaded.prepared.width(),
                                                    loaded.prepared.height(), 1),
                                    exact)
                          .meanOverMixed;
    for (const abuffer::Mask mask : kMasks) {
      const Answer answer = resolved(loaded.prepared, mask);
      const CoverageError error = coverageError(sharesOf(*answer.visibility.coverage), exact);
      EXPECT_LT(error.meanOverMixed, 0.7 * previous) << name << " mask " << int(mask);
      std::printf("%s mask %dx%d: coverage error %.4f over %lld mixed pixels\n", name, int(mask), int(mask), error.meanOverMixed,
                  static_cast<long long>(error.mixedPixels));
      previous = error.meanOverMixed;
    }
    EXPECT_LT(previous, 0.08) << name << ": 8 x 8 within 8% of the exact shares on mixed pixels";
  }
}

// Transparency resolved per subsample, in whatever order the surfaces arrive: the glass
// cycle submitted in the opposite order of objects gives the same colours, bit for bit.
TEST(ABuffer, TransparencyIsTheSameWhateverTheSubmissionOrder) {
  const Scene glass = loadScene(test::sourcePath("scenes/hard/cyclic_glass.toml"));
  Scene reversed = glass;
  std::reverse(reversed.objects.begin(), reversed.objects.end());
  const auto colours = [](const Scene& scene) {
    PreparedScene prepared(scene);
    prepared.setSize(200, 150);
    Stats stats;
    return pipeline::render(prepared, pipeline::configurationOf(findAlgorithm("abuffer"), {}), 1, stats).frame.color;
  };
  EXPECT_EQ(colours(glass), colours(reversed));
}

// Two glass squares over an opaque one, in pixel units: away from every edge, the colours
// are the reference's exact blend, to rounding; across the edges they lie between.
TEST(ABuffer, TransparencyMatchesTheExactBlendAwayFromEdges) {
  const auto square = [](double x0, double y0, double x1, double y1, double z) {
    return test::triangleMesh({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y0, z}, {x1, y1, z}, {x0, y1, z}});
  };
  Scene scene = test::sceneOf(test::pixelCamera(48), 64, 48,
                              {square(-30, -22, 30, 22, -5), square(-20.3, -15.6, 10.2, 10.7, 0), square(-5.4, -20.2, 25.1, 5.3, 1)});
  scene.effects.transparency = true;
  scene.objects[0].color = {0.2f, 0.3f, 0.9f};
  scene.objects[1].color = {0.9f, 0.2f, 0.1f}, scene.objects[1].opacity = 0.5;
  scene.objects[2].color = {0.1f, 0.8f, 0.2f}, scene.objects[2].opacity = 0.4;
  const PreparedScene prepared(scene);
  Stats stats;
  const Frame exact = renderReference(prepared, 2, stats).frame;
  const Frame frame = pipeline::render(prepared, pipeline::configurationOf(findAlgorithm("abuffer"), {}), 1, stats).frame;
  const double edgesX[] = {2, 62, 11.7, 42.2, 26.6, 57.1}, edgesY[] = {2, 46, 13.3, 39.6, 18.7, 44.2};  // pixel coordinates
  std::int64_t compared = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const auto nearAnEdge = [](double center, const double* edges) {
        return std::any_of(edges, edges + 6, [&](double edge) { return std::abs(center - edge) < 1.5; });
      };
      if (nearAnEdge(x + 0.5, edgesX) || nearAnEdge(y + 0.5, edgesY)) continue;
      const std::size_t pixel = std::size_t(y) * 64 + std::size_t(x);
      ++compared;
      for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(frame.color[4 * pixel + c], exact.color[4 * pixel + c], 1) << x << ", " << y;
    }
  EXPECT_GT(compared, 1000);
  EXPECT_GT(stats.counter("pixels with partial coverage"), 0);
}

// The id image names the surface with the largest share; the reference's, the surface at
// the pixel's center. They can differ only where more than one thing shows.
TEST(ABuffer, IdsDifferFromTheReferenceOnlyWhereMoreThanOneThingShows) {
  const test::LoadedScene loaded(test::sourcePath("scenes/counters.toml"), 240);
  Stats stats;
  const ReferenceImage reference = traceReference(loaded.prepared, 2, stats);
  const Answer answer = resolved(loaded.prepared, abuffer::Mask::fourByFour, 2);
  const PixelCoverage& coverage = *answer.visibility.coverage;
  std::int64_t differing = 0;
  for (std::size_t p = 0; p < answer.visibility.frame.pixelCount(); ++p) {
    if (answer.visibility.frame.ids[p] == reference.frame.ids[p]) continue;
    ++differing;
    EXPECT_FALSE(showsOneSurfaceWhole(coverage, p)) << "pixel " << p;
  }
  EXPECT_GT(differing, 0);
  EXPECT_GT(answer.stats.counter("pixels with partial coverage"), differing);
}

// The hard case scenes/hard/subpixel_strips.toml: boards 0.3 pixels wide, 1.37 apart.
// One sample per pixel catches a strip only where a pixel center falls inside it: whole
// pixels and gaps, about the right amount in all (780 pixels of 800.5) but at the wrong
// places (a coverage error of 0.37 on the pixels they reach). The A-buffer gives each
// pixel the strips' share of it: 0.078 at 4 x 4, 0.012 at 8 x 8, and their area to within
// a pixel.
TEST(ABufferHardCase, StripsNarrowerThanAPixelGetTheirShare) {
  const test::LoadedScene loaded(test::sourcePath("scenes/hard/subpixel_strips.toml"));
  const PixelShares exact = exactShares(loaded);
  const auto stripsArea = [&](const PixelShares& shares) {
    double area = 0;
    const std::uint32_t wallFirst = static_cast<std::uint32_t>(30 * 12);  // triangles of the 30 strips come first, 12 each
    for (const auto& [id, share] : shares.shares) area += id != conventions::kBackgroundId && id - 1 < wallFirst ? share : 0;
    return area;
  };
  const double exactArea = stripsArea(exact);
  const PixelShares oneSample =
      sharesOfSamples(test::sampledOneByOne(loaded.prepared).ids, loaded.prepared.width(), loaded.prepared.height(), 1);
  const CoverageError aliased = coverageError(oneSample, exact);
  for (const abuffer::Mask mask : {abuffer::Mask::fourByFour, abuffer::Mask::eightByEight}) {
    const PixelShares shares = sharesOf(*resolved(loaded.prepared, mask).visibility.coverage);
    const CoverageError error = coverageError(shares, exact);
    std::printf("subpixel strips, mask %dx%d: error %.3f on %lld mixed pixels (one sample: %.3f); strips' area %.1f of %.1f pixels (one sample: %.1f)\n",
                int(mask), int(mask), error.meanOverMixed, static_cast<long long>(error.mixedPixels), aliased.meanOverMixed,
                stripsArea(shares), exactArea, stripsArea(oneSample));
    EXPECT_LT(error.meanOverMixed, (mask == abuffer::Mask::fourByFour ? 0.3 : 0.1) * aliased.meanOverMixed) << int(mask);
    EXPECT_NEAR(stripsArea(shares), exactArea, 0.01 * exactArea) << int(mask);
  }
  EXPECT_GT(aliased.meanOverMixed, 0.3) << "one sample per pixel puts the strips in the wrong places";
}

TEST(ABuffer, SameBitsAndCountersOnAnyThreadCount) {
  const test::LoadedScene loaded(test::sourcePath("scenes/trees.toml"), 200);
  const Answer one = resolved(loaded.prepared, abuffer::Mask::fourByFour, 1);
  for (const int threads : {2, 3}) {
    const Answer many = resolved(loaded.prepared, abuffer::Mask::fourByFour, threads);
    EXPECT_EQ(one.visibility.frame.ids, many.visibility.frame.ids);
    EXPECT_TRUE(test::sameDepthBits(one.visibility.frame, many.visibility.frame));
    EXPECT_EQ(one.visibility.coverage->first, many.visibility.coverage->first);
    ASSERT_EQ(one.visibility.coverage->surfaces.size(), many.visibility.coverage->surfaces.size());
    for (std::size_t s = 0; s < one.visibility.coverage->surfaces.size(); ++s) {
      EXPECT_EQ(one.visibility.coverage->surfaces[s].triangle, many.visibility.coverage->surfaces[s].triangle);
      EXPECT_EQ(one.visibility.coverage->surfaces[s].share, many.visibility.coverage->surfaces[s].share);
    }
    for (const std::string& counter : one.stats.counterNames()) EXPECT_EQ(one.stats.counter(counter), many.stats.counter(counter)) << counter;
  }
}

}  // namespace
}  // namespace hsr
