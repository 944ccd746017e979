// hsr grade: a submission's answers to a coursework exercise, judged against the exact
// reference, test by test, with feedback that names what is wrong and shows where.
//
// A submission is a C++ algorithm folder (one like algorithms/zbuffer/, built into hsr
// in place of the shipped one by course/folder_build.py), or a folder with a Makefile,
// in any language (coursework.md, "Handing in a
// program"): `make build` builds it; `make run file=SCENE out=IDS.png` reads a triangle
// file (renderer/scene/triangle_file.hpp) and writes the id image (24-bit RGB, the
// triangle's number, R the high byte; 0 for the background); `implemented.txt` lists the
// hard cases it claims, one per line. Each test hands it a scene and judges the image
// (judge.hpp); a test of a hard case it does not claim scores nothing and is not run.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "grading/generated_scenes.hpp"
#include "renderer/scene/scene.hpp"

namespace hsr::grading {

// A coursework exercise hsr grade can grade: each asks for a visible-surface algorithm
// whose id image the reference decides, or a hidden-line algorithm whose drawing the
// line reference decides.
struct Exercise {
  int number;
  const char* title;
  const char* algorithm;  // the shipped algorithm that solves it
  // Whether it rasterizes, so that the fill rule decides a center on an edge exactly
  // (demanded on the fill-rule scenes); a ray caster's answer there is any tied triangle.
  bool fillRule = true;
  // Whether, of two triangles exactly as near, the first drawn must keep the pixel (the
  // z-buffer's rule; a painter, Warnock, Watkins and Weiler-Atherton order coplanar faces
  // their own way, and any of them is right).
  bool tieRule = true;
  // The hard cases its tests hand over; all when empty. Backface culling (Exercise 7) is
  // right for closed solids only, so that exercise's scenes are boxes and spheres.
  std::vector<std::string> skills = {};
  const char* cull = "";  // the culling stages the shipped answer runs first (hsr render --cull)
  // What a C++ algorithm folder is rendered with: the options that run the code the
  // student edition asks for (the z-buffer's textbook loop, not its SIMD fast path; the
  // ray caster's one-ray traversal, not its packets or wide BVH).
  const char* folderOptions = "";
  // Whether its answer is a line drawing (Exercise 5): `make run` then writes the visible
  // segments as text (grading/line_judge.hpp), not an id image.
  bool drawsLines = false;
  // Whether `make run` also writes a depth image (Exercise 1: the z-buffer and depth
  // formats): each pixel's view distance, a PFM at depth=DEPTH.pfm.
  bool writesDepth = false;
};
const std::vector<Exercise>& gradedExercises();
// Their numbers as a person lists them: "1, 3, 4, 5, 7, 8, 14, 15, 16".
std::string gradedExerciseNumbers();
// The exercise numbered so; InputError naming the graded ones otherwise.
const Exercise& findExercise(int number);

// One test: a scene handed to the submission. Shipped scenes are the visible tests;
// with --hidden, each generator makes two more scenes from the seed.
struct GradingTest {
  std::string name;   // "visible/counters", "hidden/near-plane-2"
  std::string skill;  // the hard case it tests, as implemented.txt names it
  bool hidden = false;
  std::filesystem::path file;                // a shipped scene, at `width` pixels wide
  int width = 0;
  const SceneGenerator* generator = nullptr;  // or a generated one, from `seed`
  std::uint64_t seed = 0;
  Scene scene() const;
  bool pixelExact() const { return generator && generator->pixelExact; }
};
std::vector<GradingTest> testsOf(const Exercise& exercise, std::optional<std::uint64_t> hiddenSeed);
// Every skill a test may name, in the order the tests come; those of an exercise.
std::vector<std::string> skills();
std::vector<std::string> skillsOf(const Exercise& exercise);

struct Limits {
  double buildSeconds = 600;  // make build
  double runSeconds = 20;     // each make run
};

struct TestResult {
  std::string name, skill;
  bool hidden = false;
  bool claimed = true;  // false: implemented.txt does not claim its hard case, and it was not run
  bool passed = false;
  double score = 0, maxScore = 1;
  std::string output;   // the feedback, a few lines
  std::string heatMap;  // the picture of where it is wrong (a file name in the report's folder), or ""
  double seconds = 0;   // the submission's time on it
};

struct GradeReport {
  int exercise = 0;
  std::string submission;
  std::optional<std::uint64_t> seed;  // with --hidden
  bool built = false;
  std::string buildOutput;             // make build's last lines
  std::vector<std::string> claimed;    // implemented.txt's skills
  std::vector<TestResult> tests;
  double score() const;
  double maxScore() const;
  int failed() const;
};

struct GradeOptions {
  std::filesystem::path submission;
  int exercise = 0;
  std::optional<std::uint64_t> hiddenSeed;  // --hidden [--seed S]
  std::string onlyTest;                     // --test NAME: that test alone
  std::filesystem::path work;               // the scenes and images handed back and forth
  // For a C++ algorithm folder: the checkout (course/folder_build.py) and the build
  // whose compile commands build the folder into an hsr of its own.
  std::filesystem::path source, build;
  Limits limits;
  int threads = 0;
};

// Builds the submission, runs every test and judges it. A submission that does not
// build, crashes, hangs or writes a wrong image fails the tests it fails, each with its
// reason: the grader itself fails (InputError) only on its own bad input.
// `heatMaps` receives, per failing test, its heat map's file name and RGBA pixels.
struct HeatMap {
  std::string file;
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
};
GradeReport grade(const GradeOptions& options, std::vector<HeatMap>& heatMaps);

// hsr grade --self-check (self_check.cpp): every bug of the catalogue caught, with its
// cause named, and every correct variant passed. Returns the exit status.
struct SelfCheckOptions {
  std::filesystem::path source;  // the checkout (course/ is read from it)
  std::filesystem::path build;   // the build hsr was built in: its compile commands build the bugs
  std::filesystem::path work;
  std::vector<std::string> bugs;  // these alone (and no variant unless `variants`); all when empty
  bool variants = false;          // with `bugs`: the correct variants too
  std::optional<std::uint64_t> seed = 1;  // the hidden tests too
  int threads = 0;
};
int selfCheck(const SelfCheckOptions& options);

// A submission that runs an hsr it builds: a Makefile in `folder` whose make build runs
// `build` (which leaves ./hsr there) and whose make run renders the scene with ./hsr and
// `render` (hsr render's options) into the exercise's answer (ids, or a line exercise's
// segments), and an implemented.txt of `claims`, a line each. The self-check's bugs and
// the C++ algorithm folders are graded through one.
void writeHsrSubmission(const std::filesystem::path& folder, const std::string& comment, const std::string& build, const std::string& render,
                        const Exercise& exercise, const std::vector<std::string>& claims);

// The reports courses already read: Gradescope's results.json, JUnit XML, and a page.
std::string gradescopeJson(const GradeReport& report);
std::string junitXml(const GradeReport& report);
std::string feedbackPage(const GradeReport& report);
// The terminal's table: a line per test, then the score.
std::string summary(const GradeReport& report);

}  // namespace hsr::grading
