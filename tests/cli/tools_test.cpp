// hsr compare, sweep and diff on good input: the files they write are well formed, have
// the columns README.md documents, and say what the measurements say.
#include <gtest/gtest.h>

#include <csignal>
#include <cmath>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "json_reader.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/raster/depth.hpp"
#include "renderer/util/simd.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

using Row = std::map<std::string, std::string>;

std::string readText(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// RFC 4180 fields: commas inside double quotes, "" for a quote.
std::vector<std::string> csvFields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
    else if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) fields.emplace_back();
    else fields.back() += c;
  }
  return fields;
}

// Every row as column -> field; fails the test if a row's field count differs from the header's.
std::vector<Row> readCsv(const std::filesystem::path& path, std::vector<std::string>& header) {
  std::istringstream lines(readText(path));
  std::string line;
  std::getline(lines, line);
  header = csvFields(line);
  std::vector<Row> rows;
  while (std::getline(lines, line)) {
    const std::vector<std::string> fields = csvFields(line);
    EXPECT_EQ(fields.size(), header.size()) << line;
    Row row;
    for (std::size_t i = 0; i < std::min(fields.size(), header.size()); ++i) row[header[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

double number(const Row& row, const std::string& column) {
  std::size_t used = 0;
  const double value = std::stod(row.at(column), &used);
  EXPECT_EQ(used, row.at(column).size()) << column << " = " << row.at(column);
  return value;
}

// The measured columns, in order, as README.md ("hsr compare") documents them.
const std::vector<std::string> kMeasuredColumns = {
    "width", "height", "triangles", "threads", "repeats", "visibility_median_ms", "visibility_min_ms", "visibility_max_ms",
    "effects_median_ms", "effects_min_ms", "effects_max_ms", "time_median_ms", "time_min_ms", "time_max_ms",
    "pixel_error", "wrong_pixels", "compared_pixels", "ambiguous_pixels", "depth_error_mean", "depth_error_max",
    "coverage_error", "coverage_error_mixed", "mixed_pixels", "line_error", "visible_length_px", "wrongly_drawn_px", "wrongly_hidden_px", "peak_memory_bytes"};

void expectConsistentMeasurements(const Row& row) {
  for (const std::string timing : {"visibility", "effects", "time"}) {
    EXPECT_LE(number(row, timing + "_min_ms"), number(row, timing + "_median_ms")) << timing;
    EXPECT_LE(number(row, timing + "_median_ms"), number(row, timing + "_max_ms")) << timing;
  }
  EXPECT_GT(number(row, "visibility_min_ms"), 0);
  // Each run's visibility is part of that run's time, so each order statistic is too.
  for (const std::string statistic : {"_min_ms", "_median_ms", "_max_ms"})
    EXPECT_LE(number(row, "visibility" + statistic), number(row, "time" + statistic)) << statistic;
  EXPECT_GT(number(row, "peak_memory_bytes"), 0);
  if (!row.at("line_error").empty()) {  // a line algorithm: line error only
    EXPECT_EQ(row.at("pixel_error"), "");
    EXPECT_EQ(row.at("coverage_error"), "");
    const double wrong = number(row, "wrongly_drawn_px") + number(row, "wrongly_hidden_px");
    EXPECT_NEAR(number(row, "line_error"), wrong / number(row, "visible_length_px"), 1e-9);
    return;
  }
  EXPECT_EQ(row.at("visible_length_px"), "");
  const double wrong = number(row, "wrong_pixels"), compared = number(row, "compared_pixels");
  EXPECT_NEAR(number(row, "pixel_error"), wrong / compared, 1e-9);
  EXPECT_EQ(compared + number(row, "ambiguous_pixels"), number(row, "width") * number(row, "height"));
  EXPECT_LE(number(row, "depth_error_mean"), number(row, "depth_error_max"));
  // Coverage error (on opaque scenes): a mean of distances between 0 and 1, over every
  // pixel and over the mixed ones, so the first is at least the second times their share
  // of the pixels (a whole pixel shown wrong adds to the first alone).
  if (row.at("coverage_error").empty()) return;
  const double coverage = number(row, "coverage_error"), mixed = number(row, "mixed_pixels");
  EXPECT_GE(coverage, 0);
  EXPECT_LE(number(row, "coverage_error_mixed"), 1);
  EXPECT_GE(coverage + 1e-8, number(row, "coverage_error_mixed") * mixed / (number(row, "width") * number(row, "height")));
}

std::filesystem::path freshFolder(const std::string& name) {
  const auto folder = test::outputPath(name);
  std::filesystem::remove_all(folder);
  return folder;
}

const std::string kScenes = std::string(HSR_SOURCE_DIR) + "/scenes/";

TEST(Compare, WritesTheDocumentedCsvJsonAndContactSheet) {
  const auto folder = freshFolder("compare");
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " compare " + kScenes + "cube.toml " +
                                                      kScenes + "hard/coplanar.toml --size 96x72 --repeat 2 --wide --out " + folder.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_NE(result.output.find("reference: 0 ambiguous pixels"), std::string::npos) << result.output;
  // The last line says where the report is.
  const std::string lastLine = result.output.substr(result.output.rfind('\n', result.output.size() - 2) + 1);
  EXPECT_EQ(lastLine, "open " + (folder / "report.html").string() + " in a browser: every table, image and plot of this run\n");
  // The table (--wide: every column) leads with the algorithm's own time, the shared passes beside it.
  const std::size_t visibility = result.output.find("visibility ms: median [min-max]");
  ASSERT_NE(visibility, std::string::npos) << result.output;
  EXPECT_LT(visibility, result.output.find("+ shading, effects ms", visibility)) << result.output;
  EXPECT_LT(result.output.find("+ shading, effects ms", visibility), result.output.find("= total ms", visibility)) << result.output;

  std::vector<std::string> header;
  const std::vector<Row> rows = readCsv(folder / "results.csv", header);
  std::vector<std::string> expected = {"scene", "algorithm", "knobs"};
  expected.insert(expected.end(), kMeasuredColumns.begin(), kMeasuredColumns.end());
  expected.push_back("counters");
  expected.push_back("pass_ms");
  EXPECT_EQ(header, expected);
  // Every column is in README's table of them: a row of a Markdown table naming it.
  std::set<std::string> documented;
  std::istringstream readme(readText(std::string(HSR_SOURCE_DIR) + "/README.md"));
  const std::regex named("`([a-z_]+)`");
  for (std::string line; std::getline(readme, line);)
    if (line.rfind("| `", 0) == 0)
      for (auto match = std::sregex_iterator(line.begin(), line.end(), named); match != std::sregex_iterator(); ++match)
        documented.insert((*match)[1]);
  for (const std::string& column : header) EXPECT_TRUE(documented.count(column)) << column << " is not in README's table of columns";
  // Per scene: the reference, then every algorithm that accepts it at its defaults: the
  // seven surface algorithms on both, the line algorithms (roberts, appel) on the closed
  // cube but not on coplanar's open quads.
  ASSERT_EQ(rows.size(), 18u);
  for (const char* line : {"roberts", "appel"})
    EXPECT_EQ(std::count_if(rows.begin(), rows.end(), [&](const Row& row) { return row.at("algorithm") == line; }), 1) << line;
  for (const Row& row : rows) {
    expectConsistentMeasurements(row);
    EXPECT_EQ(row.at("repeats"), "2");
  }
  EXPECT_EQ(rows[0].at("algorithm"), "reference");
  EXPECT_EQ(number(rows[0], "pixel_error"), 0);
  EXPECT_EQ(rows[1].at("algorithm"), "zbuffer");
  EXPECT_EQ(rows[1].at("knobs"), "defaults");
  EXPECT_NE(rows[1].at("counters").find("fragments tested="), std::string::npos);
  // The fast path's own counter where it ran (on a CPU with AVX2), and only there.
  EXPECT_EQ(rows[1].at("counters").find("fragments skipped by block depth=") != std::string::npos, cpuHasAvx2()) << rows[1].at("counters");
  EXPECT_EQ(rows[1].at("pass_ms").rfind("visibility=", 0), 0u) << rows[1].at("pass_ms");
  EXPECT_NE(rows[1].at("pass_ms").find(";shading="), std::string::npos) << "cube.toml is lambert: a shading pass";
  EXPECT_EQ(rows[1].at("pass_ms").find("shadow maps"), std::string::npos) << "and no shadows";
  EXPECT_EQ(rows[2].at("algorithm"), "ray_casting");
  EXPECT_NE(rows[2].at("counters").find("bvh nodes visited="), std::string::npos);
  EXPECT_EQ(rows[3].at("algorithm"), "painter");
  EXPECT_NE(rows[3].at("counters").find("bsp nodes="), std::string::npos);
  EXPECT_EQ(rows[4].at("algorithm"), "warnock");
  EXPECT_NE(rows[4].at("counters").find("windows examined="), std::string::npos);
  EXPECT_EQ(rows[5].at("algorithm"), "watkins");
  EXPECT_NE(rows[5].at("counters").find("spans="), std::string::npos);
  EXPECT_EQ(rows[6].at("algorithm"), "weiler_atherton");
  EXPECT_NE(rows[6].at("counters").find("clip polygons="), std::string::npos);
  EXPECT_EQ(rows[7].at("algorithm"), "abuffer");
  EXPECT_NE(rows[7].at("counters").find("pixels with partial coverage="), std::string::npos);
  EXPECT_EQ(rows[8].at("algorithm"), "roberts");
  EXPECT_EQ(rows[9].at("algorithm"), "appel");
  for (const std::size_t exact : {8u, 9u}) EXPECT_LT(number(rows[exact], "line_error"), 1e-12);  // one cube: only rounding
  for (const std::size_t exact : {2u, 12u}) EXPECT_EQ(number(rows[exact], "pixel_error"), 0);  // bvh is exact
  EXPECT_GT(number(rows[11], "ambiguous_pixels"), 0);  // the coplanar tie
  // The A-buffer's shares come closer to the exact ones than any one sample a pixel,
  // the exact reference's own among them.
  for (const std::size_t oneSample : {0u, 1u, 2u, 3u, 4u, 5u, 6u})
    EXPECT_LT(number(rows[7], "coverage_error"), 0.5 * number(rows[oneSample], "coverage_error")) << rows[oneSample].at("algorithm");

  const test::JsonValue json = test::parseJson(readText(folder / "results.json"));
  ASSERT_EQ(json.array().size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const test::JsonValue& object = json.array()[i];
    EXPECT_EQ(object["algorithm"].string(), rows[i].at("algorithm"));
    for (const std::string& column : kMeasuredColumns) {
      if (rows[i].at(column).empty())  // a field that does not apply to this kind of algorithm
        EXPECT_TRUE(std::holds_alternative<std::nullptr_t>(object[column].value)) << column;
      else
        EXPECT_DOUBLE_EQ(object[column].number(), number(rows[i], column)) << column;
    }
  }
  EXPECT_GT(json.array()[1]["counters"]["fragments tested"].number(), 0);

  const Image sheet = readImage(folder / "contact_sheet.png");
  // Eleven columns: the reference, zbuffer, ray_casting, painter, warnock, watkins, weiler_atherton, abuffer, the
  // exact line drawing (what both line algorithms are judged by: one tile), roberts, appel.
  EXPECT_EQ(sheet.width, 10 + 11 * (256 + 10));
  EXPECT_GT(sheet.height, 4 * 192);             // two scenes, each an image row and a heat-map row
}

// A scene narrower than a thumbnail (256 pixels): its images and heat maps are enlarged,
// and every thumbnail pixel is filled (none transparent); the line algorithms' long
// captions are broken into lines that stay inside their tile, so the 10-pixel gaps
// between tiles hold nothing but the sheet's background below the heading.
// Without --wide, the five columns a reader compares first, in a terminal's width.
TEST(Compare, TheDefaultTableFitsATerminal) {
  const auto folder = freshFolder("compare-narrow");
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " compare " + kScenes + "counters.toml " +
                                                      "--algos zbuffer,zbuffer:path=scalar,painter --size 64x36 --repeat 1 --out " +
                                                      folder.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const std::size_t heading = result.output.find("  algorithm");
  ASSERT_NE(heading, std::string::npos) << result.output;
  const std::string headingLine = result.output.substr(heading, result.output.find('\n', heading) - heading);
  for (const char* column : {"knobs", "visibility ms: median [min-max]", "error", "wrong px"})
    EXPECT_NE(headingLine.find(column), std::string::npos) << column << " in " << headingLine;
  EXPECT_EQ(headingLine.find("total"), std::string::npos) << headingLine;
  std::istringstream lines(result.output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  ", 0) == 0) {  // the table's lines
      EXPECT_LE(line.size(), 100u) << line;
    }
  }
}

TEST(Compare, TheContactSheetOfASmallSceneIsFilledAndItsCaptionsStayInTheirTiles) {
  const auto folder = freshFolder("compare-small");
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " compare " + kScenes +
                                                      "cube.toml --size 200x200 --repeat 1 --out " + folder.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const Image sheet = readImage(folder / "contact_sheet.png");
  constexpr int kMargin = 10, kThumbnail = 256, kHeading = 40;
  const int columns = (sheet.width - kMargin) / (kThumbnail + kMargin);
  ASSERT_EQ(columns, 11) << "the reference, seven surface algorithms, the exact lines, two line algorithms";
  std::int64_t transparent = 0, inGaps = 0;
  for (int y = 0; y < sheet.height; ++y)
    for (int x = 0; x < sheet.width; ++x) {
      const std::uint8_t* pixel = &sheet.pixels[4 * (std::size_t(y) * std::size_t(sheet.width) + std::size_t(x))];
      transparent += pixel[3] != 255;
      const bool gap = x >= kMargin && (x - kMargin) % (kThumbnail + kMargin) >= kThumbnail;
      if (gap && y >= kHeading) inGaps += pixel[0] != 23 || pixel[1] != 23 || pixel[2] != 26;
    }
  EXPECT_EQ(transparent, 0);
  EXPECT_EQ(inGaps, 0) << "pixels of text or image spilled into the gaps between tiles";
  // The ninth tile is the exact line drawing: white paper and black lines, where the
  // reference's tile is a shaded surface on the scene's background.
  const auto whiteIn = [&](int column) {
    std::int64_t white = 0;
    const int x0 = kMargin + column * (kThumbnail + kMargin);
    for (int y = kHeading; y < kHeading + kThumbnail; ++y)
      for (int x = x0; x < x0 + kThumbnail; ++x) white += sheet.pixels[4 * (std::size_t(y) * std::size_t(sheet.width) + std::size_t(x))] == 255;
    return white;
  };
  EXPECT_GT(whiteIn(8), kThumbnail * kThumbnail / 2);
  EXPECT_LT(whiteIn(0), kThumbnail * kThumbnail / 10);
}

TEST(Study, CullingCombosWritesItsTableAndCountsTheWorkEachModeSaves) {
  const auto folder = freshFolder("study");
  const test::CommandResult result =
      test::runCommand(std::string(HSR_BINARY) + " study culling-combos --scenes cube,counters --frames 4 --error-frames 1 " +
                       "--size 320x180 --out " + folder.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_NE(result.output.find("per-object spheres beat per-triangle tests"), std::string::npos) << result.output;
  // Each claim gets one of three verdicts, with the ratios' intervals it was decided on.
  const std::regex claim(R"(: (held|did not hold|within noise) \(.*\[[0-9.]+-[0-9.]+\])");
  const std::ptrdiff_t verdicts = std::distance(std::sregex_iterator(result.output.begin(), result.output.end(), claim), std::sregex_iterator());
  EXPECT_EQ(verdicts, 3) << "backface, frustum on the cube, spheres against triangles\n" << result.output;
  std::vector<std::string> header;
  const std::vector<Row> rows = readCsv(folder / "culling_combos.csv", header);
  ASSERT_EQ(rows.size(), 16u);  // two scenes, eight modes
  std::map<std::string, Row> at;
  for (const Row& row : rows) {
    EXPECT_EQ(number(row, "frames"), 4);
    EXPECT_EQ(number(row, "error_frames"), 1);
    EXPECT_LE(number(row, "time_best5_ms"), number(row, "time_mean_ms"));
    EXPECT_LE(number(row, "time_mean_ms"), number(row, "time_worst5_ms"));
    at[row.at("scene") + "/" + row.at("mode")] = row;
  }
  for (const std::string scene : {"cube", "counters"}) {
    const auto value = [&](const std::string& mode, const std::string& column) { return number(at.at(scene + "/" + mode), column); };
    // Backface culling halves what is rasterized; the z-buffer modes are right but for
    // snapping, the modes without a depth test are not.
    EXPECT_LT(value("backface", "triangles_rasterized"), 0.6 * value("none", "triangles_rasterized")) << scene;
    EXPECT_LT(value("z-buffer", "pixel_error"), 1e-3) << scene;
    EXPECT_LT(value("backface + z-buffer + frustum (sphere)", "pixel_error"), 1e-3) << scene;
    EXPECT_GT(value("none", "pixel_error"), 1e-3) << scene;
    // The frustum stages leave the rasterizer the same triangles.
    EXPECT_EQ(value("frustum (sphere)", "triangles_rasterized"), value("none", "triangles_rasterized")) << scene;
  }
  // On the counters, the sphere test removes the counters out of view before any vertex work.
  const auto counters = [&](const std::string& mode, const std::string& column) { return number(at.at("counters/" + mode), column); };
  EXPECT_LT(counters("frustum (sphere)", "vertices_transformed"), 0.5 * counters("none", "vertices_transformed"));
  EXPECT_LT(counters("frustum (sphere)", "triangles_submitted"), 0.5 * counters("none", "triangles_submitted"));
  EXPECT_EQ(test::parseJson(readText(folder / "culling_combos.json")).array().size(), 16u);
  EXPECT_GT(readImage(folder / "culling_combos.png").width, 0);
}

// occlusion-queries walked whole and in three shards merged: the same rows but for the
// measured times, and the same table; only the whole run and the merge draw the plot.
TEST(Study, OcclusionQueriesShardedAndMergedEqualsOneRun) {
  const std::string common = std::string(HSR_BINARY) + " study occlusion-queries --frames 8 --size 48x27 --out ";
  const auto whole = freshFolder("queries-whole");
  test::CommandResult result = test::runCommand(common + whole.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::string shards;
  for (int k = 1; k <= 3; ++k) {
    const std::string part = std::to_string(k);
    const auto shard = freshFolder("queries-shard-" + part);
    result = test::runCommand(common + shard.string() + " --shard " + part + "/3");
    ASSERT_EQ(result.exitCode, 0) << result.output;
    EXPECT_FALSE(std::filesystem::exists(shard / "occlusion_queries.png")) << "a shard's plot would show part of the walk";
    shards += ' ';
    shards += shard.string();
  }
  // Each frame's multiqueries (exercise 12.5): CHC++ batches its queries; no other method does.
  {
    std::vector<std::string> header;
    std::int64_t chcppMultiqueries = 0;
    for (const Row& row : readCsv(whole / "occlusion_queries_frames.csv", header)) {
      if (row.at("method") == "chcpp") chcppMultiqueries += std::stoll(row.at("multiqueries"));
      else EXPECT_EQ(row.at("multiqueries"), "0") << row.at("method");
    }
    EXPECT_GT(chcppMultiqueries, 0);
  }
  const auto merged = freshFolder("queries-merged");
  result = test::runCommand(std::string(HSR_BINARY) + " study occlusion-queries --out " + merged.string() + " --merge" + shards);
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_GT(readImage(merged / "occlusion_queries.png").width, 0);
  const std::vector<std::string> measured = {"frame_ms", "waiting_ms", "frame_ms_mean", "frame_ms_variance", "frame_ms_p5", "frame_ms_p95",
                                             "waiting_ms_mean"};
  for (const std::string file : {"occlusion_queries_frames.csv", "occlusion_queries.csv"}) {
    std::vector<std::string> header, mergedHeader;
    const std::vector<Row> one = readCsv(whole / file, header), joined = readCsv(merged / file, mergedHeader);
    EXPECT_EQ(header, mergedHeader) << file;
    ASSERT_EQ(one.size(), joined.size()) << file;
    EXPECT_EQ(one.size(), file == std::string("occlusion_queries.csv") ? 36u : 72u) << "4 levels x 9 methods (x 2 positions)";
    for (std::size_t r = 0; r < one.size(); ++r)
      for (const std::string& column : header)
        if (std::find(measured.begin(), measured.end(), column) == measured.end()) {
          EXPECT_EQ(one[r].at(column), joined[r].at(column)) << file << " row " << r << " " << column;
        }
  }
}

TEST(Render, ExplainSaysWhichPassesRunAndWhy) {
  const auto folder = freshFolder("explain");
  std::filesystem::create_directories(folder);
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " render " + kScenes +
                                                      "cube.toml --explain --size 64x48 -o " + (folder / "cube.png").string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  for (const char* line : {"passes for", "run   visibility: zbuffer", "skip  shadow maps", "effects does not list shadows",
                           "run     corner normals             lambert interpolates them", "decided while rendering:",
                           "normals: 18 corner normals computed, for the 6 triangles shading set up", "clipping: no triangle crosses the near plane",
                           "time per pass", "visibility", "shading"})
    EXPECT_NE(result.output.find(line), std::string::npos) << line << "\n" << result.output;
  const std::string times = result.output.substr(result.output.find("time per pass"));
  EXPECT_EQ(times.find("shadow maps"), std::string::npos) << "no time for a pass that did not run";
  EXPECT_NE(times.find("shading"), std::string::npos);
}

// The far_layers hard case: 0.5 micrometres apart at a distance of 3, below float32's
// step there (about 6e-6) and above reversed float32's (about 2e-7).
TEST(Render, DepthTiesAreCountedAndWarnedAboutWithAFinerFormat) {
  const auto folder = freshFolder("depth-ties");
  std::filesystem::create_directories(folder);
  const std::string command = std::string(HSR_BINARY) + " render " + kScenes + "hard/far_layers.toml -o " + (folder / "x.png").string();
  const test::CommandResult tied = test::runCommand(command + " --stats");
  ASSERT_EQ(tied.exitCode, 0) << tied.output;
  const std::size_t warning = tied.output.find("hsr: warning: ");
  ASSERT_NE(warning, std::string::npos) << tied.output;
  const std::string line = tied.output.substr(warning, tied.output.find('\n', warning) - warning);
  for (const char* part : {" depth ties: fragments of different triangles stored at the same float32 depth",
                           "reversed-float32 resolves ", "at the farthest visible depth (3.", " where float32 resolves "})
    EXPECT_NE(line.find(part), std::string::npos) << part << "\n" << line;
  EXPECT_TRUE(std::filesystem::exists(folder / "x.png")) << "a warning, not an error: the image is written";
  // Without --stats or --explain, one short note: ties are common, and not a failure.
  const test::CommandResult noted = test::runCommand(command);
  ASSERT_EQ(noted.exitCode, 0) << noted.output;
  EXPECT_EQ(noted.output.rfind("hsr: note: ", 0), 0u) << noted.output;
  EXPECT_EQ(std::count(noted.output.begin(), noted.output.end(), '\n'), 1) << noted.output;
  EXPECT_LE(noted.output.size(), 120u) << noted.output;
  EXPECT_NE(noted.output.find(" depth ties (fragments at one float32 depth, ordered by drawing order); --stats says more"),
            std::string::npos) << noted.output;
  const test::CommandResult resolved = test::runCommand(command + " --depth-format reversed-float32 --explain");
  ASSERT_EQ(resolved.exitCode, 0) << resolved.output;
  EXPECT_EQ(resolved.output.find("warning"), std::string::npos) << resolved.output;
  const std::size_t table = resolved.output.find("depth resolution (the smallest separation stored apart) at the nearest (2.");
  ASSERT_NE(table, std::string::npos) << resolved.output;
  for (const std::string& format : depthFormatNames()) EXPECT_NE(resolved.output.find("  " + format + " ", table), std::string::npos) << format;
  // An exact tie (the coplanar case's left pair) no format resolves: the warning says so.
  const test::CommandResult coplanar = test::runCommand(std::string(HSR_BINARY) + " render " + kScenes +
                                                        "hard/coplanar.toml --depth-format reversed-float32 --stats -o " + (folder / "c.png").string());
  EXPECT_NE(coplanar.output.find("no format resolves finer than reversed-float32's"), std::string::npos) << coplanar.output;
}

// hsr why follows the z-buffer's fragments at a pixel. On far_layers the back layer's
// fragment ties with the front's in float32 and loses the depth test in reversed float32;
// with the depth test off it replaces the front, which the verdict names. On counters at
// unorm16, a tie kept by drawing order loses the reference's triangle.
TEST(Why, FollowsTheZbuffersFragmentsAndSaysWhatLostTheReferencesTriangle) {
  const std::string why = std::string(HSR_BINARY) + " why " + kScenes;
  const std::string farLayers = why + "hard/far_layers.toml --pixel 160,120 --size 320x240";
  const test::CommandResult float32 = test::runCommand(farLayers);
  ASSERT_EQ(float32.exitCode, 0) << float32.output;
  for (const char* line : {"pixel (160, 120): 2 events, in the order the algorithm's loop met them",
                           "1. triangle 0 of \"front\": written: nearer than what the pixel held",
                           "depth stored 0.967974126, the pixel held the far end (cleared)",
                           "2. triangle 2 of \"back\": tie: the same stored depth; the triangle drawn first keeps the pixel",
                           "the exact reference: triangle 0 of \"front\" at distance 3.0308671", "=> agrees with the exact reference"})
    EXPECT_NE(float32.output.find(line), std::string::npos) << line << "\n" << float32.output;
  const test::CommandResult reversed = test::runCommand(farLayers + " --depth-format reversed-float32");
  EXPECT_NE(reversed.output.find("2. triangle 2 of \"back\": lost the depth test"), std::string::npos) << reversed.output;
  const test::CommandResult untested = test::runCommand(farLayers + " --knob depth-test=off");
  EXPECT_NE(untested.output.find("=> differs: the reference shows triangle 0 of \"front\", which was shown (event 1) and then "
                                 "replaced by triangle 2 of \"back\" (event 2: written (no depth test))"),
            std::string::npos) << untested.output;
  const std::string counters = why + "counters.toml --pixel 225,89 --size 320x180";
  const test::CommandResult unorm16 = test::runCommand(counters + " --depth-format unorm16 --json");
  ASSERT_EQ(unorm16.exitCode, 0) << unorm16.output;
  EXPECT_EQ(unorm16.output.rfind("{\"scene\": ", 0), 0u) << unorm16.output;
  for (const char* part : {"\"agrees\": false", "\"verdict\": \"differs: the reference shows triangle ", ", not shown after event 4: tie: the same stored depth"})
    EXPECT_NE(unorm16.output.find(part), std::string::npos) << part << "\n" << unorm16.output;
  const test::CommandResult finer = test::runCommand(counters + " --depth-format reversed-float32");
  EXPECT_NE(finer.output.find("=> agrees with the exact reference"), std::string::npos) << finer.output;
}

// hsr why --step N: on far_layers the z-buffer records a step per triangle drawn, then its
// overdraw and the finished image, as hsr render --steps does; by the first step only the
// front layer's fragment has reached the pixel, by the third the back's tie too.
TEST(Why, AtAStepShowsTheEventsBeforeItUnderThatStepsCaption) {
  const std::string why = std::string(HSR_BINARY) + " why " + kScenes + "hard/far_layers.toml --pixel 160,120 --size 320x240 --step ";
  const test::CommandResult first = test::runCommand(why + "1");
  ASSERT_EQ(first.exitCode, 0) << first.output;
  for (const char* line : {"up to step 1 of 5: step 2, depth test: triangle 1 of 3 drawn (red)",
                           "pixel (160, 120): 1 event by step 1 (of 2 in all), in the order the algorithm's loop met them",
                           "1. triangle 0 of \"front\": written: nearer than what the pixel held",
                           "by step 1 it shows triangle 0 of \"front\"; 1 event follows", "in the end it shows triangle 0 of \"front\" at distance",
                           "=> agrees with the exact reference"})
    EXPECT_NE(first.output.find(line), std::string::npos) << line << "\n" << first.output;
  EXPECT_EQ(first.output.find("2. triangle 2"), std::string::npos) << "the back layer's fragment comes after step 1\n" << first.output;
  const test::CommandResult third = test::runCommand(why + "3 --json");
  ASSERT_EQ(third.exitCode, 0) << third.output;
  for (const char* part : {"\"step\": {\"number\": 3, \"of\": 5, \"caption\": \"step 2, depth test: triangle 3 of 3 drawn", "\"events_by_step\": 2"})
    EXPECT_NE(third.output.find(part), std::string::npos) << part << "\n" << third.output;
  const test::CommandResult finished = test::runCommand(why + "5");
  EXPECT_NE(finished.output.find("up to step 5 of 5: the finished image"), std::string::npos) << finished.output;
}

// The painter on the cyclic overlap: the depth sort paints "third" (farther) over
// "second", which the verdict names; Newell's order, with "third" cut, paints them right.
TEST(Why, FollowsThePaintersPiecesAndSaysWhichPaintedOverTheReferencesTriangle) {
  const std::string why = std::string(HSR_BINARY) + " why " + kScenes + "hard/cyclic_overlap.toml --pixel 98,44 --algo painter --variant ";
  const test::CommandResult sort = test::runCommand(why + "sort");
  ASSERT_EQ(sort.exitCode, 0) << sort.output;
  for (const char* line : {"1. triangle 2 of \"second\": painted over what the pixel showed",
                           "piece 5 of 6 in the order, back to front (its whole triangle); distance 8.541",
                           "=> differs: the reference shows triangle 2 of \"second\", which was shown (event 1) and then replaced by "
                           "triangle 4 of \"third\" (event 2: painted over what the pixel showed)"})
    EXPECT_NE(sort.output.find(line), std::string::npos) << line << "\n" << sort.output;
  const test::CommandResult newell = test::runCommand(why + "newell");
  for (const char* line : {"1. triangle 4 of \"third\": painted over what the pixel showed", "(the part of its triangle cut out by 1 plane)",
                           "=> agrees with the exact reference"})
    EXPECT_NE(newell.output.find(line), std::string::npos) << line << "\n" << newell.output;
}

// Warnock on counters at 160 x 90: the chain of windows down to pixel (14, 37), each
// subdivided, then the rule that decided the last. At the smallest size of 8 the window
// 5 x 3 at (10, 37) is decided by its central pixel (12, 38), which the reference's
// triangle does not cover: the verdict names that; at one pixel the rule is exact.
TEST(Why, FollowsWarnocksWindowsDownToThePixelAndNamesTheRuleThatDecidedIt) {
  const std::string why = std::string(HSR_BINARY) + " why " + kScenes + "counters.toml --size 160x90 --algo warnock --pixel 14,37";
  const test::CommandResult coarse = test::runCommand(why + " --knob smallest-window=8");
  ASSERT_EQ(coarse.exitCode, 0) << coarse.output;
  for (const char* line : {"1. window 160 x 90 at (0, 0): subdivided into four: no rule decides it",
                           "5. window 10 x 6 at (10, 34): subdivided into four",
                           "6. window 5 x 3 at (10, 37): the smallest window: decided by the polygon nearest at its central pixel (12, 38) "
                           "(--knob smallest-window=8)",
                           "=> differs: the reference shows triangle 2305 of \"counter\" copy 3, not shown after event ",
                           ": does not cover the window's central pixel (12, 38): at the smallest size only the central pixel's center is tested"})
    EXPECT_NE(coarse.output.find(line), std::string::npos) << line << "\n" << coarse.output;
  const test::CommandResult exact = test::runCommand(why);
  ASSERT_EQ(exact.exitCode, 0) << exact.output;
  for (const char* line : {"fills the window: it surrounds it and is nearer than every other there", "=> agrees with the exact reference"})
    EXPECT_NE(exact.output.find(line), std::string::npos) << line << "\n" << exact.output;
}

// Ray casting on far_layers: the BVH's nodes and each triangle tested, in the textbook
// traversal's order (whatever the path), the back layer met beyond the nearest hit; the
// naive variant tests the same triangles without nodes; the march names the triangle
// nearest to where its samples entered the front layer.
TEST(Why, FollowsRayCastingsNodesAndTrianglesTested) {
  const std::string why = std::string(HSR_BINARY) + " why " + kScenes + "hard/far_layers.toml --pixel 160,120 --size 320x240 --algo ray_casting";
  for (const char* path : {" --knob path=packet", " --knob path=scalar"}) {
    const test::CommandResult bvh = test::runCommand(why + path);
    ASSERT_EQ(bvh.exitCode, 0) << bvh.output;
    for (const char* line : {"pixel (160, 120): 6 events", "1. BVH node 0: the nearer child first, the farther stacked",
                             "2. BVH node 1: a leaf: its 2 triangles tested", "3. triangle 0 of \"front\": nearest so far",
                             "(of one sign: inside); distance 3.03086711", "4. triangle 1 of \"front\": missed: the ray passes outside an edge",
                             "5. BVH node 2: a leaf: its 1 triangle tested",
                             "6. triangle 2 of \"back\": met, but beyond the nearest hit so far", "=> agrees with the exact reference"})
      EXPECT_NE(bvh.output.find(line), std::string::npos) << path << ": " << line << "\n" << bvh.output;
  }
  const test::CommandResult naive = test::runCommand(why + " --knob variant=naive");
  ASSERT_EQ(naive.exitCode, 0) << naive.output;
  EXPECT_NE(naive.output.find("pixel (160, 120): 3 events"), std::string::npos) << naive.output;
  EXPECT_EQ(naive.output.find("BVH node"), std::string::npos) << naive.output;
  const test::CommandResult march = test::runCommand(why + " --knob variant=march");
  ASSERT_EQ(march.exitCode, 0) << march.output;
  for (const char* line : {"sample ", ": inside an object: the march stops",
                           "triangle 0 of \"front\": named: the triangle of that object nearest to where the ray entered it",
                           "shows triangle 0 of \"front\""})
    EXPECT_NE(march.output.find(line), std::string::npos) << line << "\n" << march.output;
}

// Watkins on the interpenetrating pair, row 80: the span from column 71 to 130 holds both
// triangles, nearest at different ends; by default it is split at column 100 where they
// cross, and with split=none the left end's nearest fills it, which the verdict names.
// The A-buffer's fragments at pixel (71, 80), front to back, with their masks.
TEST(Why, FollowsWatkinssSpansAndTheAbuffersFragments) {
  const std::string why = std::string(HSR_BINARY) + " why " + kScenes + "hard/interpenetrating.toml --pixel 125,80 --algo watkins";
  const test::CommandResult split = test::runCommand(why);
  ASSERT_EQ(split.exitCode, 0) << split.output;
  for (const char* line : {"1. row 80: cut into spans where the polygons' edges cross it", "2 active polygons, 4 crossings",
                           "2. span 71..130 of row 80: the nearest differs between its ends (or is within rounding): split at column 100",
                           "span 100..130 of row 80: nearest at both ends by more than rounding", "=> agrees with the exact reference"})
    EXPECT_NE(split.output.find(line), std::string::npos) << line << "\n" << split.output;
  const test::CommandResult none = test::runCommand(why + " --knob split=none");
  ASSERT_EQ(none.exitCode, 0) << none.output;
  EXPECT_NE(none.output.find("=> differs: the reference shows triangle 0 of \"pair\", not shown after event 2: present in span 71..130 "
                             "of row 80, not the one the rule chose"),
            std::string::npos) << none.output;
  const test::CommandResult abuffer =
      test::runCommand(std::string(HSR_BINARY) + " why " + kScenes + "hard/interpenetrating.toml --pixel 71,80 --algo abuffer");
  ASSERT_EQ(abuffer.exitCode, 0) << abuffer.output;
  for (const char* line : {"1. triangle 1 of \"pair\": fragment 1 of 2 front to back",
                           "mask ####/####/####/####: covers 16 of 16 subsamples; opacity 1; its share 1",
                           "2. triangle 0 of \"pair\": fragment 2 of 2 front to back", "mask ..##/.###/.###/####: covers 12 of 16 subsamples",
                           "3. triangle 1 of \"pair\": resolved: the id image names the surface with the largest share",
                           "=> agrees with the exact reference"})
    EXPECT_NE(abuffer.output.find(line), std::string::npos) << line << "\n" << abuffer.output;
}

// Weiler-Atherton on the cyclic overlap at (98, 44): "third" comes first in the sort and
// clips, "second" lies inside its outline and in front, so it clips the inside list in
// turn (one recursion), where "third" is behind it and removed; "second" is drawn.
TEST(Why, FollowsWeilerAthertonsClipPolygonsAndPieces) {
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " why " + kScenes +
                                                      "hard/cyclic_overlap.toml --pixel 98,44 --algo weiler_atherton");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  for (const char* line : {"pixel (98, 44): 5 events", "1. triangle 4 of \"third\": the clip polygon's own piece, inside its outline",
                           "2. triangle 2 of \"second\": in front of the clip polygon at every corner: it clips the inside list in turn",
                           "3. triangle 4 of \"third\": removed: inside the clip polygon's outline and behind it at every corner",
                           "clip polygon: triangle 2; a piece of 4 corners, 1 recursion deep",
                           "5. triangle 2 of \"second\": drawn: a visible piece, scan-converted", "=> agrees with the exact reference"})
    EXPECT_NE(result.output.find(line), std::string::npos) << line << "\n" << result.output;
  // Where the interpenetrating pair cross, each piece is kept only where it is nearer.
  const test::CommandResult crossing = test::runCommand(std::string(HSR_BINARY) + " why " + kScenes +
                                                        "hard/interpenetrating.toml --pixel 125,80 --algo weiler_atherton");
  for (const char* line : {"kept where nearer: its plane crosses the clip polygon's", "nearer here than the triangles it passes through (1)",
                           "6. triangle 1 of \"pair\": not drawn here: a polygon it passes through is nearer", "=> agrees with the exact reference"})
    EXPECT_NE(crossing.output.find(line), std::string::npos) << line << "\n" << crossing.output;
}

// Appel's walk along an edge of the blocks: edge 2, the slab's contour, walked from its
// end at vertex 6 (QI 0), passes behind two contours in front of it and comes out from
// behind one, arriving at vertex 2 with QI 1; asked by a pixel, the nearest edge.
TEST(Why, FollowsAppelsWalkAlongAnEdge) {
  const std::string why = std::string(HSR_BINARY) + " why " + kScenes + "blocks.toml --size 320x240 --algo appel --edge ";
  const test::CommandResult walk = test::runCommand(why + "2");
  ASSERT_EQ(walk.exitCode, 0) << walk.output;
  for (const char* line : {"edge 2, the contour edge of \"slab\", from (142.018, 111.719) to (74.226, 135.645) in pixels",
                           "1. at u = 1: the walk starts at vertex 6, of QI 0",
                           "2. at u = 0.51675934: +1: it passes behind the contour edge from vertex 56 to vertex 66, which lies in front of this edge there",
                           "4. at u = 0.120809212: -1: it comes out from behind the contour edge from vertex 61 to vertex 71",
                           "5. at u = 0: the walk arrives at vertex 2",
                           "its pieces: 0 to 0.120809212 QI 1; 0.120809212 to 0.196959777 QI 2; 0.196959777 to 0.51675934 QI 1; "
                           "0.51675934 to 1 QI 0 (visible)\n",
                           "the exact line reference: visible 0.51675934 to 1", "=> agrees with the exact line reference"})
    EXPECT_NE(walk.output.find(line), std::string::npos) << line << "\n" << walk.output;
  const test::CommandResult near = test::runCommand(why + "160,120 --json");
  ASSERT_EQ(near.exitCode, 0) << near.output;
  for (const char* part : {"\"edge\": 16,", "\"pixels_away\": 0.94", "\"agrees\": true", "\"from\": [159.586396", "\"to\": [159.557976"})
    EXPECT_NE(near.output.find(part), std::string::npos) << part << "\n" << near.output;
}

// Roberts along the same edge: with the grid off, every body is looked at. The slab is
// the edge's own, the prism's box misses it, the pyramid's inequalities leave no u, and
// the tower and the ball hide the parts that make its hidden piece; the exact line
// reference agrees within rounding. An edge between two back faces is step 1's alone.
TEST(Why, FollowsRobertsTestOfEachBodyAlongAnEdge) {
  const std::string why = std::string(HSR_BINARY) + " why " + kScenes + "blocks.toml --size 320x240 --algo roberts --knob grid=off --edge ";
  const test::CommandResult tests = test::runCommand(why + "2");
  ASSERT_EQ(tests.exitCode, 0) << tests.output;
  for (const char* line : {"5 events, in the order the algorithm met them", "1. body \"slab\": not tested: the edge lies on it",
                           "2. at u = 0: body \"tower\": hides part of it: u = 0 to 0.196959776",
                           "3. body \"prism\": ruled out by the minimax test\n     its projected box misses the edge's",
                           "4. body \"pyramid\": hides none of it\n     5 face planes along the sight lines from the edge: 2 bound alpha from above, "
                           "3 from below, 0 are parallel to the sight lines; every pair of bounds, alpha > 0 and the parallel planes leave u nowhere in (0, 1)",
                           "5. at u = 0.120809213: body \"ball\": hides part of it: u = 0.120809213 to 0.51675934",
                           "its pieces: 0 to 0.51675934 hidden; 0.51675934 to 1 QI 0 (visible)\n",
                           "=> agrees with the exact line reference within 0.001 pixel"})
    EXPECT_NE(tests.output.find(line), std::string::npos) << line << "\n" << tests.output;
  const test::CommandResult own = test::runCommand(why + "0 --json");
  ASSERT_EQ(own.exitCode, 0) << own.output;
  for (const char* part : {"\"u\": null, \"change\": 0, \"subject\": \"\", \"outcome\": \"hidden by its own body (step 1)\"", "\"agrees\": true",
                           "\"decisions\": [\"hidden by its own body (step 1)\", \"not tested\", \"ruled out by the minimax test\", \"hides none of it\", "
                           "\"hides part of it\"]"})
    EXPECT_NE(own.output.find(part), std::string::npos) << part << "\n" << own.output;
}

// The floating horizon along one segment of the ripple: curve 11 of 41 in the order,
// its start between the horizons (a hair under the upper one), the upper horizon crossed
// at u = 0.763: visible from there. The exact drawing sees none of it: the horizon is
// straight between column centers, and the curve in front is not.
TEST(Why, FollowsTheFloatingHorizonAlongASegment) {
  const test::CommandResult segment =
      test::runCommand(std::string(HSR_BINARY) + " why " + kScenes + "ripple.toml --size 320x240 --algo floating_horizon --edge 3407");
  ASSERT_EQ(segment.exitCode, 0) << segment.output;
  for (const char* line : {"1. curve 11 of 41, front to back", "2. at u = 0: its start: between the horizons: hidden",
                           "the segment at y = 155.806657, the upper horizon at y = 155.759328, the lower at y = 190.027817",
                           "4. at u = 0.763485192: the upper horizon: visible from here", "5. then the curve raises the horizons",
                           "its pieces: 0 to 0.763485192 hidden; 0.763485192 to 1 QI 0 (visible)", "the exact line reference: visible nowhere",
                           "=> differs: it and the exact line reference disagree on 0.147 of the edge's 0.623 pixels"})
    EXPECT_NE(segment.output.find(line), std::string::npos) << line << "\n" << segment.output;
}

// Inside a culling stage: on the gap case the center rule culls the box seen through the
// gap, and its test says why (every texel of its footprint holds the wall); the
// conservative rule keeps it, at the first texel no wall covers entirely, and with the
// pyramid, at the level where the footprint spans 2x2 texels. The portal search names
// the cells a chain reached.
TEST(Why, SaysWhatACullingStagesTestFound) {
  const std::string why = std::string(HSR_BINARY) + " why " + kScenes + "hard/occ_gap.toml --pixel 161,120 --cull ";
  const test::CommandResult center = test::runCommand(why + "occlusion:raster=center");
  ASSERT_EQ(center.exitCode, 0) << center.output;
  for (const char* line : {"the test found every texel of its footprint on the 256x128 map (x 123 to 134, y 60 to 67) holds an occluder nearer "
                           "than its box's nearest point (distance 7.84999896)",
                           "=> differs: the reference shows triangle 34 of \"seen through the gap\", which the culling stage "
                           "occlusion:depth-map:raster=center removed before the algorithm ran"})
    EXPECT_NE(center.output.find(line), std::string::npos) << line << "\n" << center.output;
  const test::CommandResult conservative = test::runCommand(why + "occlusion");
  ASSERT_EQ(conservative.exitCode, 0) << conservative.output;
  EXPECT_NE(conservative.output.find("the test found texel (128, 60) of the 256x128 map holds no occluder, not nearer than its box's nearest "
                                     "point (distance 7.84999896): it may show there"), std::string::npos) << conservative.output;
  const test::CommandResult pyramid = test::runCommand(why + "occlusion:pyramid=on");
  ASSERT_EQ(pyramid.exitCode, 0) << pyramid.output;
  EXPECT_NE(pyramid.output.find("the test found texel (16, 7) of pyramid level 3 of the 256x128 map holds no occluder"), std::string::npos)
      << pyramid.output;
  const test::CommandResult portals =
      test::runCommand(std::string(HSR_BINARY) + " why " + kScenes + "hard/portal_rooms.toml --size 320x180 --pixel 160,90 --cull portals");
  ASSERT_EQ(portals.exitCode, 0) << portals.output;
  EXPECT_NE(portals.output.find("the test found a chain of portals from the eye's cell reaches its cells \"room 0 0\", \"room 1 0\", and its "
                                "box lies within a view narrowed through the portals"), std::string::npos) << portals.output;
  // An occlusion query's count: 12 of the box's fragments pass through the gap, which a
  // threshold of 20 calls hidden.
  const test::CommandResult query = test::runCommand(why + "occlusion:queries:stop-and-wait:threshold=20");
  ASSERT_EQ(query.exitCode, 0) << query.output;
  for (const char* line : {"the test found for its leaf of the hierarchy (depth 1): its query, waited for: 12 of its box's fragments passed the depth "
                           "test (visible: more than 20): hidden, nothing below it drawn",
                           "which the culling stage occlusion:queries:stop-and-wait:threshold=20 removed before the algorithm ran"})
    EXPECT_NE(query.output.find(line), std::string::npos) << line << "\n" << query.output;
}

// Culling before the z-buffer on hard/cull_off_center: the view-direction backface test
// removes the left cube's inner side, which faces the eye; the history leads with each
// stage's fate for the reference's triangle, and the verdict names the stage. The
// eye-position test keeps it, and so does the frustum stage after it.
TEST(Why, NamesTheCullingStageThatRemovedTheReferencesTriangle) {
  const std::string why = std::string(HSR_BINARY) + " why " + kScenes + "hard/cull_off_center.toml --pixel 72,120 --cull ";
  const test::CommandResult wrong = test::runCommand(why + "backface:view-direction,frustum");
  ASSERT_EQ(wrong.exitCode, 0) << wrong.output;
  for (const char* line : {"1. culling stage backface:view-direction: removed the reference's triangle; its test: the normal against the view direction "
                           "only: wrong under perspective, kept to show why",
                           "pixel (72, 120): 1 event, in the order they happened: the culling stages', then the algorithm's loop's",
                           "of its object's 12 triangles given to the stage, it kept 4", "shows the background",
                           "for the triangle the test found its normal turns away from the eye along the view axis (cosine -0.258819045); the "
                           "eye itself lies in front of its plane, 0.63137085 from it",
                           "=> differs: the reference shows triangle 3 of \"left\", which the culling stage backface:view-direction removed "
                           "before the algorithm ran"})
    EXPECT_NE(wrong.output.find(line), std::string::npos) << line << "\n" << wrong.output;
  EXPECT_EQ(wrong.output.find("culling stage frustum"), std::string::npos) << "no stage after the one that removed it\n" << wrong.output;
  const test::CommandResult right = test::runCommand(why + "backface,frustum");
  ASSERT_EQ(right.exitCode, 0) << right.output;
  for (const char* line : {"1. culling stage backface:object: kept the reference's triangle",
                           "of its object's 12 triangles given to the stage, it kept 4; for the triangle the test found the eye lies in front of its "
                           "plane, 0.63137085 from it",
                           "2. culling stage frustum:sphere: kept the reference's triangle", "of its object's 4 triangles given to the stage, it kept 4",
                           "=> agrees with the exact reference"})
    EXPECT_NE(right.output.find(line), std::string::npos) << line << "\n" << right.output;
}

TEST(Study, EffectsAddsEachEffectInTurnAndTimesItsPass) {
  const auto folder = freshFolder("study-effects");
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " study effects --frames 1 --size 160x100 --out " +
                                                      folder.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::vector<std::string> header;
  const std::vector<Row> rows = readCsv(folder / "effects.csv", header);
  ASSERT_EQ(rows.size(), 8u);
  EXPECT_EQ(rows.front().at("step"), "none");
  EXPECT_EQ(number(rows.front(), "ratio_to_none"), 1);
  const std::vector<std::pair<std::string, std::string>> firstWith = {{"+ shadows", "shadow maps_ms"}, {"+ transparency", "transparency_ms"},
                                                                       {"+ fog", "fog_ms"}, {"+ outline", "outline_ms"}};
  for (const auto& [step, column] : firstWith) {
    bool reached = false;
    for (const Row& row : rows) {
      reached = reached || row.at("step") == step;
      if (reached) {
        EXPECT_GT(number(row, column), 0) << row.at("step") << ": " << column;
      } else {
        EXPECT_EQ(number(row, column), 0) << row.at("step") << " spends nothing on " << column;
      }
    }
  }
  EXPECT_GT(readImage(folder / "effects_steps.png").width, 8 * 256);
  EXPECT_GT(readImage(folder / "effects.png").width, 0);
}

TEST(Study, ShadowMapShowsAcneWithoutBiasAndLessErrorAtHigherResolution) {
  const auto folder = freshFolder("study-shadow-map");
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " study shadow-map --frames 1 --size 160x100 --out " +
                                                      folder.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::vector<std::string> header;
  const std::vector<Row> rows = readCsv(folder / "shadow_map.csv", header);
  ASSERT_EQ(rows.size(), 42u);  // six resolutions, seven biases
  std::map<std::string, Row> at;
  for (const Row& row : rows) at[row.at("resolution") + "/" + row.at("bias_texels")] = row;
  for (const char* resolution : {"128", "1024", "4096"}) {
    const Row& acne = at.at(std::string(resolution) + "/0");
    const Row& biased = at.at(std::string(resolution) + "/1.5");
    EXPECT_GT(number(acne, "falsely_shadowed"), 10 * number(biased, "falsely_shadowed") + 10) << resolution;
    EXPECT_GE(number(at.at(std::string(resolution) + "/12"), "falsely_lit"), number(biased, "falsely_lit")) << resolution;
  }
  EXPECT_LT(number(at.at("4096/1.5"), "error_fraction"), number(at.at("128/1.5"), "error_fraction"));
  EXPECT_GT(readImage(folder / "shadow_map.png").width, 0);
}

// Ctrl-C after the first configuration: the sweep stops after the row it is measuring
// and writes the rows measured so far, complete and parseable, and exits with 130.
// Runs an hsr command line and sends it SIGINT (Ctrl-C) when it prints a line starting
// with `prefix`: its exit status (-1 unless it exited) and everything it printed.
struct Interrupted {
  bool sent = false;
  int exitCode = -1;
  std::string output;
};
Interrupted interruptAfter(const std::string& arguments, const std::string& prefix) {
  Interrupted result;
  // The shell prints its process id, then becomes hsr (exec keeps the id).
  FILE* pipe = popen(("echo $$; exec " + std::string(HSR_BINARY) + " " + arguments + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  char line[4096];
  if (!std::fgets(line, sizeof line, pipe)) return result;
  const pid_t hsr = static_cast<pid_t>(std::stol(line));
  while (std::fgets(line, sizeof line, pipe)) {
    result.output += line;
    if (!result.sent && std::string(line).rfind(prefix, 0) == 0) {
      kill(hsr, SIGINT);
      result.sent = true;
    }
  }
  const int status = pclose(pipe);
  if (WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
  return result;
}

// How many rows an interrupted run says it measured, of how many.
std::size_t measuredRows(const std::string& output, const std::string& planned) {
  std::smatch match;
  if (!std::regex_search(output, match, std::regex("hsr: interrupted: (\\d+) of " + planned + " measured; their rows are written")))
    return 0;
  return std::stoul(match[1].str());
}

TEST(Sweep, CtrlCKeepsTheRowsAlreadyMeasured) {
  const auto folder = freshFolder("sweep-interrupted");
  const std::string sizes = "--knob size=320x240,330x248,340x255,350x263,360x270,370x278,380x285,390x293,400x300,410x308";
  const Interrupted run = interruptAfter("sweep " + kScenes + "bunny.toml --algo zbuffer " + sizes +
                                         " --repeat 3 --threads 1 --out " + folder.string(), "  1/10 ");
  const std::string& output = run.output;
  ASSERT_TRUE(run.sent) << output;
  EXPECT_EQ(run.exitCode, 130) << output;
  const std::size_t measured = measuredRows(output, "10 configurations");
  EXPECT_GE(measured, 1u) << output;
  EXPECT_LT(measured, 10u);
  std::vector<std::string> header;
  const std::vector<Row> rows = readCsv(folder / "sweep.csv", header);
  EXPECT_EQ(rows.size(), measured);
  for (const Row& row : rows) expectConsistentMeasurements(row);
  EXPECT_EQ(test::parseJson(readText(folder / "sweep.json")).array().size(), measured);
}

// A study stops the same way: here after the first line of the shadow-map table (six
// rows, one per resolution, at bias 0), with the rows measured in its CSV and no plot.
// Interrupts `hsr study ARGUMENTS` when it prints a line starting with `prefix`: it must
// exit with 130 and say it measured at least `atLeast` and fewer than all `total` of its
// `unit`; returns how many.
std::size_t interruptStudy(const std::string& arguments, const std::string& prefix, std::size_t atLeast, std::size_t total,
                           const std::string& unit) {
  const Interrupted run = interruptAfter("study " + arguments, prefix);
  EXPECT_TRUE(run.sent) << run.output;
  EXPECT_EQ(run.exitCode, 130) << run.output;
  const std::size_t measured = measuredRows(run.output, std::to_string(total) + " " + unit);
  EXPECT_GE(measured, atLeast) << run.output;
  EXPECT_LT(measured, total) << run.output;
  return measured;
}

TEST(Study, CtrlCKeepsTheRowsAlreadyMeasured) {
  const auto folder = freshFolder("study-interrupted");
  const std::size_t measured = interruptStudy("shadow-map --size 160x100 --frames 1 --out " + folder.string(), "  0 ", 6, 42, "rows");
  std::vector<std::string> header;
  const std::vector<Row> rows = readCsv(folder / "shadow_map.csv", header);
  EXPECT_EQ(rows.size(), measured);
  for (const Row& row : rows) EXPECT_EQ(row.size(), header.size());
  EXPECT_FALSE(std::filesystem::exists(folder / "shadow_map.png")) << "a plot of part of a study misleads";
}

// occlusion-queries stops after the segment in progress: its frames' rows, the table of
// what was walked, and no plot.
TEST(Study, CtrlCKeepsTheSegmentsAlreadyWalked) {
  const auto folder = freshFolder("queries-interrupted");
  const std::size_t measured =
      interruptStudy("occlusion-queries --frames 400 --size 160x90 --out " + folder.string(), "  city, positions 0-49", 1, 8, "segments");
  std::vector<std::string> header;
  EXPECT_EQ(readCsv(folder / "occlusion_queries_frames.csv", header).size(), measured * 50 * 9) << "50 positions, 9 methods a segment";
  EXPECT_FALSE(readCsv(folder / "occlusion_queries.csv", header).empty());
  EXPECT_FALSE(std::filesystem::exists(folder / "occlusion_queries.png")) << "a plot of part of a study misleads";
}

TEST(Sweep, DepthPrecisionBuysAccuracyOnTheCoplanarCase) {
  const auto folder = freshFolder("sweep");
  const test::CommandResult result =
      test::runCommand(std::string(HSR_BINARY) + " sweep " + kScenes + "hard/coplanar.toml --algo zbuffer " +
                       "--knob depth-format=unorm16,unorm24,float32,reversed-float32 --repeat 1 --out " + folder.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::vector<std::string> header;
  const std::vector<Row> rows = readCsv(folder / "sweep.csv", header);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(header[3], "depth-format");
  EXPECT_EQ(header[header.size() - 3], "pareto");
  EXPECT_EQ(header.back(), "pass_ms");
  std::map<std::string, double> error;
  int onFront = 0;
  for (const Row& row : rows) {
    expectConsistentMeasurements(row);
    error[row.at("depth-format")] = number(row, "pixel_error");
    onFront += row.at("pareto") == "1";
  }
  EXPECT_GT(error["unorm16"], 10 * error["unorm24"]);
  EXPECT_GT(error["float32"], error["reversed-float32"]);
  EXPECT_GE(onFront, 1);
  EXPECT_EQ(test::parseJson(readText(folder / "sweep.json")).array().size(), 4u);
  EXPECT_GT(readImage(folder / "sweep.png").width, 0);
  EXPECT_NE(readText(folder / "sweep.svg").find("<svg"), std::string::npos);
  EXPECT_NE(readText(folder / "sweep.gp").find("plot $front"), std::string::npos);
}

// The A-buffer is swept by what it buys: coverage error, which falls as its mask grows,
// ranks its rows and is the plot's axis.
TEST(Sweep, TheABuffersMaskBuysCoverage) {
  const auto folder = freshFolder("sweep-abuffer");
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " sweep " + kScenes +
                                                      "counters.toml --algo abuffer --knob mask=2x2,4x4,8x8 --size 160x90 "
                                                      "--repeat 1 --out " + folder.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  EXPECT_NE(result.output.find("Pareto front of visibility time and coverage error"), std::string::npos) << result.output;
  std::vector<std::string> header;
  const std::vector<Row> rows = readCsv(folder / "sweep.csv", header);
  ASSERT_EQ(rows.size(), 3u);
  for (const Row& row : rows) expectConsistentMeasurements(row);
  EXPECT_LT(number(rows[1], "coverage_error_mixed"), 0.7 * number(rows[0], "coverage_error_mixed"));
  EXPECT_LT(number(rows[2], "coverage_error_mixed"), 0.7 * number(rows[1], "coverage_error_mixed"));
  EXPECT_EQ(rows[2].at("pareto"), "1") << "the most accurate is on the front, however slow";
  EXPECT_NE(readText(folder / "sweep.gp").find("set ylabel 'coverage error"), std::string::npos);
}

TEST(Sweep, ResolutionIsAKnobOfEveryAlgorithm) {
  const auto folder = freshFolder("sweep-size");
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " sweep " + kScenes +
                                                      "cube.toml --knob size=64x48,128x96 --knob variant=full,scanline "
                                                      "--repeat 1 --out " + folder.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::vector<std::string> header;
  const std::vector<Row> rows = readCsv(folder / "sweep.csv", header);
  ASSERT_EQ(rows.size(), 4u);  // the cross product, the first knob varying slowest
  EXPECT_EQ(rows[0].at("size"), "64x48");
  EXPECT_EQ(rows[1].at("variant"), "scanline");
  EXPECT_EQ(rows[2].at("width"), "128");
}

TEST(Sweep, TriangleScalingFitsAnExponent) {
  const auto folder = freshFolder("scale");
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " sweep " + kScenes +
                                                      "cube.toml --scale triangles --size 64x48 --repeat 1 --out " + folder.string());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::vector<std::string> header;
  const std::vector<Row> rows = readCsv(folder / "scale_triangles.csv", header);
  ASSERT_GE(rows.size(), 4u);
  for (std::size_t i = 1; i < rows.size(); ++i)
    EXPECT_EQ(number(rows[i], "triangles"), 4 * number(rows[i - 1], "triangles"));  // n x n copies, n doubling
  EXPECT_GE(number(rows.front(), "triangles"), 1000);
  EXPECT_LE(number(rows.back(), "triangles"), 1.1e6);
  // The printed exponent is the least-squares slope of log time against log triangles
  // over the CSV's rows (checked against the rows, not against a time bound: the
  // machine is shared, and speed belongs in bench/).
  std::smatch fit;
  ASSERT_TRUE(std::regex_search(result.output, fit, std::regex(R"(fit: visibility time ~ triangles\^(-?[0-9.]+))"))) << result.output;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const Row& row : rows) {
    const double x = std::log(number(row, "triangles")), y = std::log(number(row, "visibility_median_ms"));
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double n = double(rows.size());
  EXPECT_NEAR(std::stod(fit[1]), (n * sxy - sx * sy) / (n * sxx - sx * sx), 0.01);  // the CSV rounds to 1e-4 ms
  EXPECT_TRUE(std::filesystem::exists(folder / "scale_triangles.png"));
}

TEST(Diff, ExitsZeroWithinToleranceAndOneBeyond) {
  const std::string golden = std::string(HSR_SOURCE_DIR) + "/images/golden/zbuffer/";
  const auto heatmap = test::outputPath("diff-heat.png");
  std::filesystem::remove(heatmap);
  const std::string cube = golden + "cube.png";
  EXPECT_EQ(test::runCommand(std::string(HSR_BINARY) + " diff " + cube + " " + cube).exitCode, 0);

  // The same scene rendered with another depth format differs only where depth decides.
  const auto other = test::outputPath("diff-cube-unorm16.png");
  ASSERT_EQ(test::runCommand(std::string(HSR_BINARY) + " render " + kScenes + "hard/coplanar.toml --depth-format unorm16 -o " +
                             other.string()).exitCode, 0);
  const test::CommandResult beyond =
      test::runCommand(std::string(HSR_BINARY) + " diff " + golden + "hard/coplanar.png " + other.string() + " --heatmap " + heatmap.string());
  EXPECT_EQ(beyond.exitCode, 1) << beyond.output;
  EXPECT_NE(beyond.output.find("pixels over tolerance 0: "), std::string::npos) << beyond.output;
  EXPECT_EQ(readImage(heatmap).width, 320);
  EXPECT_EQ(test::runCommand(std::string(HSR_BINARY) + " diff " + golden + "hard/coplanar.png " + other.string() +
                             " --tolerance 1").exitCode, 0);
}

}  // namespace
}  // namespace hsr
