// hsr sweep: one algorithm over the cross product of knob values (or, with --scale,
// over growing triangle counts or resolutions), each configuration timed and measured
// against the exact reference, written as CSV and JSON and plotted.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/geometry/camera.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/util/error.hpp"
#include "studies/common.hpp"
#include "studies/interrupt.hpp"
#include "studies/plot.hpp"
#include "studies/results.hpp"
#include "studies/studies.hpp"

namespace hsr::studies {
namespace {

constexpr const char* kSizeKnob = "size";  // not an algorithm's knob: the image resolution
constexpr std::size_t kLabelledPoints = 12;  // a sweep plot names every point up to this many

struct Axis {
  std::string name;
  std::vector<std::string> values;
};

// The settings every configuration of the sweep shares (--variant).
KnobSettings fixedSettings(const SweepOptions& options) {
  if (options.variant.empty()) return {};
  return {{"variant", options.variant}};
}

std::vector<Axis> parseAxes(const AlgorithmEntry& algorithm, const SweepOptions& options) {
  std::vector<Axis> axes;
  std::set<std::string> seen;
  std::vector<std::string> sweptVariants;
  for (const std::string& text : options.knobs) {
    const auto [name, list] = parseKnobSetting(text, "--knob");
    if (!seen.insert(name).second) throw InputError("--knob " + text + ": " + name + " is swept twice; give one list");
    if (name == "variant" && !options.variant.empty())
      throw InputError("--knob " + text + ": the variant is already fixed by --variant " + options.variant);
    axes.push_back({name, splitList(list, "--knob " + name + "=")});
    if (name == "variant") sweptVariants = axes.back().values;
  }
  for (const Axis& axis : axes)
    for (const std::string& value : axis.values) {
      if (axis.name == kSizeKnob) {
        parseSize(value, "--knob size:");
        continue;
      }
      // A knob of some variants is checked with one of them when the variant is swept
      // (the other variants' configurations leave it out).
      KnobSettings settings = fixedSettings(options);
      const KnobSpec* knob = findKnob(algorithm, axis.name);
      if (knob && axis.name != "variant" && !sweptVariants.empty()) {
        const auto fitting = std::find_if(sweptVariants.begin(), sweptVariants.end(),
                                          [&](const std::string& variant) { return knob->appliesTo(variant); });
        settings.emplace_back("variant", fitting != sweptVariants.end() ? *fitting : sweptVariants.front());
      }
      settings.emplace_back(axis.name, value);
      resolveKnobs(algorithm, settings);  // throws for an unknown knob or value
    }
  return axes;
}

// Every combination of the axes' values, the first axis varying slowest.
std::vector<std::vector<std::pair<std::string, std::string>>> crossProduct(const std::vector<Axis>& axes) {
  std::vector<std::vector<std::pair<std::string, std::string>>> combinations = {{}};
  for (const Axis& axis : axes) {
    std::vector<std::vector<std::pair<std::string, std::string>>> grown;
    for (const auto& partial : combinations)
      for (const std::string& value : axis.values) {
        grown.push_back(partial);
        grown.back().emplace_back(axis.name, value);
      }
    combinations = std::move(grown);
  }
  return combinations;
}

std::string dataBlock(const std::string& name, const std::vector<std::string>& lines) {
  std::string text = "$" + name + " << EOD\n";
  for (const std::string& line : lines) text += line + "\n";
  return text + "EOD\n";
}

std::string quotedLabel(std::string text) {
  for (char& c : text)
    if (c == '"' || c == '\'') c = ' ';
  return "\"" + text + "\"";
}

// Writes stem.csv, stem.json and the plot (stem.png, .svg, .gp) into the folder, all or none.
void writeResults(const std::filesystem::path& folder, const std::string& stem, const std::vector<ResultRow>& rows,
                  const std::vector<std::string>& sweptKnobs, const std::string& plotBody) {
  OutputFiles files;
  files.addText(folder / (stem + ".csv"), resultsCsv(rows, sweptKnobs));
  files.addText(folder / (stem + ".json"), resultsJson(rows));
  addPlot(files, folder, stem, plotBody);
  files.commit();
  std::printf("wrote %s.csv, .json, .png, .svg and .gp in %s\n", stem.c_str(), folder.string().c_str());
}

int knobSweep(const SweepOptions& options, const AlgorithmEntry& algorithm, const std::vector<Axis>& axes) {
  LoadedScene scene = loadPrepared(options.scene, options.size);
  const int defaultWidth = scene.prepared->width(), defaultHeight = scene.prepared->height();

  // Every configuration is checked (a knob combination, an over-budget size) before
  // the first render.
  struct Planned {
    pipeline::Configuration configuration;
    std::pair<int, int> size;
    std::string label;
    std::vector<std::pair<std::string, std::string>> swept;  // "-" for a knob the variant does not have
  };
  std::vector<std::string> sweptKnobs;
  for (const Axis& axis : axes) sweptKnobs.push_back(axis.name);
  std::vector<Planned> plan;
  for (const auto& combination : crossProduct(axes)) {
    Planned planned;
    planned.size = {defaultWidth, defaultHeight};
    planned.swept = combination;
    std::string variant = options.variant;
    for (const auto& [name, value] : combination)
      if (name == "variant") variant = value;
    KnobSettings settings = fixedSettings(options);
    for (auto& [name, value] : planned.swept) {
      if (name == kSizeKnob) {
        planned.size = parseSize(value, "--knob size:");
      } else if (const KnobSpec* knob = findKnob(algorithm, name); knob && !variant.empty() && !knob->appliesTo(variant)) {
        value = "-";  // swept for the other variants
        continue;
      } else {
        settings.emplace_back(name, value);
      }
      planned.label += (planned.label.empty() ? "" : " ") + name + "=" + value;
    }
    planned.configuration = pipeline::configurationOf(algorithm, settings);
    // A variant without some swept knobs recurs once per value of them: run it once.
    if (std::any_of(plan.begin(), plan.end(), [&](const Planned& earlier) {
          return earlier.size == planned.size && earlier.configuration.knobs == planned.configuration.knobs;
        }))
      continue;
    scene.prepared->setSize(planned.size.first, planned.size.second);
    pipeline::checkRenders(planned.configuration, scene.name + " (" + planned.label + ")", *scene.prepared);
    plan.push_back(std::move(planned));
  }
  makeFolder(options.out, "--out");

  std::map<std::pair<int, int>, Truth> references;  // one per resolution
  std::vector<ResultRow> rows;
  Progress progress(plan.size());
  const InterruptibleRun interruptible;
  for (const auto& [configuration, size, label, swept] : plan) {
    if (InterruptibleRun::requested()) break;
    progress.update(rows.size(), label);
    scene.prepared->setSize(size.first, size.second);
    // A line algorithm is judged by the line reference of the edges it draws instead.
    if (!references.contains(size) && algorithm.kind != AlgorithmKind::line) {
      Stats ignored;
      Truth& truth = references.emplace(size, Truth{renderReference(*scene.prepared, options.threads, ignored), std::nullopt}).first->second;
      addExactShares(truth, *scene.prepared, options.threads);
    }
    ResultRow row = measureConfiguration(scene.name, *scene.prepared, references[size], configuration, options.repeat,
                                         options.threads).row;
    row.swept = swept;
    std::printf("  %zu/%zu %s: visibility %s ms\n", rows.size() + 1, plan.size(), label.c_str(),
                formattedRange(row.visibility, 1e3, "%.3f").c_str());
    std::fflush(stdout);
    rows.push_back(std::move(row));
  }
  progress.update(rows.size(), "done");
  if (InterruptibleRun::requested()) {
    reportInterrupted(rows.size(), plan.size(), "configurations");
    if (rows.empty()) return kInterruptedExit;
  }
  markParetoFront(rows);
  warnIfBusy(rows, options.repeat);
  const bool lines = algorithm.kind == AlgorithmKind::line;
  // What the rows are ranked by: their errorValue, the same kind for every row of one algorithm.
  const std::string errorName = rows.empty() ? "pixel error" : rows.front().errorName();
  std::printf("%s on %s (* = on the Pareto front of visibility time and %s; times within each other's range tie)\n%s",
              algorithm.name.c_str(), options.scene.c_str(),
              errorName.c_str(), resultsTable(rows, sweptKnobs, options.wide).c_str());

  // The error on a log axis, where a tenfold gain in accuracy reads as one step; an
  // error of exactly 0 is drawn on the floor below the smallest non-zero one.
  double smallest = 1;
  for (const ResultRow& row : rows)
    if (row.errorValue() > 0) smallest = std::min(smallest, row.errorValue());
  const double floor = smallest / 10;
  const auto plotted = [&](const ResultRow& row) { return std::max(row.errorValue(), floor) * 100; };
  std::vector<std::string> points, front;
  std::vector<const ResultRow*> frontRows;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ResultRow& row = rows[i];
    std::string label;
    // Values alone when one knob is swept (or for the variant), NAME=VALUE otherwise;
    // a knob the row's variant does not have is left out.
    for (const auto& [name, value] : row.swept) {
      if (value == "-") continue;
      label += label.empty() ? "" : " ";
      label += name == "variant" || row.swept.size() == 1 ? value : name + "=" + value;
    }
    if (row.errorValue() == 0) label += " (error 0)";
    // Past a dozen points their labels overprint: then only the front is named (the CSV
    // and the table name every row).
    if (rows.size() > kLabelledPoints && !row.pareto) label.clear();
    char line[256];
    // Labels alternate above and below their points, so neighbours do not overprint;
    // the time's range is the point's horizontal bar.
    std::snprintf(line, sizeof line, "%.6g %.6g %s %d %.6g %.6g", row.visibility.median * 1e3, plotted(row), quotedLabel(label).c_str(),
                  i % 2 ? -1 : 1, row.visibility.min * 1e3, row.visibility.max * 1e3);
    points.push_back(line);
    if (row.pareto) frontRows.push_back(&row);
  }
  std::sort(frontRows.begin(), frontRows.end(),
            [](const ResultRow* a, const ResultRow* b) { return a->visibility.median < b->visibility.median; });
  for (const ResultRow* row : frontRows) {
    char line[128];
    std::snprintf(line, sizeof line, "%.6g %.6g", row->visibility.median * 1e3, plotted(*row));
    front.push_back(line);
  }
  const std::string sceneFile = std::filesystem::path(options.scene).filename().string();
  std::vector<double> times;
  for (const ResultRow& row : rows) times.insert(times.end(), {row.visibility.min * 1e3, row.visibility.max * 1e3});
  const std::string body =
      dataBlock("points", points) + dataBlock("front", front) + timeAxis('x', times, false) + "set title " +
      quotedLabel(algorithm.name + " on " + sceneFile + ": " + errorName + " against visibility time") +
      "\nset xlabel 'visibility time per frame, median and range of " + std::to_string(options.repeat) + " runs (ms)'\nset ylabel '" +
      (lines                          ? "line error (% of the visible length, log scale)"
       : errorName == "coverage error" ? "coverage error (% of the image area shown wrong, log scale)"
                                       : "pixel error (% of non-ambiguous pixels, log scale)") +
      "'\nset logscale y\nset format y '%g'\nset grid\n"
      "set offsets graph 0.1, graph 0.35, graph 0.3, graph 0.3\nset key top right\n"
      "plot $front using 1:2 with linespoints lw 2 pt 6 ps 2 lc rgb '#d95f02' title 'Pareto front', \\\n"
      "     $points using 1:2:5:6 with xerrorbars pt 7 ps 1.3 lc rgb '#1b9e77' title 'configurations', \\\n"
      "     $points using 1:($2 * (1 + 0.25 * $4)):3 with labels left offset char 1,0 font ',9' notitle";
  writeResults(options.out, "sweep", rows, sweptKnobs, body);
  return InterruptibleRun::requested() ? kInterruptedExit : 0;
}

// Least-squares slope and intercept of log(time) against log(size): time ~ e^b size^a.
std::pair<double, double> powerFit(const std::vector<double>& sizes, const std::vector<double>& times) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(sizes.size());
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const double x = std::log(sizes[i]), y = std::log(times[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return {slope, (sy - slope * sx) / n};
}

// The scene tiled n x n times across its own footprint in the view plane, each copy
// shrunk by 1/n about the scene's center: the triangles grow by n^2, the covered
// pixels stay about the same.
std::vector<dmat4> tiledCopies(const PreparedScene& scene, int n) {
  Aabb bounds;
  for (const dvec3& p : scene.positions()) bounds.grow(p);
  const CameraTransform& camera = scene.camera();
  const dvec3 extent = bounds.hi - bounds.lo;
  const double step = std::max({extent.x, extent.y, extent.z}) / n;
  std::vector<dmat4> copies;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const dvec3 offset = camera.right() * ((i - (n - 1) / 2.0) * step) + camera.up() * ((j - (n - 1) / 2.0) * step);
      dmat4 copy = glm::translate(dmat4(1.0), bounds.center() + offset);
      copy = glm::scale(copy, dvec3(1.0 / n));
      copies.push_back(glm::translate(copy, -bounds.center()));
    }
  return copies;
}

int scaleSweep(const SweepOptions& options, const AlgorithmEntry& algorithm, const std::vector<Axis>& axes) {
  if (options.scale != "triangles" && options.scale != "pixels")
    throw InputError("--scale " + options.scale + ": expected triangles or pixels");
  KnobSettings settings = fixedSettings(options);
  for (const Axis& axis : axes) {
    if (axis.values.size() != 1 || axis.name == kSizeKnob)
      throw InputError("--knob " + axis.name + ": with --scale, each --knob fixes one algorithm setting (NAME=VALUE)");
    settings.emplace_back(axis.name, axis.values.front());
  }
  const pipeline::Configuration configuration = pipeline::configurationOf(algorithm, settings);
  LoadedScene scene = loadPrepared(options.scene, options.size);

  // The sizes: resolutions 256^2 ... 4096^2, or n x n copies, n doubling from the first
  // that gives 1,000 triangles while the copies stay under 1.1 million.
  std::vector<int> steps;
  const auto baseTriangles = static_cast<double>(scene.prepared->triangleCount());
  if (options.scale == "pixels") {
    steps = {256, 512, 1024, 2048, 4096};
  } else {
    if (baseTriangles == 0 || baseTriangles * 4 > 1.1e6)
      throw InputError(options.scene + ": has " + std::to_string(std::int64_t(baseTriangles)) +
                       " triangles; --scale triangles grows a scene of at most 275,000 to about 1,000,000");
    for (int n = std::max(1, int(std::ceil(std::sqrt(1000 / baseTriangles)))); baseTriangles * n * n <= 1.1e6; n *= 2)
      steps.push_back(n);
  }
  makeFolder(options.out, "--out");

  std::vector<ResultRow> rows;
  std::vector<double> sizes, times;
  Progress progress(steps.size());
  const InterruptibleRun interruptible;
  for (const int step : steps) {
    if (InterruptibleRun::requested()) break;
    std::unique_ptr<PreparedScene> grown;
    const PreparedScene* prepared = scene.prepared.get();
    std::string value;
    if (options.scale == "pixels") {
      scene.prepared->setSize(step, step);
      value = std::to_string(step) + "x" + std::to_string(step);
    } else {
      grown = std::make_unique<PreparedScene>(*scene.scene, tiledCopies(*scene.prepared, step));
      grown->setSize(scene.prepared->width(), scene.prepared->height());
      prepared = grown.get();
      value = std::to_string(prepared->triangleCount());
    }
    // The first size the algorithm refuses (a budget) ends the sweep: where it stops
    // being practical is part of the answer. The first size must render.
    if (const std::string refusal = pipeline::refusal(*prepared, configuration); !refusal.empty() && !rows.empty()) {
      std::printf("stopping at %s %s: %s\n", options.scale.c_str(), value.c_str(), refusal.c_str());
      break;
    }
    pipeline::checkRenders(configuration, scene.name + " (" + options.scale + " " + value + ")", *prepared);
    progress.update(rows.size(), options.scale + " " + value);
    Stats ignored;  // a line algorithm is judged by the line reference of its own edges instead
    // Time against size: the coverage error, which needs the exact shares, is left out.
    const Truth truth{algorithm.kind == AlgorithmKind::line ? ReferenceImage() : renderReference(*prepared, options.threads, ignored), std::nullopt};
    ResultRow row = measureConfiguration(scene.name, *prepared, truth, configuration, options.repeat, options.threads).row;
    row.swept = {{options.scale, value}};
    sizes.push_back(options.scale == "pixels" ? double(step) * step : double(prepared->triangleCount()));
    times.push_back(row.visibility.median);
    std::printf("  %zu/%zu %s %s: visibility %s ms\n", rows.size() + 1, steps.size(), options.scale.c_str(), value.c_str(),
                formattedRange(row.visibility, 1e3, "%.3f").c_str());
    std::fflush(stdout);
    rows.push_back(std::move(row));
  }
  progress.update(rows.size(), "done");
  if (InterruptibleRun::requested()) {
    // A fit needs two sizes; with fewer there is nothing to write.
    reportInterrupted(rows.size() < 2 ? 0 : rows.size(), steps.size(), "sizes");
    if (rows.size() < 2) return kInterruptedExit;
  }
  if (rows.size() < 2) throw InputError(options.scene + ": " + algorithm.name + " renders only one size; no exponent to fit");
  warnIfBusy(rows, options.repeat);
  const auto [exponent, intercept] = powerFit(sizes, times);
  std::printf("%s on %s, growing %s\n%s  fit: visibility time ~ %s^%.3f\n", algorithm.name.c_str(), options.scene.c_str(),
              options.scale.c_str(), resultsTable(rows, {options.scale}, options.wide).c_str(), options.scale.c_str(), exponent);

  std::vector<std::string> points;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    char line[128];
    std::snprintf(line, sizeof line, "%.6g %.6g %.6g %.6g", sizes[i], times[i] * 1e3, rows[i].visibility.min * 1e3,
                  rows[i].visibility.max * 1e3);
    points.push_back(line);
  }
  char fit[256];
  std::snprintf(fit, sizeof fit, "fit(x) = exp(%.9g) * x**%.9g * 1000\n", intercept, exponent);
  char key[96];
  std::snprintf(key, sizeof key, "fit: visibility time ~ %s^%.2f", options.scale.c_str(), exponent);
  const std::string sceneFile = std::filesystem::path(options.scene).filename().string();
  const std::string body = dataBlock("points", points) + fit + "set title " +
                           quotedLabel(algorithm.name + " on " + sceneFile + ": visibility time against " + options.scale) +
                           "\nset logscale xy\nset xlabel '" + options.scale + "'\nset ylabel 'visibility time per frame, median and range (ms)'\n"
                           "set grid\nset key top left\n"
                           "plot $points using 1:2:3:4 with yerrorbars pt 7 ps 1.3 lc rgb '#1b9e77' title 'measured', \\\n"
                           "     fit(x) with lines lw 2 lc rgb '#d95f02' title " + quotedLabel(key);
  writeResults(options.out, "scale_" + options.scale, rows, {options.scale}, body);
  return InterruptibleRun::requested() ? kInterruptedExit : 0;
}

}  // namespace

int sweep(const SweepOptions& options) {
  const AlgorithmEntry& algorithm = findAlgorithm(options.algorithm);
  if (algorithm.kind == AlgorithmKind::reference)
    throw InputError("--algo reference: the reference is what a sweep measures against; sweep a surface or line algorithm");
  if (options.repeat < 1) throw InputError("--repeat " + std::to_string(options.repeat) + ": expected at least 1");
  const std::vector<Axis> axes = parseAxes(algorithm, options);
  if (!options.scale.empty()) return scaleSweep(options, algorithm, axes);
  if (axes.empty()) throw InputError("hsr sweep: give at least one --knob NAME=v1,v2,... (or --scale triangles|pixels)");
  return knobSweep(options, algorithm, axes);
}

}  // namespace hsr::studies
