#include "studies/results.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include "renderer/lines/line_drawing.hpp"
#include "renderer/reference/line_reference.hpp"

namespace hsr::studies {
namespace {

std::string number(double value) { return formatted(value, "%.9g"); }

std::string milliseconds(double seconds) { return formatted(seconds * 1e3, "%.4f"); }

// The measured fields, in column order, shared by the CSV and the JSON; "" where a
// field does not apply (CSV: empty, JSON: null).
std::vector<std::pair<std::string, std::string>> measuredFields(const ResultRow& row) {
  const auto surface = [&](std::string value) { return row.lines ? std::string() : value; };
  const auto line = [&](double value) { return row.lines ? number(value) : std::string(); };
  return {
      {"width", std::to_string(row.width)},
      {"height", std::to_string(row.height)},
      {"triangles", std::to_string(row.triangles)},
      {"threads", std::to_string(row.threads)},
      {"repeats", std::to_string(row.repeats)},
      {"visibility_median_ms", milliseconds(row.visibility.median)},
      {"visibility_min_ms", milliseconds(row.visibility.min)},
      {"visibility_max_ms", milliseconds(row.visibility.max)},
      {"effects_median_ms", milliseconds(row.effects.median)},
      {"effects_min_ms", milliseconds(row.effects.min)},
      {"effects_max_ms", milliseconds(row.effects.max)},
      {"time_median_ms", milliseconds(row.time.median)},
      {"time_min_ms", milliseconds(row.time.min)},
      {"time_max_ms", milliseconds(row.time.max)},
      {"pixel_error", surface(number(row.error.pixelError))},
      {"wrong_pixels", surface(std::to_string(row.error.wrongPixels))},
      {"compared_pixels", surface(std::to_string(row.error.comparedPixels))},
      {"ambiguous_pixels", surface(std::to_string(row.error.ambiguousPixels))},
      {"depth_error_mean", surface(number(row.error.depthErrorMean))},
      {"depth_error_max", surface(number(row.error.depthErrorMax))},
      {"coverage_error", row.coverage ? number(row.coverage->mean) : std::string()},
      {"coverage_error_mixed", row.coverage ? number(row.coverage->meanOverMixed) : std::string()},
      {"mixed_pixels", row.coverage ? std::to_string(row.coverage->mixedPixels) : std::string()},
      {"line_error", line(row.lineError.error)},
      {"visible_length_px", line(row.lineError.visibleLength)},
      {"wrongly_drawn_px", line(row.lineError.wronglyDrawn)},
      {"wrongly_hidden_px", line(row.lineError.wronglyHidden)},
      {"peak_memory_bytes", std::to_string(row.peakBytes)},
  };
}

// "name=value;name=value" for the CSV, "name value, name value" for the terminal.
template <typename Value, typename Format>
std::string joined(const std::vector<std::pair<std::string, Value>>& items, const char* between, const char* separator,
                   Format&& format) {
  std::string text;
  for (const auto& [name, value] : items) {
    if (!text.empty()) text += separator;
    text += name;
    text += between;
    text += format(value);
  }
  return text;
}

std::string joinedCounters(const ResultRow& row, const char* between, const char* separator) {
  return joined(row.counters, between, separator, [](std::int64_t value) { return std::to_string(value); });
}

// Each pass's median.
std::string joinedPasses(const ResultRow& row, const char* between, const char* separator, const char* format) {
  return joined(row.passes, between, separator, [&](const Timing& time) { return formatted(time.median * 1e3, format); });
}


}  // namespace

std::string ResultRow::label() const {
  return algorithm + (knobs == "defaults" ? "" : " " + knobs) + " on " + std::filesystem::path(scene).filename().string();
}

void splitTimes(ResultRow& row, const std::vector<Stats>& runs, const std::vector<double>& seconds) {
  std::vector<double> own, after;
  std::vector<std::pair<std::string, std::vector<double>>> passes;
  for (std::size_t run = 0; run < runs.size(); ++run) {
    const std::vector<pipeline::PassTime> times = pipeline::passTimes(runs[run]);
    // The reference runs outside the pipeline: its ray casting is its visibility.
    double visibility = times.empty() ? runs[run].seconds("reference") : 0;
    for (const pipeline::PassTime& pass : times) {
      if (pass.visibility) visibility += pass.seconds;
      auto same = std::find_if(passes.begin(), passes.end(), [&](const auto& p) { return p.first == pass.pass; });
      if (same == passes.end()) same = passes.insert(passes.end(), {pass.pass, {}});
      same->second.push_back(pass.seconds);
    }
    own.push_back(visibility);
    after.push_back(std::max(0.0, seconds[run] - visibility));
  }
  row.visibility = summarize(own);
  row.effects = summarize(after);
  row.passes.clear();
  for (const auto& [pass, times] : passes) row.passes.emplace_back(pass, summarize(times));
}

void addExactShares(Truth& truth, const PreparedScene& prepared, int threads) {
  if (prepared.scene().effects.transparency) return;  // shares of colour, not of coverage: not judged
  Stats stats;
  truth.shares = traceExactShares(prepared, kCoverageSamples, threads, stats);
  std::printf("  exact shares (%d x %d samples per pixel, %s of %s pixels traced in full): %.0f ms\n", kCoverageSamples,
              kCoverageSamples, formatCount(stats.counter("coverage reference pixels traced in full")).c_str(),
              formatCount(std::int64_t(prepared.width()) * prepared.height()).c_str(), stats.seconds("coverage reference") * 1e3);
}

MeasuredConfiguration measureConfiguration(const std::string& scene, const PreparedScene& prepared, const Truth& truth,
                                           const pipeline::Configuration& configuration, int repeats, int threads) {
  const AlgorithmEntry& algorithm = *configuration.algorithm;
  auto measured = measure(repeats, [&](Stats& stats) { return pipeline::render(prepared, configuration, threads, stats); });
  ResultRow row = measuredRow(scene, prepared, algorithm, configuration.knobs.described(), measured, threads);
  if (algorithm.kind == AlgorithmKind::line) {
    Stats referenceStats;
    LineJudgement judgement = algorithm.judgeLines(prepared, configuration.knobs, measured.result.drawing, threads, referenceStats);
    row.lines = true;
    row.lineError = judgement.error;
    return {std::move(row), std::move(measured.result.frame), std::move(judgement.errorMap), std::move(judgement.exact), {}};
  }
  row.error = surfaceError(measured.result.frame, truth.image);
  std::vector<std::uint8_t> coverageErrorMap;
  if (truth.shares) {
    const pipeline::Rendered& rendered = measured.result;
    row.antialiased = rendered.coverage.has_value();
    const PixelShares shares = row.antialiased ? sharesOf(*rendered.coverage) : sharesOfSamples(rendered.frame.ids, row.width, row.height, 1);
    row.coverage = coverageError(shares, *truth.shares);
    if (row.antialiased) coverageErrorMap = coverageHeatMap(shares, *truth.shares, truth.image);
  }
  return {std::move(row), std::move(measured.result.frame), {}, {}, std::move(coverageErrorMap)};
}

std::string resultsCsv(const std::vector<ResultRow>& rows, const std::vector<std::string>& sweptKnobs) {
  const auto line = [](const std::vector<std::string>& fields) {
    std::string text;
    for (const std::string& field : fields) {
      if (!text.empty()) text += ',';
      text += csvField(field);
    }
    return text + '\n';
  };
  std::vector<std::string> heading = {"scene", "algorithm", "knobs"};
  heading.insert(heading.end(), sweptKnobs.begin(), sweptKnobs.end());
  for (const auto& [name, value] : measuredFields(ResultRow{})) heading.push_back(name);
  if (!sweptKnobs.empty()) heading.push_back("pareto");
  heading.push_back("counters");
  heading.push_back("pass_ms");
  std::string csv = line(heading);
  for (const ResultRow& row : rows) {
    std::vector<std::string> fields = {row.scene, row.algorithm, row.knobs};
    for (const auto& [knob, value] : row.swept) fields.push_back(value);
    for (const auto& [name, value] : measuredFields(row)) fields.push_back(value);
    if (!sweptKnobs.empty()) fields.push_back(row.pareto ? "1" : "0");
    fields.push_back(joinedCounters(row, "=", ";"));
    fields.push_back(joinedPasses(row, "=", ";", "%.4f"));
    csv += line(fields);
  }
  return csv;
}

const ColumnMeaning* columnMeaning(const std::string& column) {
  static const std::map<std::string, ColumnMeaning> kMeanings = {
      {"scene", {"the scene file, from the suite's folder for a shipped scene", true}},
      {"algorithm", {"the algorithm's name in the registry (hsr list)", true}},
      {"knobs", {"the knob settings that differ from the defaults (defaults if none; exact for the reference)", true}},
      {"width", {"the image's width in pixels"}},
      {"height", {"the image's height in pixels"}},
      {"triangles", {"the scene's triangles"}},
      {"threads", {"threads the run used (0 = all cores)"}},
      {"repeats", {"timed runs"}},
      {"visibility_median_ms", {"the algorithm's own time per run, median: its culling and visibility passes (the reference's ray casting)", true}},
      {"visibility_min_ms", {"the algorithm's own time, fastest run"}},
      {"visibility_max_ms", {"the algorithm's own time, slowest run"}},
      {"effects_median_ms", {"the passes after visibility (shading, shadows, fog...), the same code for every algorithm, median"}},
      {"effects_min_ms", {"the passes after visibility, fastest run"}},
      {"effects_max_ms", {"the passes after visibility, slowest run"}},
      {"time_median_ms", {"one whole render, median"}},
      {"time_min_ms", {"one whole render, fastest"}},
      {"time_max_ms", {"one whole render, slowest"}},
      {"pixel_error", {"the fraction of the compared pixels whose visible triangle is not the exact reference's", true}},
      {"wrong_pixels", {"pixels whose visible triangle is not the exact reference's", true}},
      {"compared_pixels", {"pixels compared: all but the ambiguous ones"}},
      {"ambiguous_pixels", {"pixels the reference certifies as ties (two surfaces at exactly one distance): no answer is wrong there"}},
      {"depth_error_mean", {"the mean difference from the reference's depth, in scene units"}},
      {"depth_error_max", {"the largest difference from the reference's depth, in scene units"}},
      {"coverage_error", {"the mean over every pixel (but those where the exact shares meet a tie) of how much of it shows something other than the exact shares say (0 to 1): "
                          "of its shares for an antialiasing algorithm, of its one sample per pixel for the others (opaque scenes)", true}},
      {"coverage_error_mixed", {"the coverage error over the mixed pixels alone: those the exact shares show more than one thing in"}},
      {"mixed_pixels", {"pixels the exact shares (the reference at 32 x 32 samples) show more than one thing in"}},
      {"line_error", {"a line algorithm's error: the fraction of the visible length drawn wrong", true}},
      {"visible_length_px", {"the exact drawing's visible length, in pixels"}},
      {"wrongly_drawn_px", {"pixels of line drawn though hidden"}},
      {"wrongly_hidden_px", {"pixels of line hidden though visible"}},
      {"peak_memory_bytes", {"the most heap one timed run held above what was allocated before it"}},
      {"pareto", {"1 on the Pareto front: no other configuration is both at least as accurate and surely faster", true}},
      {"counters", {"the algorithm's key counters, name=value;..."}},
      {"pass_ms", {"each pass's median time in ms, name=ms;..."}},
  };
  const auto found = kMeanings.find(column);
  return found == kMeanings.end() ? nullptr : &found->second;
}

std::string resultsJson(const std::vector<ResultRow>& rows) {
  std::string json = "[";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ResultRow& row = rows[i];
    json += i ? ",\n  {" : "\n  {";
    json += "\"scene\": " + jsonString(row.scene) + ", \"algorithm\": " + jsonString(row.algorithm) +
            ", \"knobs\": " + jsonString(row.knobs);
    if (!row.swept.empty()) {
      json += ", \"swept\": {";
      for (std::size_t k = 0; k < row.swept.size(); ++k) {
        if (k) json += ", ";
        json += jsonString(row.swept[k].first) + ": " + jsonString(row.swept[k].second);
      }
      json += "}, \"pareto\": " + std::string(row.pareto ? "true" : "false");
    }
    for (const auto& [name, value] : measuredFields(row)) json += ", \"" + name + "\": " + (value.empty() ? "null" : value);
    json += ", \"counters\": {";
    for (std::size_t k = 0; k < row.counters.size(); ++k) {
      if (k) json += ", ";
      json += jsonString(row.counters[k].first) + ": " + std::to_string(row.counters[k].second);
    }
    json += "}, \"pass_ms\": {";
    for (std::size_t k = 0; k < row.passes.size(); ++k) {
      if (k) json += ", ";
      json += jsonString(row.passes[k].first) + ": " + formatted(row.passes[k].second.median * 1e3, "%.4f");
    }
    json += "}}";
  }
  return json + "\n]\n";
}

