// hsr grade --self-check: the grader graded. Every bug of the catalogue
// (course/bugs/catalogue.toml), built into an hsr of its own (course/bugs/mutant.py),
// must fail its exercise with feedback naming its cause; every correct variant
// (course/variants/) must pass all it claims. Ends with the line
// "caught N of N bugs, M of M correct variants passed".
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "grading/grading.hpp"
#include "renderer/scene/toml_reader.hpp"
#include "renderer/scene/toml_text.hpp"
#include "renderer/util/error.hpp"

namespace hsr::grading {
namespace {

struct Bug {
  std::string name, story;
  int exercise = 0;
  std::vector<std::string> render, expect;
};

struct Variant {
  std::string folder, story;
  int exercise = 0;
  std::vector<std::string> environment;  // "NAME=VALUE": what its make reads
};

std::vector<std::string> strings(TableReader& table, const std::string& key) {
  std::vector<std::string> words;
  const toml::array* array = table.array(key);
  if (!array) table.fail(nullptr, key, "is missing; expected a list of strings");
  for (const toml::node& node : *array) {
    if (!node.is_string()) table.fail(&node, key, "expected a list of strings");
    words.push_back(node.as_string()->get());
  }
  return words;
}

void readCatalogue(const std::filesystem::path& file, std::vector<Bug>& bugs, std::vector<Variant>& variants) {
  const toml::table root = parseTomlText(readInputFile(file, "catalogue"), file.string());
  TableReader reader(root, "", file);
  reader.rejectUnknown({"bug", "variant"});
  for (const char* kind : {"bug", "variant"}) {
    const toml::array* entries = reader.array(kind);
    if (!entries) continue;
    for (std::size_t k = 0; k < entries->size(); ++k) {
      const toml::table* table = (*entries)[k].as_table();
      if (!table) reader.fail(&(*entries)[k], kind, "expected [[" + std::string(kind) + "]] tables");
      TableReader entry(*table, std::string(kind) + "[" + std::to_string(k) + "]", file);
      if (std::string(kind) == "bug") {
        Bug bug{entry.string("name"), entry.string("story"), entry.integer("exercise", std::nullopt, 1, 99), strings(entry, "render"),
                strings(entry, "expect")};
        entry.rejectUnknown({"name", "story", "exercise", "file", "find", "replace", "render", "expect"});  // the text is mutant.py's
        bugs.push_back(bug);
      } else {
        Variant variant{entry.string("folder"), entry.string("story"), entry.integer("exercise", std::nullopt, 1, 99), {}};
        if (entry.has("environment")) variant.environment = strings(entry, "environment");
        entry.rejectUnknown({"folder", "story", "exercise", "environment"});
        variants.push_back(variant);
      }
    }
  }
}

// A submission whose make build builds the bug into ./hsr, and whose make run renders with it.
std::filesystem::path bugSubmission(const Bug& bug, const SelfCheckOptions& options) {
  const std::filesystem::path folder = std::filesystem::absolute(options.work / "bugs" / bug.name);
  std::string render;
  for (const std::string& word : bug.render) render += (render.empty() ? "" : " ") + word;
  writeHsrSubmission(folder, bug.story,
                     "python3 " + (options.source / "course/bugs/mutant.py").string() + " build " + bug.name + " --build " +
                         options.build.string() + " --out .",
                     render, findExercise(bug.exercise), skillsOf(findExercise(bug.exercise)));
  return folder;
}

}  // namespace

int selfCheck(const SelfCheckOptions& options) {
  std::vector<Bug> bugs;
  std::vector<Variant> variants;
  readCatalogue(options.source / "course/bugs/catalogue.toml", bugs, variants);
  if (!options.bugs.empty()) {
    std::vector<Bug> chosen;
    for (const std::string& name : options.bugs) {
      const auto found = std::find_if(bugs.begin(), bugs.end(), [&](const Bug& bug) { return bug.name == name; });
      if (found == bugs.end()) throw InputError("--bugs " + name + ": no such bug in course/bugs/catalogue.toml");
      chosen.push_back(*found);
    }
    bugs = chosen;
    if (!options.variants) variants.clear();
  }
  const auto gradeOne = [&](const std::filesystem::path& submission, int exercise, const std::string& name) {
    GradeOptions grading;
    grading.submission = submission;
    grading.exercise = exercise;
    grading.hiddenSeed = options.seed;
    grading.work = options.work / "work" / name;
    grading.threads = options.threads;
    std::vector<HeatMap> heatMaps;
    return grade(grading, heatMaps);
  };

  // The variants are graded in a copy: their builds leave the checkout as it was.
  const std::filesystem::path variantCopies = options.work / "variants";
  std::filesystem::create_directories(variantCopies);
  if (!variants.empty())
    std::filesystem::copy(options.source / "course/variants", variantCopies,
                        std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);

  int caught = 0, passed = 0;
  for (const Bug& bug : bugs) {
    const GradeReport report = gradeOne(bugSubmission(bug, options), bug.exercise, "bug-" + bug.name);
    std::string feedback;
    for (const TestResult& test : report.tests)
      if (!test.passed) feedback += test.output;
    std::string unnamed;
    for (const std::string& cause : bug.expect)
      if (feedback.find(cause) == std::string::npos) unnamed += (unnamed.empty() ? "" : "; ") + cause;
    const bool ok = report.built && report.failed() > 0 && unnamed.empty();
    caught += ok;
    std::printf("%s bug %-34s %d of %zu tests failed%s\n", ok ? "caught" : "MISSED", bug.name.c_str(), report.failed(), report.tests.size(),
                !report.built ? " (it did not build: the catalogue or mutant.py is broken)"
                : unnamed.empty() ? ""
                                  : (", but the feedback never names: " + unnamed).c_str());
    if (!report.built) std::printf("%s", report.buildOutput.c_str());
    std::fflush(stdout);
  }
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const Variant& variant = variants[v];
    for (const std::string& setting : variant.environment) {
      const std::size_t equals = setting.find('=');
      setenv(setting.substr(0, equals).c_str(), setting.substr(equals + 1).c_str(), 1);
    }
    const std::filesystem::path copy = variantCopies / std::filesystem::path(variant.folder).lexically_relative("course/variants");
    const GradeReport report = gradeOne(copy, variant.exercise, "variant-" + std::to_string(v + 1));
    for (const std::string& setting : variant.environment) unsetenv(setting.substr(0, setting.find('=')).c_str());
    std::string name = variant.folder;
    for (const std::string& setting : variant.environment) name += " " + setting;
    int claimedTests = 0;
    std::string firstFailure;
    for (const TestResult& test : report.tests) {
      if (!test.claimed) continue;
      ++claimedTests;
      if (!test.passed && firstFailure.empty()) firstFailure = test.name + ": " + test.output;
    }
    const bool ok = report.built && firstFailure.empty() && claimedTests > 0;
    passed += ok;
    std::printf("%s variant %-45s %d tests claimed\n%s", ok ? "passed" : "FAILED", name.c_str(), claimedTests, firstFailure.c_str());
    std::fflush(stdout);
  }
  std::printf("caught %d of %zu bugs, %d of %zu correct variants passed\n", caught, bugs.size(), passed, variants.size());
  return caught == int(bugs.size()) && passed == int(variants.size()) ? 0 : 1;
}

}  // namespace hsr::grading
