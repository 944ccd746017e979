#include <algorithm>
#include <cstdio>
#include <fstream>
#include <span>
#include <sstream>

#include "grading/grading.hpp"
#include "grading/judge.hpp"
#include "grading/line_judge.hpp"
#include "grading/run.hpp"
#include "renderer/image/image_library.hpp"
#include "renderer/image/pfm.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/scene/triangle_file.hpp"
#include "renderer/util/error.hpp"

namespace hsr::grading {
namespace {

// The shipped scenes every visible-surface exercise's visible tests hand over, by the hard case each tests.
struct ShippedTest {
  const char* skill;
  const char* scene;  // under scenes/
};
constexpr ShippedTest kShipped[] = {
    {"visibility", "cube.toml"},
    {"visibility", "counters.toml"},
    {"visibility", "bunny.toml"},
    {"orthographic", "hard/aligned_edges.toml"},
    {"orthographic", "ripple.toml"},
    {"fill-rule", "hard/shared_edges.toml"},
    {"fill-rule", "hard/watertight.toml"},
    {"near-plane", "hard/near_plane.toml"},
    {"near-plane", "hard/huge_triangle.toml"},
    {"far-from-origin", "hard/large_coordinates.toml"},
    {"far-from-origin", "hard/far_layers.toml"},
    {"coplanar", "hard/coplanar.toml"},
    {"coplanar", "hard/many_coplanar.toml"},
    {"slivers", "hard/slivers.toml"},
    {"slivers", "hard/near_degenerate_splits.toml"},
    {"interpenetrating", "hard/interpenetrating.toml"},
    {"interpenetrating", "hard/box_junctions.toml"},
    {"cycles", "hard/cyclic_overlap.toml"},
    {"far-plane", "hard/far_planes.toml"},
    {"occlusion", "hard/occ_near.toml"},
    {"occlusion", "hard/occ_edge_opening.toml"},
    {"occlusion", "hard/occ_gap.toml"},
};
// A line exercise's shipped scenes: closed solids in front of the near plane, Appel's input.
constexpr ShippedTest kShippedDrawings[] = {
    {"visibility", "cube.toml"},
    {"visibility", "blocks.toml"},
    {"visibility", "bunny.toml"},
    {"visibility", "hard/torus.toml"},
    {"visibility", "hard/touching_boxes.toml"},
    {"orthographic", "hard/aligned_edges.toml"},
    {"far-from-origin", "hard/uv_sphere.toml"},
    {"interpenetrating", "hard/box_junctions.toml"},
    {"interpenetrating", "hard/merged_city.toml"},
};
// The visible sample of each generator's scenes, and how many hidden ones each makes.
constexpr std::uint64_t kSampleSeed = 2026;
constexpr int kHiddenPerGenerator = 2;
// The widest image a shipped scene is graded at (its own size up to this).
constexpr int kMostWidth = 400;

std::uint64_t mixed(std::uint64_t seed, std::uint64_t generator, std::uint64_t k) {
  return seed * 0x9E3779B97F4A7C15ull ^ (generator << 32) ^ k;
}

std::string fileNameOf(const std::string& testName) {
  std::string name = testName;
  std::replace(name.begin(), name.end(), '/', '-');
  return name;
}

std::string withCommas(std::int64_t n) {
  const std::string digits = std::to_string(n);
  std::string grouped;
  for (std::size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0 && digits[k - 1] != '-') grouped += ',';
    grouped += digits[k];
  }
  return grouped;
}

std::vector<std::string> claimedSkills(const std::filesystem::path& submission, std::string& notes) {
  std::ifstream file(submission / "implemented.txt");
  std::vector<std::string> claimed;
  if (!file) {
    notes += "implemented.txt is missing: it lists the hard cases your program handles, one per line.\n";
    return claimed;
  }
  const std::vector<std::string> known = skills();
  for (std::string line; std::getline(file, line);) {
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    for (std::string word; words >> word;) {
      if (std::find(known.begin(), known.end(), word) == known.end())
        notes += "implemented.txt: '" + word + "' is not a hard case this grader tests (it knows: " + [&] {
          std::string list;
          for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
          return list;
        }() + ").\n";
      else
        claimed.push_back(word);
    }
  }
  return claimed;
}

// The submission's image as ids, or why it cannot be read as one.
std::string readIds(const std::filesystem::path& file, int width, int height, std::vector<std::uint32_t>& ids) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) return "wrote no image at " + file.filename().string();
  Image image;
  if (const std::string problem = imageLibrary().readImage(file.string(), image); !problem.empty())
    return "its image cannot be read as a PNG: " + problem;
  if (image.width != width || image.height != height)
    return "its image is " + std::to_string(image.width) + "x" + std::to_string(image.height) + "; expected " + std::to_string(width) +
           "x" + std::to_string(height) + ", the scene's size line";
  if (image.channels < 3) return "its image has " + std::to_string(image.channels) + " channel(s); expected RGB, the id in 24 bits";
  ids.resize(std::size_t(width) * std::size_t(height));
  for (std::size_t p = 0; p < ids.size(); ++p) {
    const std::uint8_t* rgb = &image.pixels[p * std::size_t(image.channels)];
    ids[p] = std::uint32_t(rgb[0]) << 16 | std::uint32_t(rgb[1]) << 8 | rgb[2];
  }
  return "";
}

