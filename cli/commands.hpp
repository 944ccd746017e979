// The hsr subcommands of the command line itself: render, why, list, diff and pvs (compare, sweep
// and study are the studies', studies/studies.hpp). Each validates all of its input
// before doing any work, throws InputError for bad input (main prints it as one line and
// exits 2), and writes its output files only when all of them are complete.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/pipeline.hpp"

namespace hsr::cli {

// What render and why both take: the scene at a size, and the algorithm with its knobs
// after culling stages, on some threads.
struct ConfiguredScene {
  std::string scene;
  std::string algorithm = "zbuffer";
  std::string variant, depthFormat, size;
  std::vector<std::string> knobs;
  std::string cull;  // culling stages before the algorithm: "backface,frustum:sphere"
  int threads = 0;
};
// The configuration they run: the algorithm with the --variant, --depth-format and --knob
// settings, after the --cull stages (InputError for any that is wrong).
pipeline::Configuration configurationOf(const ConfiguredScene& options);

struct RenderOptions : ConfiguredScene {
  std::string output, depth, ids;
  std::string segments;   // a line algorithm's visible segments as text (what hsr grade reads from a line exercise)
  std::string triangles;  // the scene as a triangle file, at the render's size (hsr grade hands programs these)
  std::string lineStyle;  // line algorithms: visible | hidden | qi (default visible)
  bool stats = false;
  bool explain = false;   // print the pass plan before rendering, the decisions and time per pass after
  std::string steps;      // folder for the algorithm's steps (renderer/steps/steps.hpp); "" = none
  int every = 0;          // record every Nth repeated step; 0 = about 40 frames per run
};
int render(const RenderOptions& options);
int list();

// hsr why: how an algorithm decided some pixels, beside the exact reference's answer
// (pipeline/why.hpp), as text or JSON on stdout.
struct WhyOptions : ConfiguredScene {
  std::vector<std::string> pixels;  // "X,Y" each
  std::string edge;                 // a line algorithm's edge: "N", or "X,Y" for the one nearest that pixel
  bool json = false;
  int step = -1;  // hsr why --step N: the histories up to the Nth step hsr render --steps records; -1: not asked
  int every = 0;  // with --step: as hsr render --every
};
int why(const WhyOptions& options);

struct DiffOptions {
  std::string first, second;
  std::string heatmap;
  double tolerance = 0;  // per channel, in [0, 1]
};
int diff(const DiffOptions& options);

// hsr grade: a submission's answers to an exercise, judged against the exact reference
// (grading/grading.hpp). Exit 0 when every test passed, 1 when one failed, 2 on bad input.
struct GradeOptions {
  std::filesystem::path submission;
  int exercise = 0;
  bool hidden = false;                  // the hidden tests too, generated from the seed
  std::optional<std::uint64_t> seed;    // default 1
  std::string test;                     // that test alone (a command grader's test per command)
  std::filesystem::path out = "out/grade";
  double buildSeconds = 600, runSeconds = 20;
  int threads = 0;
  bool list = false;               // --list: the exercise's tests, a name per line
  bool selfCheck = false;          // the grader graded: the catalogue of bugs and the correct variants
  std::vector<std::string> bugs;   // --self-check: these bugs alone
  bool variants = false;           // --self-check --bugs: the correct variants too
};
int grade(const GradeOptions& options);

// hsr pvs build: a level's potentially visible sets, cached beside it
// (algorithms/culling/cells/pvs.hpp).
struct PvsOptions {
  std::string scene;
  std::string build = "conservative";
  std::string samples, resolution;  // "": the stage's defaults
  std::string out;                  // the cache file to write
  int threads = 0;
};
int pvsBuild(const PvsOptions& options);

}  // namespace hsr::cli
