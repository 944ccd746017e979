// The A-buffer: fragments with coverage masks, listed per pixel in any order, each pixel
// resolved front to back, subsample by subsample.
#include "algorithms/abuffer/abuffer.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <limits>
#include <span>
#include <string>

#include "renderer/raster/plane_depth.hpp"
#include "renderer/raster/screen_triangles.hpp"
#include "renderer/util/conventions.hpp"
#include "renderer/util/memory.hpp"
#include "renderer/util/parallel.hpp"

namespace hsr::abuffer {
namespace {

// One polygon in one pixel: which subsamples it covers (bit sy * k + sx), and the next
// fragment of the pixel's list.
struct Fragment {
  std::uint64_t mask;
  std::uint32_t polygon;  // screen triangle, in the subsamples' geometry
  std::uint32_t next;
};
constexpr std::uint32_t kEndOfList = std::numeric_limits<std::uint32_t>::max();

// The per-pixel lists (Carpenter's linked lists): a head per pixel, into the pool of
// fragments of the band of rows that holds the pixel (step 1 builds each band's on a
// thread of its own).
struct FragmentLists {
  static constexpr int kBandRows = 8;
  PixelBuffer<std::uint32_t> head;
  std::vector<std::vector<Fragment>> pools;  // one per band
  const std::vector<Fragment>& poolOfRow(std::size_t y) const { return pools[y / kBandRows]; }
  std::size_t fragments() const {
    std::size_t count = 0;
    for (const std::vector<Fragment>& pool : pools) count += pool.size();
    return count;
  }
};

// Step 1, for the pixel rows [firstRow, endRow): each polygon that reaches them, in
// submission order, is rasterized at the subsamples' resolution: a covered subsample
// sets its bit in the polygon's fragment in the pixel that holds it, the fragment made
// when the polygon first reaches the pixel. Returns the subsamples covered.
std::int64_t scanConvertBand(const ScreenGeometry& fine, int k, int width, int firstRow, int endRow,
                             std::span<const std::uint32_t> polygons, std::uint32_t* head, std::vector<Fragment>& pool) {
  const std::size_t firstPixel = std::size_t(firstRow) * std::size_t(width), pixels = std::size_t(endRow - firstRow) * std::size_t(width);
  std::fill_n(head + firstPixel, pixels, kEndOfList);
  // The fragment each pixel holds for the polygon being rasterized, found by a stamp
  // rather than by walking the pixel's list.
  std::vector<std::uint32_t> stampedBy(pixels, kEndOfList), fragmentOf(pixels);
  std::int64_t covered = 0;
  for (const std::uint32_t polygon : polygons) {
    const ScreenTriangle& tri = fine.triangles[polygon];
    for (int y = std::max(tri.minY, firstRow * k); y <= std::min(tri.maxY, endRow * k - 1); ++y) {
      int first, last;
      if (!coveredRun(tri, y, tri.minX, tri.maxX + 1, first, last)) continue;
      covered += last - first + 1;
      const std::size_t row = std::size_t(y / k) * std::size_t(width);
      const std::uint64_t rowBits = std::uint64_t(y % k) * std::uint64_t(k);
      for (int x = first; x <= last; ++x) {
        const std::size_t pixel = row + std::size_t(x / k), inBand = pixel - firstPixel;
        if (stampedBy[inBand] != polygon) {
          stampedBy[inBand] = polygon;
          fragmentOf[inBand] = static_cast<std::uint32_t>(pool.size());
          pool.push_back({0, polygon, head[pixel]});
          head[pixel] = fragmentOf[inBand];
        }
        pool[fragmentOf[inBand]].mask |= std::uint64_t{1} << (rowBits + std::uint64_t(x % k));
      }
    }
  }
  return covered;
}

// Step 1 over the image, cut into bands of rows scan-converted on the threads (REYES,
// the renderer Carpenter made the A-buffer for, renders bucket by bucket). A band takes
// the polygons that reach its rows in submission order, so its lists are the same for
// any thread count; a pixel's list may hold its fragments in any order, as the resolve
// sorts them.
FragmentLists buildLists(const ScreenGeometry& fine, int k, int width, int height, int threads, std::int64_t& subsamplesCovered) {
  constexpr int kBandRows = FragmentLists::kBandRows;
  const auto bands = static_cast<std::size_t>((height + kBandRows - 1) / kBandRows);
  const auto bandOf = [&](int fineRow) { return static_cast<std::size_t>(fineRow / k / kBandRows); };
  std::vector<std::vector<std::uint32_t>> reaching(bands);  // the polygons whose rows reach each band
  for (std::uint32_t polygon = 0; polygon < fine.triangles.size(); ++polygon)
    for (std::size_t band = bandOf(fine.triangles[polygon].minY); band <= bandOf(fine.triangles[polygon].maxY); ++band)
      reaching[band].push_back(polygon);

  FragmentLists lists;
  lists.head.resize(std::size_t(width) * std::size_t(height));
  lists.pools.resize(bands);
  std::vector<std::int64_t> covered(bands);
  parallelFor(bands, threads, [&](std::size_t band, int) {
    const int firstRow = int(band) * kBandRows;
    std::vector<Fragment> pool;  // made here: neighbouring bands' pools in `pools` share cache lines
    covered[band] = scanConvertBand(fine, k, width, firstRow, std::min(height, firstRow + kBandRows), reaching[band],
                                    lists.head.data(), pool);
    lists.pools[band] = std::move(pool);
  });
  for (const std::int64_t count : covered) subsamplesCovered += count;
  return lists;
}

// A fragment being resolved: its polygon's depth at the pixel's center as an order key
// (smaller is nearer) and its opacity.
struct Resolving {
  double key;
  std::uint32_t polygon;
  std::uint64_t mask;
  float opacity;
};

// A row's counts, on a cache line of their own: neighbouring rows are often resolved on
// different threads, which would otherwise wait for each other at every pixel's count.
struct alignas(64) Counts {
  std::int64_t mostFragments = 0, partial = 0;
  Counts& operator+=(const Counts& other) {
    mostFragments = std::max(mostFragments, other.mostFragments), partial += other.partial;
    return *this;
  }
};

// hsr why: a pixel asked about, resolved: its fragments front to back (the order the
// resolve takes them in), each with its mask and the subsamples it took, then the surface
// the id image names.
void witnessResolve(const std::vector<Resolving>& fragments, const std::vector<float>& shares, const ScreenGeometry& geometry,
                    const CameraTransform& fine, const DepthOrder& order, int k, std::uint32_t shown, float shownShare,
                    std::vector<PixelEvent>& history) {
  const int samples = k * k;
  for (std::size_t i = 0; i < fragments.size(); ++i) {
    std::string mask;  // the k x k subsamples, rows top to bottom: # covered, . not
    for (int sample = 0; sample < samples; ++sample)
      mask += std::string(sample && sample % k == 0 ? "/" : "") + (fragments[i].mask >> sample & 1 ? "#" : ".");
    char detail[240];
    std::snprintf(detail, sizeof detail, "mask %s: covers %d of %d subsamples; opacity %.3g; its share %.6g", mask.c_str(),
                  std::popcount(fragments[i].mask), samples, double(fragments[i].opacity), double(shares[i]) / samples);
    history.push_back({geometry.triangles[fragments[i].polygon].triangle + 1,
                       "fragment " + std::to_string(i + 1) + " of " + std::to_string(fragments.size()) + " front to back",
                       detail, fine.distanceFromScreenAffine(order.sign * fragments[i].key), false, {}});
  }
  char detail[120];
  std::snprintf(detail, sizeof detail, "the largest share, %.6g of the pixel (the background's is 1 less the shares' sum)",
                double(shownShare));
  history.push_back({shown, "resolved: the id image names the surface with the largest share", detail,
                     std::numeric_limits<double>::quiet_NaN(), true, {}});
}

}  // namespace

void visibility(const VisibilityRequest& request, const Knobs& knobs, Visibility& visibility) {
  const int k = static_cast<int>(knobs.mask);
  Frame& frame = visibility.frame;
  const int width = frame.width, height = frame.height;
  // The subsamples are the pixel centers of an image k times finer: the shared geometry
  // stage and rasterizer, at that resolution, give exact coverage of each.
  const CameraTransform fine(request.view.camera(), width * k, height * k);
  const ScreenGeometry geometry =
      buildScreenTriangles(request.scene, fine, {.submitted = request.triangles}, request.threads, request.stats);
  PhaseTimer timer(request.stats, "fragments");
  std::int64_t subsamplesCovered = 0;
  const FragmentLists lists = buildLists(geometry, k, width, height, request.threads, subsamplesCovered);
  if (request.steps) {
    std::vector<double> perPixel(lists.head.size(), 0);
    for (std::size_t y = 0; y < std::size_t(height); ++y) {
      const std::vector<Fragment>& pool = lists.poolOfRow(y);
      for (std::size_t p = y * std::size_t(width); p < (y + 1) * std::size_t(width); ++p)
        for (std::uint32_t f = lists.head[p]; f != kEndOfList; f = pool[f].next) ++perPixel[p];
    }
    request.steps->record("the fragment lists: " + std::to_string(lists.fragments()) + " fragments, each a polygon's coverage mask in a pixel",
                          heatMapPicture(perPixel, width, height, "fragments"));
  }

  // Step 2: each pixel resolved, front to back at each subsample: a fragment that covers
  // it shows its opacity times what nearer fragments let through there, and leaves the
  // rest. Front to back is each fragment's depth at the pixel's center (Carpenter's one
  // depth per fragment), or with depth=subsample its plane's depth at the subsample (what
  // a supersampled z-buffer compares); a tie goes to the earlier polygon.
  const bool transparency = request.scene.scene().effects.transparency;
  const int samples = k * k;
  const DepthOrder order(fine);
  PixelCoverage coverage;
  coverage.first.resize(frame.pixelCount() + 1);  // filled by the rows: pixel p's count at p + 1, then the offsets
  coverage.first[0] = 0;
  std::vector<std::vector<CoveredSurface>> rowSurfaces(static_cast<std::size_t>(height));
  std::vector<Counts> rowCounts(static_cast<std::size_t>(height));
  parallelFor(static_cast<std::size_t>(height), request.threads, [&](std::size_t y, int) {
    std::vector<Resolving> fragments;
    std::vector<float> shares;
    std::vector<std::pair<double, std::uint32_t>> atSubsample;  // (key, fragment) of those covering it
    const double centerY = (double(y) + 0.5) * k;
    const std::vector<Fragment>& pool = lists.poolOfRow(y);
    for (int x = 0; x < width; ++x) {
      const std::size_t pixel = y * std::size_t(width) + std::size_t(x);
      const double centerX = (double(x) + 0.5) * k;
      fragments.clear();
      for (std::uint32_t f = lists.head[pixel]; f != kEndOfList; f = pool[f].next) {
        const Fragment& fragment = pool[f];
        const ScreenTriangle& tri = geometry.triangles[fragment.polygon];
        const float opacity = transparency ? static_cast<float>(request.scene.instanceOf(tri.triangle).opacity) : 1.0f;
        fragments.push_back({order.sign * tri.depthAt(centerX, centerY), fragment.polygon, fragment.mask, opacity});
      }
      std::sort(fragments.begin(), fragments.end(),
                [](const Resolving& a, const Resolving& b) { return DepthOrder::inFront(a.key, a.polygon, b.key, b.polygon); });
      shares.assign(fragments.size(), 0.0f);
      const bool allOpaque = std::all_of(fragments.begin(), fragments.end(), [](const Resolving& f) { return f.opacity >= 1; });
      if (fragments.size() == 1) {
        // Inside a surface, the common case: one fragment takes its opacity at each subsample it covers.
        shares[0] = fragments[0].opacity * static_cast<float>(std::popcount(fragments[0].mask));
      } else if (allOpaque && knobs.depth == Depth::center) {
        // Opaque, in one order for the whole pixel: each fragment takes the covered
        // subsamples no nearer one has taken, a mask operation.
        std::uint64_t untaken = ~std::uint64_t{0};
        for (std::size_t i = 0; i < fragments.size(); ++i) {
          shares[i] = static_cast<float>(std::popcount(fragments[i].mask & untaken));
          untaken &= ~fragments[i].mask;
        }
      } else {
        // At each subsample, the fragments covering it front to back, until one is opaque.
        for (int sample = 0; sample < samples; ++sample) {
          atSubsample.clear();
          const double sampleX = x * k + sample % k + 0.5, sampleY = double(y) * k + sample / k + 0.5;
          for (std::uint32_t i = 0; i < fragments.size(); ++i)
            if (fragments[i].mask >> sample & 1)
              atSubsample.emplace_back(knobs.depth == Depth::center
                                           ? fragments[i].key
                                           : order.sign * geometry.triangles[fragments[i].polygon].depthAt(sampleX, sampleY),
                                       i);
          const auto inFront = [&](const auto& a, const auto& b) {
            return DepthOrder::inFront(a.first, fragments[a.second].polygon, b.first, fragments[b.second].polygon);
          };
          if (atSubsample.empty()) continue;
          if (allOpaque) {  // only the nearest shows
            shares[std::min_element(atSubsample.begin(), atSubsample.end(), inFront)->second] += 1;
            continue;
          }
          if (knobs.depth == Depth::subsample) std::sort(atSubsample.begin(), atSubsample.end(), inFront);
          float left = 1;
          for (const auto& [key, i] : atSubsample) {
            shares[i] += fragments[i].opacity * left;
            left *= 1 - fragments[i].opacity;
            if (left <= 0) break;
          }
        }
      }
      const std::size_t firstSurface = rowSurfaces[y].size();
      std::uint32_t largest = conventions::kBackgroundId;
      float largestShare = 0, total = 0;
      double largestKey = 0;
      for (std::size_t i = 0; i < fragments.size(); ++i) {
        if (shares[i] <= 0) continue;
        const float share = shares[i] / static_cast<float>(samples);
        total += share;
        const std::uint32_t triangle = geometry.triangles[fragments[i].polygon].triangle;
        rowSurfaces[y].push_back({triangle, share});
        if (share > largestShare) largest = triangle + 1, largestShare = share, largestKey = fragments[i].key;
      }
      // The id and depth images name the surface with the largest share, or the
      // background when it has more than any.
      const bool background = 1 - total > largestShare;
      frame.ids[pixel] = background ? conventions::kBackgroundId : largest;
      if (std::vector<PixelEvent>* history = request.why ? request.why->at(x, int(y)) : nullptr) [[unlikely]]
        witnessResolve(fragments, shares, geometry, fine, order, k, frame.ids[pixel], background ? 1 - total : largestShare, *history);
      frame.depth[pixel] = background ? std::numeric_limits<float>::infinity()
                                      : static_cast<float>(fine.distanceFromScreenAffine(order.sign * largestKey));
      const std::size_t surfaces = rowSurfaces[y].size() - firstSurface;
      rowCounts[y].mostFragments = std::max(rowCounts[y].mostFragments, static_cast<std::int64_t>(fragments.size()));
      rowCounts[y].partial += surfaces > 1 || (surfaces == 1 && total < 1);
      coverage.first[pixel + 1] = static_cast<std::uint32_t>(surfaces);
    }
  });
  // The rows' lists joined in pixel order: each row's surfaces copied into their place,
  // and its pixels' counts turned into where each pixel's surfaces end, on the threads.
  Counts total;
  std::vector<std::uint32_t> rowPlace(rowSurfaces.size() + 1, 0);
  for (std::size_t y = 0; y < rowSurfaces.size(); ++y) {
    rowPlace[y + 1] = rowPlace[y] + static_cast<std::uint32_t>(rowSurfaces[y].size());
    total += rowCounts[y];
  }
  coverage.surfaces.resize(rowPlace.back());
  parallelFor(rowSurfaces.size(), request.threads, [&](std::size_t y, int) {
    std::copy(rowSurfaces[y].begin(), rowSurfaces[y].end(), coverage.surfaces.begin() + std::ptrdiff_t(rowPlace[y]));
    std::uint32_t end = rowPlace[y];
    for (std::size_t pixel = y * std::size_t(width); pixel < (y + 1) * std::size_t(width); ++pixel)
      coverage.first[pixel + 1] = end += coverage.first[pixel + 1];
  });
  if (request.steps) {
    // How far each pixel is from showing one thing: 1 less the largest share (the
    // background's among them): 0 inside a surface, up to 1/2 on a clean edge.
    std::vector<double> mixed(frame.pixelCount());
    for (std::size_t p = 0; p < frame.pixelCount(); ++p) {
      double shares = 0, largest = 0;
      for (std::uint32_t s = coverage.first[p]; s < coverage.first[p + 1]; ++s)
        shares += coverage.surfaces[s].share, largest = std::max(largest, double(coverage.surfaces[s].share));
      mixed[p] = 1 - std::max(largest, 1 - shares);
    }
    request.steps->record("resolved: " + std::to_string(total.partial) + " pixels shared by more than one surface or partly background",
                          heatMapPicture(mixed, width, height, "1 - largest share"));
  }
  visibility.coverage = std::move(coverage);

  request.stats.add("fragments", static_cast<std::int64_t>(lists.fragments()));
  request.stats.add("subsamples covered", subsamplesCovered);
  request.stats.add("most fragments in a pixel", total.mostFragments);
  request.stats.add("pixels with partial coverage", total.partial);
  request.stats.add("fragment bytes", static_cast<std::int64_t>(lists.fragments() * sizeof(Fragment)));
}

AlgorithmEntry entry() {
  AlgorithmEntry entry;
  entry.name = "abuffer";
  entry.summary = "antialiased visibility (Carpenter 1984): per-pixel fragment lists with subsample coverage masks";
  setKnobs(entry, knobTable());
  entry.keyCounters = {"fragments", "pixels with partial coverage", "most fragments in a pixel"};
  entry.studyConfigurations = {{}, {{"mask", "8x8"}}, {{"mask", "2x2"}}};
  entry.takesTriangleSubsets = true;
  entry.resolvesTransparency = true;
  entry.answersWhy = true;
  setVisibility(entry, visibility);
  return entry;
}

}  // namespace hsr::abuffer
