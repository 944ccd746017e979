// hsr compare: every applicable algorithm on each scene against the exact reference,
// time and error side by side, as a table, CSV, JSON and a contact sheet.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <span>
#include <sstream>
#include <utility>

#include "algorithms/registry.hpp"
#include "renderer/lines/line_drawing.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/markup.hpp"
#include "studies/common.hpp"
#include "studies/contact_sheet.hpp"
#include "studies/measure.hpp"
#include "studies/results.hpp"
#include "studies/studies.hpp"

namespace hsr::studies {
namespace {

// The default study: the shipped scenes that each teach something about visibility.
const char* const kStudyScenes[] = {"cube.toml", "bunny.toml", "counters.toml", "trees.toml", "dragons.toml",
                                    "hard/coplanar.toml", "hard/near_plane.toml"};

// The suite's own folder: where its scenes and each algorithm's README are.
std::filesystem::path suiteFolder() { return std::filesystem::path(HSR_SCENES_DIR).parent_path(); }

// A scene of the suite's own named from the suite's folder (scenes/cube.toml), as a
// student finds it; any other as it was given.
std::string suiteRelative(const std::string& path) {
  const std::string suite = suiteFolder().string() + "/";
  return path.rfind(suite, 0) == 0 ? path.substr(suite.size()) : path;
}

// The options that run a row's configuration again: "--algo zbuffer --knob variant=scanline".
std::string commandOptions(const ResultRow& row) {
  std::string options = "--algo " + row.algorithm;
  if (row.knobs == "defaults" || row.knobs == "exact") return options;
  std::istringstream settings(row.knobs);
  for (std::string setting; settings >> setting;) options += " --knob " + setting;
  return options;
}

// The algorithm's README, as a link from the report's folder; none where there is none.
std::string readmeLink(const std::string& algorithm, const std::filesystem::path& out) {
  const std::filesystem::path folder = algorithm == "reference" ? "renderer/reference" : "algorithms/" + algorithm;
  const std::filesystem::path readme = suiteFolder() / folder / "README.md";
  std::error_code error;
  if (!std::filesystem::exists(readme, error)) return "";
  const std::filesystem::path link = std::filesystem::relative(readme, std::filesystem::absolute(out, error), error);
  return error ? readme.string() : link.generic_string();
}

// The gallery report.html leads with (studies/report.hpp): per scene, the reference and
// each configuration with its picture, its error map and the figures a student compares,
// as JSON, the pictures under images/.
class Gallery {
 public:
  explicit Gallery(std::filesystem::path out) : out_(std::move(out)) {}

  void beginScene(const std::string& scene, const PreparedScene& prepared) {
    // Named after the scene, in the characters an address takes as they are.
    std::string stem = std::filesystem::path(scene).stem().string();
    for (char& c : stem)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    folder_ = "images/" + std::to_string(++scenes_) + "-" + stem;
    std::filesystem::create_directories(out_ / folder_);
    json_ += std::string(scenes_ > 1 ? "]}," : "") + "{\"scene\":" + jsonString(scene) + ",\"width\":" + std::to_string(prepared.width()) +
             ",\"height\":" + std::to_string(prepared.height()) + ",\"triangles\":" + std::to_string(prepared.triangleCount()) + ",\"entries\":[";
    entries_ = 0;
  }

  // One tile: the row's figures, its picture and the map of where it is wrong.
  void add(const ResultRow& row, std::span<const std::uint8_t> picture, std::span<const std::uint8_t> errorMap, const std::string& errorLegend) {
    const std::string name = folder_ + "/" + std::to_string(++entries_);
    files_.addRgbaPng(out_ / (name + ".png"), row.width, row.height, picture);
    files_.addRgbaPng(out_ / (name + "-error.png"), row.width, row.height, errorMap);
    json_ += std::string(entries_ > 1 ? "," : "") + "{\"algorithm\":" + jsonString(row.algorithm) + ",\"knobs\":" + jsonString(row.knobs) +
             ",\"picture\":" + jsonString(name + ".png") + ",\"errorMap\":" + jsonString(name + "-error.png") +
             ",\"errorLegend\":" + jsonString(errorLegend) + ",\"lines\":" + (row.lines ? "true" : "false") +
             ",\"visibilityMs\":[" + jsonNumber(row.visibility.median * 1e3) + "," + jsonNumber(row.visibility.min * 1e3) + "," +
             jsonNumber(row.visibility.max * 1e3) + "],\"error\":" + jsonNumber(row.lines ? row.lineError.error : row.error.pixelError) +
             ",\"coverageError\":" + (row.coverage ? jsonNumber(row.coverage->mean) : "null") +
             ",\"wrongPixels\":" + std::to_string(row.error.wrongPixels) + ",\"ambiguousPixels\":" + std::to_string(row.error.ambiguousPixels) +
             ",\"options\":" + jsonString(commandOptions(row)) + ",\"readme\":" + jsonString(readmeLink(row.algorithm, out_)) +
             ",\"answersWhy\":" + (findAlgorithm(row.algorithm).answersWhy ? "true" : "false") + "}";
  }