// The feedback for a judged image: how much is wrong, each cause with its first pixel
// and what to check, and how to see the shipped algorithm decide that pixel.
std::string feedbackOf(const Judgement& judgement, const std::string& algorithm, const std::string& sceneFile, const std::string& heatMap) {
  char line[256];
  std::snprintf(line, sizeof line, "%s of %s pixels wrong (%s certified ties, %s differences within the tolerances)\n",
                withCommas(judgement.wrong).c_str(), withCommas(judgement.pixels).c_str(), withCommas(judgement.ties).c_str(),
                withCommas(judgement.excused).c_str());
  std::string text = line;
  if (judgement.passed()) return text;
  for (const CauseCount& cause : judgement.causes) {
    text += "- " + std::string(causeName(cause.cause)) + ": " + withCommas(cause.pixels) + " pixels" +
            (cause.cause == Cause::nothingDrawn ? "" : ", first at " + cause.first) + "\n";
    text += "  " + std::string(causeAdvice(cause.cause)) + "\n";
  }
  if (const CauseCount& first = judgement.causes.front(); first.x >= 0)
    text += "How the shipped algorithm decides that pixel: hsr why " + sceneFile + " --pixel " + std::to_string(first.x) + "," +
            std::to_string(first.y) + " " + algorithm + "\n";
  text += "Where: " + heatMap + " (wrong pixels red, differences within the tolerances yellow, certified ties blue)\n";
  return text;
}

// The feedback for a judged drawing: how much line is wrong, each cause with its longest
// stretch and what to check, and how to see the shipped algorithm walk that edge.
std::string drawingFeedbackOf(const DrawingJudgement& judgement, const std::string& algorithm, const std::string& sceneFile,
                              const std::string& heatMap) {
  char line[256];
  std::snprintf(line, sizeof line, "%.2f of %.2f px of visible line wrong (%.3f px in stretches under %.2f px, excused as rounding)\n",
                judgement.wrong, judgement.visibleLength, judgement.excused, kExcusedLength);
  std::string text = line;
  if (judgement.passed()) return text;
  for (const LineCauseLength& cause : judgement.causes) {
    std::snprintf(line, sizeof line, "- %s: %.2f px, the longest stretch ", lineCauseName(cause.cause), cause.pixels);
    text += line + cause.first + "\n";
    text += "  " + std::string(lineCauseAdvice(cause.cause)) + "\n";
  }
  const dvec2 at = judgement.causes.front().at;
  text += "How the shipped algorithm walks the edge there: hsr why " + sceneFile + " --edge " + std::to_string(int(at.x)) + "," +
          std::to_string(int(at.y)) + " " + algorithm + "\n";
  text += "Where: " + heatMap + " (the visible lines grey, hidden ones light grey, wrong stretches red)\n";
  return text;
}

