// report.html (studies/report.hpp), loaded in a real browser: Debian's chromium, headless.
#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "renderer/image/frame.hpp"
#include "studies/results.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

std::string readText(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// The folder of an hsr run (`arguments` after "hsr"), in this test process's own folder
// (the tests run as parallel processes).
std::filesystem::path folderOfRun(const std::string& name, const std::string& arguments) {
  const auto out = test::outputPath(name + "-" + std::to_string(getpid()));
  std::filesystem::remove_all(out);
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " " + arguments + " --out " + out.string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  return out;
}

// A compare of two algorithms on the cube and a sweep of two depth formats, each made
// once per process and small enough to take well under a second.
const std::filesystem::path& compareFolder() {
  static const std::filesystem::path folder = folderOfRun(
      "report-compare", "compare " + test::sourcePath("scenes/cube.toml").string() + " --algos zbuffer,painter --size 96x72 --repeat 1");
  return folder;
}

const std::filesystem::path& sweepFolder() {
  static const std::filesystem::path folder = folderOfRun(
      "report-sweep", "sweep " + test::sourcePath("scenes/cube.toml").string() + " --knob depth-format=float32,unorm16 --size 96x72 --repeat 1");
  return folder;
}

// Every file the page points at (src= and href=), which must lie beside it.
std::vector<std::string> referencedFiles(const std::string& html) {
  std::vector<std::string> files;
  const std::regex reference(R"((src|href)="([^"#]+)\")");
  for (auto match = std::sregex_iterator(html.begin(), html.end(), reference); match != std::sregex_iterator(); ++match)
    files.push_back((*match)[2]);
  return files;
}

// The page as chromium leaves it after running its script, and what it logged.
struct Loaded {
  std::string dom, log;
};
Loaded loadInChromium(const std::filesystem::path& page, const std::string& fragment) {
  const auto log = test::outputPath("chromium-" + page.parent_path().filename().string() + ".log");  // the folder names the process
  const std::string command = "chromium --headless --no-sandbox --disable-gpu --enable-logging=stderr --v=0 --dump-dom 'file://" +
                              std::filesystem::absolute(page).string() + fragment + "' 2> " + log.string();
  const test::CommandResult result = test::runCommand(command);
  EXPECT_EQ(result.exitCode, 0) << "chromium (scripts/setup.sh installs it): " << result.output;
  return {result.output, readText(log)};
}

TEST(Report, NamesTheCommandAndTheMachineAndHoldsEveryRowOfTheCsv) {
  const std::string html = readText(compareFolder() / "report.html");
  EXPECT_NE(html.find("hsr compare " + test::sourcePath("scenes/cube.toml").string() + " --algos zbuffer,painter"), std::string::npos);
  EXPECT_NE(html.find("cores available"), std::string::npos);
  // The reference and the two algorithms: three rows, and the heading row.
  const std::string csv = readText(compareFolder() / "results.csv");
  const auto lines = std::count(csv.begin(), csv.end(), '\n');
  const std::regex row("<tr>");
  EXPECT_EQ(std::distance(std::sregex_iterator(html.begin(), html.end(), row), std::sregex_iterator()), lines);
  EXPECT_EQ(lines, 4);
}

TEST(Report, EveryFileItPointsAtIsBesideItAndItNeedsNoNetwork) {
  for (const auto& folder : {compareFolder(), sweepFolder()}) {
    const std::string html = readText(folder / "report.html");
    const std::vector<std::string> files = referencedFiles(html);
    EXPECT_FALSE(files.empty());
    for (const std::string& file : files) {
      EXPECT_EQ(file.find('/'), std::string::npos) << file;  // beside it: no path, no scheme, no network
      EXPECT_TRUE(std::filesystem::exists(folder / file)) << folder / file;
    }
    // No address at all but SVG's namespace, which names the kind of element and is never fetched.
    std::string withoutNamespace = html;
    for (std::size_t at; (at = withoutNamespace.find("http://www.w3.org/2000/svg")) != std::string::npos;) withoutNamespace.erase(at, 26);
    EXPECT_EQ(withoutNamespace.find("http"), std::string::npos);
  }
  // The sweep's plot is shown once, as its SVG, and its PNG is listed among the files.
  const std::string sweep = readText(sweepFolder() / "report.html");
  EXPECT_NE(sweep.find("<img src=\"sweep.svg\""), std::string::npos);
  EXPECT_EQ(sweep.find("<img src=\"sweep.png\""), std::string::npos);
}

TEST(Report, LoadsInABrowserWithoutAConsoleMessageAndSortsByAColumn) {
  const Loaded loaded = loadInChromium(compareFolder() / "report.html", "#sort=time_median_ms:desc");
  EXPECT_EQ(loaded.log.find("CONSOLE"), std::string::npos) << loaded.log;
  EXPECT_NE(loaded.dom.find("aria-sort=\"descending\">time_median_ms"), std::string::npos);
  // The rows' time_median_ms, in the order the browser left them: descending.
  const std::string csv = readText(compareFolder() / "results.csv");
  const std::string heading = csv.substr(0, csv.find('\n'));
  const auto column = std::count(heading.begin(), heading.begin() + std::ptrdiff_t(heading.find("time_median_ms")), ',');
  std::vector<double> times;
  const std::regex rowPattern(R"re(<tr>((?:<td(?: class="more")?>[^<]*</td>)+)</tr>)re");
  const std::regex cellPattern(R"re(<td(?: class="more")?>([^<]*)</td>)re");
  for (auto row = std::sregex_iterator(loaded.dom.begin(), loaded.dom.end(), rowPattern); row != std::sregex_iterator(); ++row) {
    const std::string cells = (*row)[1];
    auto cell = std::sregex_iterator(cells.begin(), cells.end(), cellPattern);
    std::advance(cell, column);
    times.push_back(std::stod((*cell)[1]));
  }
  ASSERT_EQ(times.size(), 3u);
  EXPECT_TRUE(std::is_sorted(times.rbegin(), times.rend())) << times[0] << " " << times[1] << " " << times[2];
}

TEST(Report, LeadsWithTheColumnsAReaderComparesFirstAndExplainsEveryColumn) {
  const std::string html = readText(compareFolder() / "report.html");
  const std::string csv = readText(compareFolder() / "results.csv");
  std::istringstream heading(csv.substr(0, csv.find('\n')));
  std::vector<std::string> shown;
  for (std::string column; std::getline(heading, column, ',');) {
    const studies::ColumnMeaning* meaning = studies::columnMeaning(column);
    ASSERT_NE(meaning, nullptr) << column << " has no explanation";
    EXPECT_NE(html.find("<dt>" + column + "</dt><dd>" + meaning->meaning + "</dd>"), std::string::npos) << column;
    if (html.find("<th title=\"" + meaning->meaning) != std::string::npos) shown.push_back(column);
    else EXPECT_NE(html.find("<th class=\"more\" title=\"" + meaning->meaning), std::string::npos) << column;
  }
  const std::vector<std::string> key = {"scene",        "algorithm",    "knobs",          "visibility_median_ms",
                                       "pixel_error",  "wrong_pixels", "coverage_error", "line_error"};
  EXPECT_EQ(shown, key);
}

// hsr compare's gallery: a card per row, each with its picture and error map at the
// scene's size, and the scatter of error against time with a point per surface row.
TEST(Report, CompareLeadsWithEachConfigurationsPictureAndErrorMapAndTheScatter) {
  const std::string gallery = readText(compareFolder() / "gallery.json");
  const std::regex picture(R"re("(picture|errorMap)":"(images/[^"]+\.png)")re");
  std::size_t pictures = 0;
  for (auto match = std::sregex_iterator(gallery.begin(), gallery.end(), picture); match != std::sregex_iterator(); ++match, ++pictures) {
    const Image image = readImage(compareFolder() / (*match)[2].str());
    EXPECT_EQ(image.width, 96) << (*match)[2];
    EXPECT_EQ(image.height, 72) << (*match)[2];
  }
  EXPECT_EQ(pictures, 2u * 3);  // the reference, zbuffer and painter
  EXPECT_NE(gallery.find("\"options\":\"--algo painter\""), std::string::npos);
  const Loaded loaded = loadInChromium(compareFolder() / "report.html", "");
  EXPECT_EQ(loaded.log.find("CONSOLE"), std::string::npos) << loaded.log;
  const auto count = [&](const std::string& pattern) {
    const std::regex expression(pattern);
    return std::distance(std::sregex_iterator(loaded.dom.begin(), loaded.dom.end(), expression), std::sregex_iterator());
  };
  EXPECT_EQ(count(R"re(<article class="card (exact|right|wrong)" id="card-0-\d">)re"), 3);
  EXPECT_EQ(count(R"re(<g class="point">)re"), 3);
  // The contact sheet is listed, not shown: the cards show its pictures at their size.
  EXPECT_EQ(loaded.dom.find("<img src=\"contact_sheet.png\""), std::string::npos);
  EXPECT_NE(loaded.dom.find("href=\"contact_sheet.png\""), std::string::npos);
}

TEST(Report, AScreenshotOfItShowsThePage) {
  const auto screenshot = test::outputPath("report-screenshot-" + std::to_string(getpid()) + ".png");
  std::filesystem::remove(screenshot);
  const test::CommandResult result = test::runCommand("chromium --headless --no-sandbox --disable-gpu --window-size=1000,700 --screenshot=" +
                                                      screenshot.string() + " 'file://" +
                                                      std::filesystem::absolute(compareFolder() / "report.html").string() + "' 2>&1");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const Image image = readImage(screenshot);
  EXPECT_EQ(image.width, 1000);
  // Text and pictures: far from one colour.
  std::size_t dark = 0;
  for (std::size_t p = 0; p < image.pixels.size(); p += std::size_t(image.channels)) dark += image.pixels[p] < 128;
  EXPECT_GT(dark, 1000u);
}

}  // namespace
}  // namespace hsr