  // Written with the run's other files: gallery.json and the pictures.
  void commit() {
    files_.addText(out_ / "gallery.json", "{\"scenes\":[" + json_ + (scenes_ > 0 ? "]}" : "") + "]}\n");
    files_.commit();
  }

 private:
  std::filesystem::path out_;
  std::string folder_, json_;
  int scenes_ = 0, entries_ = 0;
  OutputFiles files_;
};

// A one-sample configuration's coverage error, under its map of wrong pixels: what even
// a right pixel center costs at edges.
std::string coverageNote(const ResultRow& row) {
  if (!row.coverage) return "";
  char note[64];
  std::snprintf(note, sizeof note, "; coverage error %.2f%%", row.coverage->mean * 100);
  return note;
}

}  // namespace

int compare(const CompareOptions& options) {
  // Everything the run needs is read and checked before the first render.
  const bool study = options.scenes.empty();
  std::vector<std::string> scenePaths = options.scenes;
  if (study)
    for (const char* name : kStudyScenes) scenePaths.push_back(std::string(HSR_SCENES_DIR) + "/" + name);
  std::vector<LoadedScene> scenes;
  for (const std::string& path : scenePaths) scenes.push_back(loadPrepared(path, options.size));

  std::vector<pipeline::Configuration> configurations;
  if (!options.algorithms.empty()) {
    for (const std::string& item : splitList(options.algorithms, "--algos")) {
      configurations.push_back(parseConfiguration(item, "--algos"));
      if (configurations.back().algorithm->kind == AlgorithmKind::reference)
        throw InputError("--algos " + item + ": the reference is always run; name the algorithms to compare with it");
    }
  } else {
    // The default study is of the surface algorithms on the shipped surface scenes; named
    // scenes get every algorithm, line algorithms included, that accepts them.
    for (const AlgorithmEntry& algorithm : algorithms()) {
      if (algorithm.kind == AlgorithmKind::reference || (study && algorithm.kind != AlgorithmKind::surface)) continue;
      if (!study) configurations.push_back(pipeline::configurationOf(algorithm, {}));
      else
        for (const KnobSettings& settings : algorithm.studyConfigurations) configurations.push_back(pipeline::configurationOf(algorithm, settings));
    }
  }
  if (options.repeat < 1) throw InputError("--repeat " + std::to_string(options.repeat) + ": expected at least 1");
  makeFolder(options.out, "--out");

  std::vector<ResultRow> rows;
  std::vector<SheetSection> sections;
  Gallery gallery(options.out);
  const AlgorithmEntry& referenceAlgorithm = referenceEntry();
  for (const LoadedScene& scene : scenes) {
    const PreparedScene& prepared = *scene.prepared;
    const std::string sceneName = suiteRelative(scene.name);
    gallery.beginScene(sceneName, prepared);
    auto reference = measure(options.repeat, [&](Stats& stats) { return renderReference(prepared, options.threads, stats); });

    SheetSection section;
    section.heading = scene.name.substr(scene.name.find_last_of('/') + 1) + ":  " + std::to_string(prepared.width()) + "x" +
                      std::to_string(prepared.height()) + ", " + formatCount(std::int64_t(prepared.triangleCount())) +
                      " triangles";
    std::printf("%s\n  reference: %s ambiguous pixels, %s exact fall-backs\n", section.heading.c_str(),
                formatCount(reference.result.ambiguousPixels).c_str(), formatCount(reference.result.exactFallbacks).c_str());
    std::vector<ResultRow> sceneRows;
    ResultRow referenceRow = measuredRow(sceneName, prepared, referenceAlgorithm, "exact", reference, options.threads);
    Truth truth{std::move(reference.result), std::nullopt};
    if (std::any_of(configurations.begin(), configurations.end(),
                    [](const pipeline::Configuration& c) { return c.algorithm->kind == AlgorithmKind::surface; }))
      addExactShares(truth, prepared, options.threads);
    referenceRow.error = surfaceError(truth.image.frame, truth.image);
    // One sample per pixel, even the exact one, gets edges' shares wrong: the lesson of the column.
    if (truth.shares)
      referenceRow.coverage = coverageError(sharesOfSamples(truth.image.frame.ids, prepared.width(), prepared.height(), 1), *truth.shares);
    std::vector<std::uint8_t> ambiguity = errorHeatMap(truth.image.frame, truth.image);
    gallery.add(referenceRow, truth.image.frame.color, ambiguity, "ambiguous pixels blue");
    sceneRows.push_back(referenceRow);
    char line[128];
    std::snprintf(line, sizeof line, "visibility %.1f ms, total %.1f", referenceRow.visibility.median * 1e3, referenceRow.time.median * 1e3);
    section.images.push_back({prepared.width(), prepared.height(), truth.image.frame.color, {"reference (exact)", line}});
    section.heatMaps.push_back({prepared.width(), prepared.height(), std::move(ambiguity),
                                {formatCount(truth.image.ambiguousPixels) + " ambiguous px (blue)" + coverageNote(referenceRow)}});

    std::vector<PixelBuffer<std::uint8_t>> exactDrawingsShown;  // the line references' tiles so far
    for (const pipeline::Configuration& configuration : configurations) {
      const AlgorithmEntry& algorithm = *configuration.algorithm;
      if (const std::string refusal = pipeline::refusal(prepared, configuration); !refusal.empty()) {
        std::printf("  %s %s: skipped, %s\n", algorithm.name.c_str(), configuration.knobs.described().c_str(),
                    refusal.c_str());
        continue;
      }
      const auto [row, frame, lineErrors, exactLines, coverageErrors] =
          measureConfiguration(sceneName, prepared, truth, configuration, options.repeat, options.threads);
      // A line algorithm is judged by an exact drawing, not by the reference image: that
      // drawing gets a tile of its own before the first algorithm judged by it.
      if (row.lines) {
        Frame exact = lineSetFrame(exactLines, LineStyle::visible);
        if (std::find(exactDrawingsShown.begin(), exactDrawingsShown.end(), exact.color) == exactDrawingsShown.end()) {
          exactDrawingsShown.push_back(exact.color);
          section.images.push_back({prepared.width(), prepared.height(), std::move(exact.color), {"exact lines (reference)", "line errors are measured against it"}});
          section.heatMaps.push_back({prepared.width(), prepared.height(), lineSetFrame(exactLines, LineStyle::hidden).color,
                                      {"hidden parts dashed"}});
        }
      }
      sceneRows.push_back(row);
      std::snprintf(line, sizeof line, "visibility %.1f ms, %s %.4f%%%s", row.visibility.median * 1e3, row.errorName(),
                    row.errorValue() * 100, frame.partial.empty() ? "" : " (partial)");
      if (!frame.partial.empty())
        std::printf("  %s %s: the image is partial: %s\n", algorithm.name.c_str(), row.knobs.c_str(), frame.partial.c_str());
      section.images.push_back({prepared.width(), prepared.height(), frame.color,
                                {algorithm.name + (row.knobs == "defaults" ? "" : " " + row.knobs), line}});
      if (row.lines) {
        std::snprintf(line, sizeof line, "%.1f px wrong (red), %.1f px missing (blue)", row.lineError.wronglyDrawn,
                      row.lineError.wronglyHidden);
        section.heatMaps.push_back({prepared.width(), prepared.height(), lineErrors, {line}});
        gallery.add(row, frame.color, lineErrors, "drawn though hidden red, hidden though visible blue");
      } else if (row.antialiased && row.coverage) {
        gallery.add(row, frame.color, coverageErrors, "the more of a pixel its shares get wrong, the redder; ties blue");
        section.heatMaps.push_back({prepared.width(), prepared.height(), coverageErrors,
                                    {formatCount(row.coverage->mixedPixels) + " mixed px; wrong shares red, ties blue"}});
      } else {
        std::vector<std::uint8_t> errorMap = errorHeatMap(frame, truth.image);
        gallery.add(row, frame.color, errorMap, "wrong pixels red, ambiguous blue, over the reference dimmed");
        section.heatMaps.push_back({prepared.width(), prepared.height(), std::move(errorMap),
                                    {formatCount(row.error.wrongPixels) + " wrong px (red)" + coverageNote(row)}});
      }
    }
    std::printf("%s\n", resultsTable(sceneRows, {}, options.wide).c_str());
    rows.insert(rows.end(), sceneRows.begin(), sceneRows.end());
    sections.push_back(std::move(section));
  }

  warnIfBusy(rows, options.repeat);
  const Image sheet = composeContactSheet(std::move(sections));
  const std::filesystem::path out = options.out;
  OutputFiles files;
  files.addRgbaPng(out / "contact_sheet.png", sheet.width, sheet.height, sheet.pixels);
  files.addText(out / "results.csv", resultsCsv(rows, {}));
  files.addText(out / "results.json", resultsJson(rows));
  files.commit();
  gallery.commit();
  std::printf("wrote %s, results.csv, results.json, gallery.json and images/ in %s\n", "contact_sheet.png", out.string().c_str());
  return 0;
}

}  // namespace hsr::studies