// The algorithm a C++ folder replaces: the NAME of its CMakeLists.txt's hsr_algorithm(NAME
// ...), which must be the exercise's; checked before anything is written.
std::string algorithmOfFolder(const GradeOptions& options, const Exercise& exercise) {
  std::ifstream cmake(options.submission / "CMakeLists.txt");
  std::stringstream text;
  text << cmake.rdbuf();
  const std::string lists = text.str();
  const std::size_t call = lists.find("hsr_algorithm(");
  if (call == std::string::npos)
    throw InputError(options.submission.string() + ": has no Makefile, and no CMakeLists.txt calling hsr_algorithm(NAME ...); expected a "
                     "program's folder (make build, make run) or an algorithm folder");
  std::istringstream words(lists.substr(call + std::string("hsr_algorithm(").size()));
  std::string algorithm;
  words >> algorithm;
  algorithm = algorithm.substr(0, algorithm.find(')'));
  if (algorithm != exercise.algorithm)
    throw InputError(options.submission.string() + ": is the folder of " + algorithm + "; exercise " + std::to_string(exercise.number) +
                     " asks for " + exercise.algorithm);
  if (options.source.empty() || !std::filesystem::exists(options.build / "compile_commands.json"))
    throw InputError(options.submission.string() + ": an algorithm folder is built with hsr's own build, and " + options.build.string() +
                     " holds no compile_commands.json; expected the build folder hsr was built in");
  return algorithm;
}

// hsr render's options for the exercise's shipped algorithm: the algorithm, and the
// culling stages it runs first.
std::string shippedOptions(const Exercise& exercise) {
  return std::string("--algo ") + exercise.algorithm + (*exercise.cull ? std::string(" --cull ") + exercise.cull : "");
}

// A C++ algorithm folder as a program: a submission in the work folder whose make build
// builds it into an hsr of its own, rendering with the options that run the student's
// code. Its implemented.txt, if it has one, says what it claims; else all of the exercise.
std::filesystem::path algorithmFolderSubmission(const GradeOptions& options, const std::string& algorithm, const Exercise& exercise,
                                                const std::filesystem::path& work) {
  const std::filesystem::path folder = std::filesystem::absolute(options.submission);
  std::vector<std::string> claims = skillsOf(exercise);
  if (std::ifstream own(folder / "implemented.txt"); own) {
    claims.clear();
    for (std::string line; std::getline(own, line);) claims.push_back(line);
  }
  const std::filesystem::path wrapper = work / "algorithm-folder";
  writeHsrSubmission(wrapper, folder.string() + " in place of algorithms/" + algorithm + "/",
                     "python3 " + (options.source / "course/folder_build.py").string() + " " + folder.string() + " --algorithm " + algorithm +
                         " --build " + options.build.string() + " --out .",
                     shippedOptions(exercise) + " " + exercise.folderOptions, exercise, claims);
  return wrapper;
}

}  // namespace

const std::vector<Exercise>& gradedExercises() {
  static const std::vector<Exercise> exercises = {
      {1, "the z-buffer", "zbuffer", true, true, {}, "", "--knob path=scalar", false, true},
      {3, "ray casting", "ray_casting", false, false, {}, "", "--knob path=scalar"},
      {4, "the painter's algorithm", "painter", true, false},
      {5, "hidden lines: Appel's quantitative invisibility", "appel", false, false, {"visibility", "orthographic", "far-from-origin", "interpenetrating"}, "", "", true},
      {7, "culling: backface and frustum", "zbuffer", true, true, {"visibility", "orthographic", "far-from-origin", "far-plane", "occlusion"}, "backface,frustum"},
      {8, "occlusion culling", "zbuffer", true, true, {}, "occlusion"},
      {14, "Warnock's area subdivision", "warnock", true, false},
      {15, "Watkins' scanline", "watkins", true, false},
      {16, "Weiler-Atherton", "weiler_atherton", true, false},
  };
  return exercises;
}

std::string gradedExerciseNumbers() {
  std::string numbers;
  for (const Exercise& exercise : gradedExercises()) numbers += (numbers.empty() ? "" : ", ") + std::to_string(exercise.number);
  return numbers;
}

const Exercise& findExercise(int number) {
  for (const Exercise& exercise : gradedExercises())
    if (exercise.number == number) return exercise;
  throw InputError("--exercise " + std::to_string(number) + ": not graded automatically; expected one of " + gradedExerciseNumbers() +
                   " (the visible-surface exercises, and 5: hidden lines)");
}

std::vector<std::string> skills() {
  std::vector<std::string> names;
  for (const SceneGenerator& generator : sceneGenerators()) names.push_back(generator.skill);
  return names;
}

