// hsr: the command-line front end. Every subcommand turns bad input into one line on
// stderr ("hsr: error: what, where, expected") and exit status 2, and writes no file.
#include <cstdio>

#include <CLI/CLI.hpp>

#include "cli/commands.hpp"
#include "studies/common.hpp"
#include "studies/studies.hpp"
#include "renderer/error.hpp"
#include "renderer/memory.hpp"

int main(int argc, char** argv) {
  hsr::keepFreedMemoryForReuse();
  CLI::App app{"hsr: classic hidden-surface algorithms on one software rasterizer"};
  app.require_subcommand(1);
  const auto threadsOption = [](CLI::App* command, int& threads) {
    command->add_option("--threads", threads, "worker threads, 0 = all cores")->check(CLI::Range(0, 256))->capture_default_str();
  };

  hsr::cli::RenderOptions render;
  CLI::App* renderCommand = app.add_subcommand("render", "render a scene with one algorithm");
  renderCommand->add_option("scene", render.scene, "scene file (TOML)")->required();
  renderCommand->add_option("--algo", render.algorithm, "algorithm (see `hsr list`)")->capture_default_str();
  renderCommand->add_option("--variant", render.variant, "shorthand for --knob variant=V");
  renderCommand->add_option("--depth-format", render.depthFormat, "shorthand for --knob depth-format=F");
  renderCommand->add_option("--knob", render.knobs, "NAME=VALUE, any knob `hsr list` shows (repeatable)");
  renderCommand->add_option("--size", render.size, "WIDTHxHEIGHT, overrides the scene's image size");
  threadsOption(renderCommand, render.threads);
  renderCommand->add_option("-o,--output", render.output, "color image (.png), or for a line algorithm a drawing (.svg)")->required();
  renderCommand->add_option("--line-style", render.lineStyle,
                            "line algorithms: visible (default), hidden (hidden parts dashed grey), qi (shade by quantitative invisibility)");
  renderCommand->add_option("--cull", render.cull,
                            "culling stages run before the algorithm, in order: STAGE[:VARIANT],... (see `hsr list`)");
  renderCommand->add_option("--depth", render.depth, "depth image (.exr): distance along the view axis");
  renderCommand->add_option("--ids", render.ids, "id image (.png): triangle index + 1 as 24-bit RGB, R high");
  renderCommand->add_flag("--stats", render.stats, "print counters and phase times");
  renderCommand->add_flag("--explain", render.explain,
                          "print the passes the scene's effects call for and why, then what was decided and the time of each pass");

  hsr::studies::CompareOptions compare;
  CLI::App* compareCommand = app.add_subcommand(
      "compare", "every algorithm against the exact reference: time, error, memory, counters, contact sheet");
  compareCommand->add_option("scenes", compare.scenes, "scene files; none: the default study of the shipped scenes");
  compareCommand->add_option("--algos", compare.algorithms,
                             "comma-separated algorithms, each NAME or NAME:knob=value:...; default: all at their defaults");
  compareCommand->add_option("--repeat", compare.repeat, "timed runs after one warm-up")->capture_default_str();
  compareCommand->add_option("--size", compare.size, "WIDTHxHEIGHT for every scene");
  threadsOption(compareCommand, compare.threads);
  compareCommand->add_option("--out", compare.out, "folder for contact_sheet.png, results.csv, results.json")
      ->capture_default_str();

  hsr::studies::SweepOptions sweep;
  CLI::App* sweepCommand = app.add_subcommand("sweep", "an algorithm's accuracy against time over its knobs, plotted");
  sweepCommand->add_option("scene", sweep.scene, "scene file (TOML)")->required();
  sweepCommand->add_option("--algo", sweep.algorithm, "algorithm (see `hsr list`)")->capture_default_str();
  sweepCommand->add_option("--variant", sweep.variant, "the algorithm's variant, the same in every configuration");
  sweepCommand->add_option("--knob", sweep.knobs, "NAME=v1,v2,... (repeatable; the cross product is run); size=WxH,... sweeps the resolution");
  sweepCommand->add_option("--scale", sweep.scale, "triangles | pixels: time against scene size instead, with the fitted exponent");
  sweepCommand->add_option("--repeat", sweep.repeat, "timed runs after one warm-up")->capture_default_str();
  sweepCommand->add_option("--size", sweep.size, "WIDTHxHEIGHT, overrides the scene's image size");
  threadsOption(sweepCommand, sweep.threads);
  sweepCommand->add_option("--out", sweep.out, "folder for the CSV, JSON and plots")->capture_default_str();

  hsr::studies::StudyOptions study;
  CLI::App* studyCommand = app.add_subcommand(
      "study", "an experiment, reproduced: culling-combos, occlusion-walkthrough, hzb-resolution, occluder-fraction, effects, shadow-map");
  studyCommand->add_option("name", study.name,
                           "the study: culling-combos, occlusion-walkthrough, hzb-resolution, occluder-fraction, effects or shadow-map")
      ->required();
  studyCommand->add_option("--scenes", study.scenes, "some of the study's scenes: cube,counters,trees,dragons (default all)");
  studyCommand->add_option("--frames", study.frames,
                           "frames: culling-combos over a full turn at 60 degrees/s (default 360), occlusion-walkthrough "
                           "along its path (500); the timing repeats of hzb-resolution (30) and occluder-fraction (20)")
      ->check(CLI::Range(1, 100000));
  studyCommand->add_option("--error-frames", study.errorFrames, "frames compared with the exact reference, evenly spread")
      ->check(CLI::Range(0, 100000))->capture_default_str();
  studyCommand->add_option("--size", study.size, "WIDTHxHEIGHT for every scene");
  threadsOption(studyCommand, study.threads);
  studyCommand->add_option("--out", study.out, "folder for the study's CSV and plot (default out/study/NAME)");

  hsr::cli::DiffOptions diff;
  CLI::App* diffCommand = app.add_subcommand("diff", "compare two images: exit 0 within tolerance, 1 beyond");
  diffCommand->add_option("first", diff.first, "image A")->required();
  diffCommand->add_option("second", diff.second, "image B")->required();
  diffCommand->add_option("--heatmap", diff.heatmap, "write where they differ (.png)");
  diffCommand->add_option("--tolerance", diff.tolerance, "largest allowed channel difference, in [0, 1]")->capture_default_str();

  CLI::App* listCommand = app.add_subcommand("list", "list algorithms, their knobs, and the shipped scenes");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // Help is not an error; a usage mistake is one line and exit 2 like any bad input.
    if (error.get_exit_code() == 0) return app.exit(error);
    std::fprintf(stderr, "hsr: error: %s (see --help)\n", error.what());
    return hsr::studies::kBadInput;
  }

  try {
    if (*renderCommand) return hsr::cli::render(render);
    if (*compareCommand) return hsr::studies::compare(compare);
    if (*sweepCommand) return hsr::studies::sweep(sweep);
    if (*studyCommand) return hsr::studies::study(study);
    if (*diffCommand) return hsr::cli::diff(diff);
    if (*listCommand) return hsr::cli::list();
  } catch (const hsr::InputError& error) {
    std::fprintf(stderr, "hsr: error: %s\n", error.what());
    return hsr::studies::kBadInput;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "hsr: error: %s\n", error.what());
    return 1;
  }
  return 0;
}