std::string resultsTable(const std::vector<ResultRow>& rows, const std::vector<std::string>& sweptKnobs, bool wide) {
  std::vector<std::vector<std::string>> cells;
  std::vector<std::string> heading = {"algorithm", "knobs"};
  heading.insert(heading.end(), sweptKnobs.begin(), sweptKnobs.end());
  heading.push_back("visibility ms: median [min-max]");
  heading.push_back("error");
  heading.push_back("wrong px");
  heading.push_back("coverage error");
  if (wide)
    for (const char* name : {"+ shading, effects ms", "= total ms", "depth error mean / max", "peak MB", "counters", "median ms per pass"})
      heading.push_back(name);
  cells.push_back(heading);
  for (const ResultRow& row : rows) {
    std::vector<std::string> line = {row.algorithm + (row.pareto ? " *" : ""), row.knobs};
    for (const auto& [knob, value] : row.swept) line.push_back(value);
    line.push_back(formattedRange(row.visibility, 1e3));
    char text[160];
    if (row.lines) {
      std::snprintf(text, sizeof text, "%.4f%% of lines", row.lineError.error * 100);
      line.push_back(text);
      std::snprintf(text, sizeof text, "%.1f of line", row.lineError.wronglyDrawn + row.lineError.wronglyHidden);
      line.push_back(text);
    } else {
      std::snprintf(text, sizeof text, "%.4f%%", row.error.pixelError * 100);
      line.push_back(text);
      line.push_back(std::to_string(row.error.wrongPixels));
    }
    if (row.coverage) {
      std::snprintf(text, sizeof text, "%.4f%%", row.coverage->mean * 100);
      line.push_back(text);
    } else {
      line.push_back("-");
    }
    if (wide) {
      line.push_back(formattedRange(row.effects, 1e3));
      line.push_back(formattedRange(row.time, 1e3));
      if (row.lines) {
        line.push_back("-");
      } else {
        std::snprintf(text, sizeof text, "%.2g / %.2g", row.error.depthErrorMean, row.error.depthErrorMax);
        line.push_back(text);
      }
      std::snprintf(text, sizeof text, "%.1f", double(row.peakBytes) / (1 << 20));
      line.push_back(text);
      line.push_back(joinedCounters(row, " ", ", "));
      line.push_back(joinedPasses(row, " ", ", ", "%.2f"));
    }
    cells.push_back(line);
  }
  std::vector<std::size_t> widths(heading.size(), 0);
  for (const auto& line : cells)
    for (std::size_t c = 0; c < line.size(); ++c) widths[c] = std::max(widths[c], line[c].size());
  std::string table;
  for (const auto& line : cells) {
    std::string text;
    for (std::size_t c = 0; c < line.size(); ++c)
      text += line[c] + (c + 1 < line.size() ? std::string(widths[c] - line[c].size() + 2, ' ') : "");
    table += "  " + text + "\n";
  }
  return table;
}