Scene GradingTest::scene() const {
  if (generator) return generator->make(seed);
  Scene scene = loadScene(file);
  if (scene.width > width) {
    scene.height = std::max(1, int(std::int64_t(scene.height) * width / scene.width));
    scene.width = width;
  }
  return scene;
}

std::vector<GradingTest> testsOf(const Exercise& exercise, std::optional<std::uint64_t> hiddenSeed) {
  std::vector<GradingTest> tests;
  for (const ShippedTest& shipped : exercise.drawsLines ? std::span<const ShippedTest>(kShippedDrawings) : std::span<const ShippedTest>(kShipped)) {
    GradingTest test;
    test.name = "visible/" + std::filesystem::path(shipped.scene).replace_extension().string();
    test.skill = shipped.skill;
    test.file = std::filesystem::path(HSR_SCENES_DIR) / shipped.scene;
    test.width = kMostWidth;
    tests.push_back(test);
  }
  const std::vector<SceneGenerator>& generators = sceneGenerators();
  for (std::size_t g = 0; g < generators.size(); ++g) {
    if (exercise.drawsLines && !generators[g].forLines) continue;
    GradingTest sample;
    sample.name = "visible/" + std::string(generators[g].skill) + "-sample";
    sample.skill = generators[g].skill;
    sample.generator = &generators[g];
    sample.seed = mixed(kSampleSeed, g, 0);
    tests.push_back(sample);
    for (int k = 1; hiddenSeed && k <= kHiddenPerGenerator; ++k) {
      GradingTest hidden = sample;
      hidden.name = "hidden/" + std::string(generators[g].skill) + "-" + std::to_string(k);
      hidden.hidden = true;
      hidden.seed = mixed(*hiddenSeed, g, std::uint64_t(k));
      tests.push_back(hidden);
    }
  }
  const std::vector<std::string>& only = exercise.skills;
  if (!only.empty())
    std::erase_if(tests, [&](const GradingTest& test) { return std::find(only.begin(), only.end(), test.skill) == only.end(); });
  return tests;
}

std::vector<std::string> skillsOf(const Exercise& exercise) { return exercise.skills.empty() ? skills() : exercise.skills; }

void writeHsrSubmission(const std::filesystem::path& folder, const std::string& comment, const std::string& build, const std::string& render,
                        const Exercise& exercise, const std::vector<std::string>& claims) {
  std::filesystem::create_directories(folder);
  const std::string answer = exercise.drawsLines    ? "--segments $(out) -o $(out).svg"
                             : exercise.writesDepth ? "--ids $(out) --depth $(depth) -o $(out).color.png"
                                                    : "--ids $(out) -o $(out).color.png";
  std::ofstream(folder / "Makefile") << "# " << comment << "\nbuild:\n\t" << build << "\n\nrun:\n\t./hsr render $(file) " << render
                                     << " --threads 1 " << answer << "\n\n.PHONY: build run\n";
  std::ofstream implemented(folder / "implemented.txt");
  for (const std::string& claim : claims) implemented << claim << "\n";
}

double GradeReport::score() const {
  double sum = 0;
  for (const TestResult& test : tests) sum += test.score;
  return sum;
}
double GradeReport::maxScore() const {
  double sum = 0;
  for (const TestResult& test : tests) sum += test.maxScore;
  return sum;
}
int GradeReport::failed() const {
  return int(std::count_if(tests.begin(), tests.end(), [](const TestResult& test) { return !test.passed; }));
}

