// One measured configuration (a row of hsr compare's and hsr sweep's tables) and the
// CSV and JSON they write. The columns are documented in README.md ("hsr compare").
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/pipeline.hpp"
#include "renderer/raster/coverage.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/util/markup.hpp"
#include "studies/common.hpp"
#include "studies/measure.hpp"

namespace hsr::studies {

struct ResultRow {
  std::string scene;      // scene file as given
  std::string algorithm;  // registry name
  std::string knobs;      // settings that differ from the defaults, or "defaults"
  std::vector<std::pair<std::string, std::string>> swept;  // hsr sweep: the value of each swept knob
  int width = 0, height = 0;
  std::int64_t triangles = 0;
  int repeats = 0, threads = 0;
  // Seconds, over the timed runs. The algorithm's own cost leads: its visibility passes
  // (culling and visibility; for the reference, its ray casting), then what follows it,
  // the same code for every algorithm (shadow maps, shading, transparency, fog, outline,
  // a line drawing rasterized), then the whole render.
  Timing visibility, effects, time;
  std::int64_t peakBytes = 0;
  SurfaceError error;    // surface algorithms
  bool lines = false;    // a line algorithm: lineError holds its error, `error` is unused
  LineError lineError;
  // A surface algorithm's coverage error (renderer/raster/coverage.hpp) against the exact
  // shares, on an opaque scene: of the shares it gives each pixel where it antialiases,
  // else of its one sample per pixel (each pixel wholly what its center shows).
  std::optional<CoverageError> coverage;
  bool antialiased = false;  // it shares pixels among surfaces: coverage error is what it buys
  // The error hsr sweep plots and ranks by and the contact sheet leads with: line error for
  // a line algorithm, coverage error for an antialiasing one, pixel error for the others.
  double errorValue() const { return lines ? lineError.error : antialiased && coverage ? coverage->mean : error.pixelError; }
  // That error's name: "line error", "coverage error" or "pixel error".
  const char* errorName() const { return lines ? "line error" : antialiased && coverage ? "coverage error" : "pixel error"; }
  std::vector<std::pair<std::string, std::int64_t>> counters;  // the algorithm's key counters
  // Each pass of the pipeline that ran (pipeline::passTimes), over the timed runs.
  std::vector<std::pair<std::string, Timing>> passes;
  bool pareto = false;  // hsr sweep: on the front of (visibility time, error)
  // How the row is named in a warning: "zbuffer variant=scanline on counters.toml".
  std::string label() const;
};

// Fills the row's visibility, effects and per-pass timings from each timed run's
// phase times and wall time.
void splitTimes(ResultRow& row, const std::vector<Stats>& runs, const std::vector<double>& seconds);

// A row for a measured run: what ran, its timing and memory, and the algorithm's key
// counters from the last run (the error is left for the caller to fill in).
template <typename Result>
ResultRow measuredRow(const std::string& scene, const PreparedScene& prepared, const AlgorithmEntry& algorithm,
                      const std::string& knobs, const Measured<Result>& measured, int threads) {
  ResultRow row;
  row.scene = scene;
  row.algorithm = algorithm.name;
  row.knobs = knobs;
  row.width = prepared.width();
  row.height = prepared.height();
  row.triangles = static_cast<std::int64_t>(prepared.triangleCount());
  row.repeats = measured.repeats;
  row.threads = threads;
  row.time = measured.time;
  splitTimes(row, measured.runs, measured.seconds);
  row.peakBytes = measured.peakBytes;
  // A key counter only where the configuration counted it (the z-buffer's block skips,
  // say, exist on its fast path only).
  for (const std::string& counter : algorithm.keyCounters)
    if (measured.lastStats().counted(counter)) row.counters.emplace_back(counter, measured.lastStats().counter(counter));
  return row;
}

// The exact shares' samples per pixel side (traceExactShares): 32 x 32, four times finer
// than the A-buffer's finest mask, whose own subsamples it then does not share.
inline constexpr int kCoverageSamples = 32;
// The truth a scene's configurations are judged by at one size: the reference image, and
// on an opaque scene with a surface algorithm to judge, the exact shares.
struct Truth {
  ReferenceImage image;
  std::optional<PixelShares> shares;
};
// Traces the exact shares into `truth` when the scene is opaque, and says what they cost.
void addExactShares(Truth& truth, const PreparedScene& prepared, int threads);

// Measures one configuration on the prepared scene (at its current size) and its error
// against the reference (for a line algorithm, the line reference of the edges it drew;
// a surface algorithm's coverage error too where the truth has the exact shares); also
// returns the last run's frame (a line algorithm's drawing, rasterized) and, for a line
// algorithm or an antialiasing one, a picture of where it is wrong.
struct MeasuredConfiguration {
  ResultRow row;
  Frame frame;
  std::vector<std::uint8_t> lineErrorMap;  // RGBA8
  LineSet exactLines;                      // a line algorithm's: the exact drawing it was judged by
  std::vector<std::uint8_t> coverageErrorMap;  // RGBA8, an antialiasing algorithm's (coverageHeatMap)
};
MeasuredConfiguration measureConfiguration(const std::string& scene, const PreparedScene& prepared, const Truth& truth,
                                           const pipeline::Configuration& configuration, int repeats, int threads);

// Columns: scene, algorithm, knobs, then one per swept knob (hsr sweep), then the
// measurements; the counters as one "name=value;..." field.
std::string resultsCsv(const std::vector<ResultRow>& rows, const std::vector<std::string>& sweptKnobs);
// An array of objects with the same fields; counters as an object.
std::string resultsJson(const std::vector<ResultRow>& rows);
// The terminal table: one line per row. By default the columns a reader compares first
// (algorithm, knobs, the swept knobs, visibility time, error, wrong pixels, coverage error), narrow
// enough for a terminal; `wide` adds the rest (effects and total time, depth error,
// memory, counters, time per pass), which the CSV and JSON always hold.
std::string resultsTable(const std::vector<ResultRow>& rows, const std::vector<std::string>& sweptKnobs, bool wide);

// What a column of results.csv (and sweep.csv) means, in a sentence, and whether a reader
// compares it first (the report shows those and folds the rest); nothing for a column it
// does not know (a swept knob's, named after the knob).
struct ColumnMeaning {
  std::string meaning;
  bool key = false;
};
const ColumnMeaning* columnMeaning(const std::string& column);

// A CSV field, quoted when it holds a comma, quote or newline (a JSON string literal:
// jsonString, renderer/util/markup.hpp).
std::string csvField(const std::string& text);

// Rows of (column, value) pairs, every row with the same columns, as CSV with a header.
using CsvRow = std::vector<std::pair<std::string, std::string>>;
std::string csvOf(const std::vector<CsvRow>& rows);
// A number in a printf format ("%.4g" unless told).
std::string formatted(double value, const char* format = "%.4g");
// A count with its thousands separated: "1,234,567".
std::string formatCount(std::int64_t value);
// "8.73 [8.70-9.02]": a timing's median and range, each multiplied by `scale` (1e3: seconds to ms).
std::string formattedRange(const Timing& time, double scale = 1, const char* format = "%.2f");

// Marks the rows no other row beats: a row is beaten by one at least as accurate
// (errorValue) whose visibility time is faster or within noise (compareTimings), and
// which is more accurate or surely faster. Within noise, time does not decide.
void markParetoFront(std::vector<ResultRow>& rows);

// The busy-machine warning (warnIfBusy) over the rows' visibility and whole-render timings.
void warnIfBusy(const std::vector<ResultRow>& rows, int repeats);

}  // namespace hsr::studies