void markParetoFront(std::vector<ResultRow>& rows) {
  for (ResultRow& row : rows) {
    row.pareto = std::none_of(rows.begin(), rows.end(), [&](const ResultRow& other) {
      const Order time = compareTimings(other.visibility, row.visibility);
      const bool noWorse = time != Order::slower && other.errorValue() <= row.errorValue();
      const bool better = time == Order::faster || other.errorValue() < row.errorValue();
      return noWorse && better;
    });
  }
}

void warnIfBusy(const std::vector<ResultRow>& rows, int repeats) {
  std::vector<std::pair<std::string, Timing>> timings;
  for (const ResultRow& row : rows) {
    timings.emplace_back(row.label() + " (visibility)", row.visibility);
    timings.emplace_back(row.label() + " (total)", row.time);
  }
  warnIfBusy(timings, "--repeat " + std::to_string(std::max(9, 3 * repeats)));
}

std::string formatCount(std::int64_t value) {
  std::string digits = std::to_string(value), text;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i && (digits.size() - i) % 3 == 0) text += ',';
    text += digits[i];
  }
  return text;
}

std::string formatted(double value, const char* format) {
  char text[48];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string formattedRange(const Timing& time, double scale, const char* format) {
  const std::string pattern = std::string(format) + " [" + format + "-" + format + "]";
  char text[128];
  std::snprintf(text, sizeof text, pattern.c_str(), time.median * scale, time.min * scale, time.max * scale);
  return text;
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string csvOf(const std::vector<CsvRow>& rows) {
  std::string text;
  for (std::size_t i = 0; i < rows.front().size(); ++i) {
    if (i > 0) text += ',';
    text += rows.front()[i].first;
  }
  text += "\n";
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i > 0) text += ',';
      text += csvField(row[i].second);
    }
    text += "\n";
  }
  return text;
}

}  // namespace hsr::studies