GradeReport grade(const GradeOptions& options, std::vector<HeatMap>& heatMaps) {
  const Exercise& exercise = findExercise(options.exercise);
  std::error_code error;
  if (!std::filesystem::is_directory(options.submission, error))
    throw InputError(options.submission.string() + ": no such folder; expected a submission's folder, with its Makefile");
  std::vector<GradingTest> tests = testsOf(exercise, options.hiddenSeed);
  if (!options.onlyTest.empty()) {
    std::erase_if(tests, [&](const GradingTest& test) { return test.name != options.onlyTest; });
    if (tests.empty()) {
      std::string names;
      for (const GradingTest& test : testsOf(exercise, options.hiddenSeed)) names += (names.empty() ? "" : ", ") + test.name;
      throw InputError("--test " + options.onlyTest + ": no such test; expected one of " + names);
    }
  }
  const bool program = std::filesystem::is_regular_file(options.submission / "Makefile");
  const std::string algorithm = program ? "" : algorithmOfFolder(options, exercise);
  std::filesystem::create_directories(options.work);
  const std::filesystem::path work = std::filesystem::absolute(options.work);
  const std::filesystem::path submission =
      program ? std::filesystem::absolute(options.submission) : algorithmFolderSubmission(options, algorithm, exercise, work);

  GradeReport report;
  report.exercise = exercise.number;
  report.submission = options.submission.string();
  report.seed = options.hiddenSeed;
  std::string notes;
  report.claimed = claimedSkills(submission, notes);
  const RunResult build = runCommand({"make", "build"}, submission, work / "build.log", options.limits.buildSeconds);
  report.built = build.succeeded();
  report.buildOutput = notes + "make build " + build.outcome() + "\n" + build.output;

  for (const GradingTest& test : tests) {
    TestResult result;
    result.name = test.name;
    result.skill = test.skill;
    result.hidden = test.hidden;
    const std::string file = fileNameOf(test.name);
    if (!report.built) {
      result.output = "the submission did not build: make build " + build.outcome() + "\n" + build.output;
    } else if (std::find(report.claimed.begin(), report.claimed.end(), test.skill) == report.claimed.end()) {
      result.claimed = false;
      result.output = "not run: implemented.txt does not claim " + test.skill + "\n";
    } else {
      const Scene scene = test.scene();
      PreparedScene prepared(scene);
      prepared.setSize(scene.width, scene.height);
      const std::filesystem::path sceneFile = work / (file + ".tri"), answer = work / (file + (exercise.drawsLines ? ".txt" : ".png"));
      std::ofstream(sceneFile, std::ios::binary) << triangleFileText(prepared);
      const std::filesystem::path depthImage = work / (file + ".depth.pfm");
      std::filesystem::remove(answer, error);
      std::filesystem::remove(depthImage, error);
      std::vector<std::string> command = {"make", "-s", "run", "file=" + sceneFile.string(), "out=" + answer.string()};
      if (exercise.writesDepth) command.push_back("depth=" + depthImage.string());
      const RunResult run = runCommand(command, submission, work / (file + ".log"), options.limits.runSeconds);
      result.seconds = run.seconds;
      const std::string heatMap = file + "-where.png";
      std::vector<std::uint8_t> where;  // a judged answer's heat map
      if (!run.succeeded()) {
        result.output = "make run " + run.outcome() + " on " + sceneFile.filename().string() + "\n" + run.output;
      } else if (exercise.drawsLines) {
        std::vector<DrawnSegment> segments;
        if (const std::string problem = readSegments(answer, segments); !problem.empty()) {
          result.output = "make run " + problem + "\n";
        } else {
          const DrawingJudgement judgement = judgeDrawing(prepared, segments, options.threads);
          result.passed = judgement.passed();
          result.output = drawingFeedbackOf(judgement, shippedOptions(exercise), sceneFile.string(), heatMap);
          where = judgement.heatMap;
        }
      } else {
        std::vector<std::uint32_t> ids;
        std::vector<float> depth;
        std::string problem = readIds(answer, scene.width, scene.height, ids);
        if (problem.empty() && exercise.writesDepth) problem = readPfm(depthImage, scene.width, scene.height, depth);
        if (!problem.empty()) {
          result.output = "make run " + problem + "\n";
        } else {
          Stats stats;
          const ReferenceImage reference = traceReference(prepared, options.threads, stats);
          // A fill-rule scene's every pixel is decided by the conventions.
          const std::vector<std::uint32_t> conventions =
              test.pixelExact() && exercise.fillRule ? conventionsAnswer(prepared) : std::vector<std::uint32_t>();
          const Judgement judgement = judge(prepared, reference, ids, conventions, exercise.tieRule, depth);
          result.passed = judgement.passed();
          result.output = feedbackOf(judgement, shippedOptions(exercise), sceneFile.string(), heatMap);
          where = judgement.heatMap;
        }
      }
      result.score = result.passed ? result.maxScore : 0;
      if (!result.passed && !where.empty()) {
        result.heatMap = heatMap;
        heatMaps.push_back({heatMap, scene.width, scene.height, std::move(where)});
      }
    }
    report.tests.push_back(std::move(result));
  }
  return report;
}

}  // namespace hsr::grading
