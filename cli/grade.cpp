// hsr grade: a submission's answers to an exercise, judged against the exact reference
// (grading/grading.hpp); the reports in --out, written only once all are complete.
#include <cstdio>

#include "cli/commands.hpp"
#include "grading/grading.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/util/error.hpp"

namespace hsr::cli {
namespace {

// The build this hsr came from: its compile commands build a bug or an algorithm folder
// into an hsr of its own.
std::filesystem::path buildOfThisHsr() { return std::filesystem::canonical("/proc/self/exe").parent_path(); }

}  // namespace

int grade(const GradeOptions& options) {
  if (options.selfCheck) {
    if (!options.submission.empty() || options.exercise != 0 || options.hidden || !options.test.empty())
      throw InputError("--self-check: grades the catalogue and the variants; give no submission, --exercise, --hidden or --test");
    grading::SelfCheckOptions check;
    check.source = HSR_SOURCE_DIR;
    check.build = buildOfThisHsr();
    if (!std::filesystem::exists(check.build / "compile_commands.json"))
      throw InputError("--self-check: " + check.build.string() + " holds no compile_commands.json; expected the build folder hsr was built in");
    check.work = options.out / "self-check";
    check.bugs = options.bugs;
    check.variants = options.variants;
    if (options.seed) check.seed = options.seed;
    check.threads = options.threads;
    return grading::selfCheck(check);
  }
  if (options.list) {
    if (options.exercise == 0) throw InputError("--list: give --exercise too");
    std::optional<std::uint64_t> seed;
    if (options.hidden) seed = options.seed.value_or(1);
    for (const grading::GradingTest& test : grading::testsOf(grading::findExercise(options.exercise), seed))
      std::printf("%s\n", test.name.c_str());
    return 0;
  }
  if (!options.bugs.empty() || options.variants) throw InputError("--bugs, --variants: choose what --self-check grades; give --self-check too");
  if (options.submission.empty()) throw InputError("grade: expected a submission's folder (or --self-check)");
  if (options.exercise == 0) throw InputError("grade: --exercise is required: one of " + grading::gradedExerciseNumbers());
  if (options.seed && !options.hidden) throw InputError("--seed: makes the hidden tests; give --hidden too");
  grading::GradeOptions grading;
  grading.submission = options.submission;
  grading.exercise = options.exercise;
  if (options.hidden) grading.hiddenSeed = options.seed.value_or(1);
  grading.onlyTest = options.test;
  grading.source = HSR_SOURCE_DIR;
  grading.build = buildOfThisHsr();
  grading.work = options.out / "work";
  grading.limits.buildSeconds = options.buildSeconds;
  grading.limits.runSeconds = options.runSeconds;
  grading.threads = options.threads;
  std::vector<grading::HeatMap> heatMaps;
  const grading::GradeReport report = grading::grade(grading, heatMaps);

  OutputFiles files;
  files.addText(options.out / "results.json", grading::gradescopeJson(report));
  files.addText(options.out / "junit.xml", grading::junitXml(report));
  files.addText(options.out / "feedback.html", grading::feedbackPage(report));
  for (const grading::HeatMap& map : heatMaps) files.addRgbaPng(options.out / map.file, map.width, map.height, map.rgba);
  files.commit();
  std::fputs(grading::summary(report).c_str(), stdout);
  std::printf("feedback: %s (results.json for Gradescope, junit.xml beside it)\n", (options.out / "feedback.html").string().c_str());
  return report.failed() == 0 ? 0 : 1;
}

}  // namespace hsr::cli
