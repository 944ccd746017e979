// Steps (renderer/steps/steps.hpp, hsr render --steps): recording an algorithm's steps changes
// nothing it computes, records what it says, and writes a folder a person can look at.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "algorithms/culling/culling.hpp"
#include "algorithms/registry.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/why.hpp"
#include "renderer/image/image_library.hpp"
#include "renderer/lines/line_drawing.hpp"
#include "renderer/steps/steps.hpp"
#include "renderer/steps/steps_page.hpp"
#include "renderer/util/error.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

TEST(Steps, ARunOfRepeatedStepsIsRecordedAboutFortyTimesEndingOnItsLast) {
  const StepRecorder chosen;
  for (const std::size_t count : {1u, 7u, 40u, 41u, 1000u, 123457u}) {
    std::size_t recorded = 0;
    for (std::size_t i = 0; i < count; ++i) recorded += chosen.due(i, count);
    EXPECT_TRUE(chosen.due(count - 1, count)) << count;
    EXPECT_GE(recorded, std::min<std::size_t>(count, StepRecorder::kFramesPerRun / 2)) << count;
    EXPECT_LE(recorded, StepRecorder::kFramesPerRun + 1) << count;
  }
  const StepRecorder everyThird(3);
  EXPECT_FALSE(everyThird.due(0, 10));
  EXPECT_TRUE(everyThird.due(2, 10));
  EXPECT_FALSE(everyThird.due(3, 10));
  EXPECT_TRUE(everyThird.due(9, 10));  // the last
  // Events with no known end: the first forty, or every Nth.
  EXPECT_TRUE(chosen.due(StepRecorder::kFramesPerRun - 1));
  EXPECT_FALSE(chosen.due(StepRecorder::kFramesPerRun));
  EXPECT_TRUE(everyThird.due(302));
  EXPECT_FALSE(everyThird.due(303));
}

// Not every pixel of the picture the same colour.
bool showsSomething(const Image& picture) {
  for (std::size_t i = 4; i < picture.pixels.size(); ++i)
    if (picture.pixels[i] != picture.pixels[i % 4]) return true;
  return false;
}

// A label partly or wholly off a small picture is cut, not drawn past it (OpenImageIO's
// own clipping failed an assertion: Appel's steps and the QI legend on a 96 x 64 image).
TEST(Steps, LabelsAndLegendsOffASmallPictureAreCut) {
  Image picture = blankPicture(24, 12);
  for (const auto& [x, baseline] : std::vector<std::pair<int, int>>{{-30, 5}, {20, 14}, {5, 40}, {-5, -3}, {100, 100}, {2, 11}})
    drawLabel(picture, x, baseline, "QI 12", {0, 0, 0});
  drawLegend(picture, qiLegend());
  EXPECT_EQ(picture.pixels.size(), 24u * 12u * 4u);
  EXPECT_TRUE(showsSomething(picture));
  // And through the command: a drawing by QI, and Appel's steps, on a tiny image.
  const auto folder = test::outputPath("steps-tiny");
  std::filesystem::remove_all(folder);
  const std::string scene = test::sourcePath("scenes/hard/occ_gap.toml").string();
  for (const std::string& arguments : {" --line-style qi -o " + test::outputPath("tiny-qi.png").string(),
                                       " -o " + test::outputPath("tiny.png").string() + " --steps " + folder.string()}) {
    const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " render " + scene + " --algo appel --size 40x30" + arguments);
    EXPECT_EQ(result.exitCode, 0) << arguments << "\n" << result.output;
  }
}

// The label font compiled in: a label is as wide as its glyphs' advances, draws in its
// colour only, and a character the table lacks is drawn as U+FFFD.
TEST(Steps, LabelsAreDrawnFromTheFontCompiledIn) {
  EXPECT_EQ(labelWidth("QI 12"), labelWidth("QI") + labelWidth(" ") + labelWidth("12"));
  EXPECT_GT(labelWidth("W"), labelWidth("i"));
  EXPECT_LT(labelWidth("QI 12", kSmallLabelSize), labelWidth("QI 12", kLabelSize));
  const auto drawn = [](const std::string& text) {
    Image picture = blankPicture(80, 20);
    drawLabel(picture, 2, 15, text, {200, 0, 0});
    return picture;
  };
  const Image label = drawn("QI 12");
  std::size_t inked = 0;
  for (std::size_t p = 0; p < label.pixels.size(); p += 4) {
    const std::uint8_t* pixel = &label.pixels[p];
    EXPECT_EQ(pixel[1], pixel[2]);  // white blended toward red only
    EXPECT_EQ(pixel[3], 255);
    inked += pixel[1] < 128;
  }
  EXPECT_GT(inked, 20u);
  EXPECT_EQ(drawn("\xe2\x82\xac").pixels, drawn("\xef\xbf\xbd").pixels);  // the euro sign, which the table lacks
  EXPECT_NE(drawn("\xc3\x97").pixels, drawn("\xef\xbf\xbd").pixels);  // the multiplication sign, which it has
}

// A number of steps as typed: a whole number, or one line saying what was expected.
TEST(Steps, AStepCountIsAWholeNumber) {
  EXPECT_EQ(stepCountError("0"), "");
  EXPECT_EQ(stepCountError("999999999"), "");
  for (const std::string bad : {"", "abc", "-1", "1.5", "1e3", "1000000000", " 5"})
    EXPECT_EQ(stepCountError(bad), bad + ": expected a whole number from 0 to 999999999") << bad;
}

struct Configured {
  std::string scene, algorithm;
  KnobSettings knobs;
  std::string cull;
};

void PrintTo(const Configured& c, std::ostream* out) {
  *out << c.algorithm << " on " << c.scene;
  for (const auto& [name, value] : c.knobs) *out << " " << name << "=" << value;
  if (!c.cull.empty()) *out << " --cull " << c.cull;
}

class EveryAlgorithmsSteps : public testing::TestWithParam<Configured> {};

// The counters of a render: what the algorithm did, without its times. Left out: the
// z-buffer fast path's "fragments skipped by block depth", which counts work saved, not
// work done. A recording draws the image as one tile, and how much the block test saves
// depends on how the image is cut: a triangle with few pixels in a tile goes to the
// textbook loop there (fast_path_test checks the fast path's other counters).
std::map<std::string, std::int64_t> countersOf(const Stats& stats) {
  std::map<std::string, std::int64_t> counters;
  for (const std::string& name : stats.counterNames())
    if (name != "fragments skipped by block depth") counters[name] = stats.counter(name);
  return counters;
}

TEST_P(EveryAlgorithmsSteps, ChangeNoCounterAndNoPixelAndShowTheAlgorithmsOwnSteps) {
  const Configured& c = GetParam();
  pipeline::Configuration configuration = pipeline::configurationOf(findAlgorithm(c.algorithm), c.knobs);
  if (!c.cull.empty()) configuration.culling = culling::parsePipeline(c.cull);
  // One thread without steps (a recording runs its loops on one thread), and two; each
  // on a scene of its own, so that each builds what the scene builds on first use.
  const auto renderFresh = [&](int threads, Stats& stats, StepRecorder* steps) {
    const test::LoadedScene loaded(test::sourcePath(c.scene), 160);
    return pipeline::render(loaded.prepared, configuration, threads, stats, nullptr, steps);
  };
  Stats plainOne, plainTwo, recorded;
  const pipeline::Rendered one = renderFresh(1, plainOne, nullptr);
  const pipeline::Rendered two = renderFresh(2, plainTwo, nullptr);
  StepRecorder steps;
  const pipeline::Rendered watched = renderFresh(2, recorded, &steps);
  EXPECT_EQ(watched.frame.color, one.frame.color);
  EXPECT_EQ(watched.frame.ids, one.frame.ids);
  EXPECT_EQ(watched.frame.color, two.frame.color);
  EXPECT_EQ(countersOf(recorded), countersOf(plainOne));
  EXPECT_EQ(watched.drawing.segments.size(), one.drawing.segments.size());

  // Steps were recorded, each a picture with a caption, and a run of repeated steps
  // stays near kFramesPerRun frames however many triangles, rows or edges there are.
  ASSERT_FALSE(steps.steps().empty());
  EXPECT_LE(steps.steps().size(), 3 * StepRecorder::kFramesPerRun);
  for (const Step& step : steps.steps()) {
    EXPECT_FALSE(step.caption.empty());
    EXPECT_EQ(step.caption.find('\n'), std::string::npos) << step.caption;
    ASSERT_GT(step.picture.width, 0) << step.caption;
    EXPECT_EQ(step.picture.pixels.size(), std::size_t(step.picture.width) * std::size_t(step.picture.height) * 4) << step.caption;
    const bool meantEmpty = step.caption.find("every texel empty") != std::string::npos;
    EXPECT_EQ(showsSomething(step.picture), !meantEmpty) << step.caption;
    // The steps page shows the algorithm's own statement that recorded the step.
    const SourceExcerpt source = sourceExcerpt(step.where);
    EXPECT_EQ(source.file.rfind("algorithms/", 0), 0u) << source.file << " for " << step.caption;
    std::string marked;
    for (int line = source.line; line <= source.markedTo && line - source.firstLine < int(source.lines.size()); ++line)
      marked += source.lines[std::size_t(line - source.firstLine)] + "\n";
    EXPECT_TRUE(std::regex_search(marked, std::regex(R"(record\w*\(|->drawn\()"))) << source.file << ":" << source.line << "\n" << marked;
    // From the loop that took the step: a recording helper passes its caller's place on.
    EXPECT_EQ(source.function.find("::record"), std::string::npos) << source.function;
    EXPECT_EQ(source.function.find("::drawn("), std::string::npos) << source.function;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Steps, EveryAlgorithmsSteps,
    testing::Values(Configured{"scenes/counters.toml", "zbuffer", {}, ""},
                    Configured{"scenes/counters.toml", "zbuffer", {{"variant", "scanline"}}, ""},
                    Configured{"scenes/counters.toml", "painter", {}, ""},
                    Configured{"scenes/hard/cyclic_overlap.toml", "painter", {{"variant", "newell"}}, ""},
                    Configured{"scenes/counters.toml", "painter", {{"variant", "sort"}}, ""},
                    Configured{"scenes/counters.toml", "warnock", {}, ""},
                    Configured{"scenes/counters.toml", "warnock", {{"smallest-window", "4"}}, ""},
                    Configured{"scenes/counters.toml", "watkins", {}, ""},
                    Configured{"scenes/hard/interpenetrating.toml", "watkins", {{"split", "halves"}}, ""},
                    Configured{"scenes/hard/cyclic_overlap.toml", "weiler_atherton", {}, ""},
                    Configured{"scenes/counters.toml", "abuffer", {}, ""},
                    Configured{"scenes/counters.toml", "ray_casting", {}, ""},
                    Configured{"scenes/cube.toml", "ray_casting", {{"variant", "naive"}}, ""},
                    Configured{"scenes/cube.toml", "ray_casting", {{"variant", "march"}}, ""},
                    Configured{"scenes/blocks.toml", "roberts", {}, ""},
                    Configured{"scenes/blocks.toml", "appel", {}, ""},
                    Configured{"scenes/ripple.toml", "floating_horizon", {}, ""},
                    Configured{"scenes/city.toml", "zbuffer", {}, "backface,frustum,occlusion:pyramid=on"}));

// hsr why --step N: each pixel's history up to the Nth step grows with N and is whole at
// the last, the finished image; the steps are numbered and captioned as hsr render
// --steps records them (on any number of threads: hsr why records on one).
TEST_P(EveryAlgorithmsSteps, AskedAtAStepAPixelsHistoryHoldsTheEventsBeforeIt) {
  const Configured& c = GetParam();
  const AlgorithmEntry& algorithm = findAlgorithm(c.algorithm);
  if (!algorithm.answersWhy) {  // a line algorithm: asked at a pixel, it refuses
    EXPECT_THROW(pipeline::checkAnswersWhy(algorithm), InputError);
    return;
  }
  pipeline::Configuration configuration = pipeline::configurationOf(algorithm, c.knobs);
  if (!c.cull.empty()) configuration.culling = culling::parsePipeline(c.cull);
  const test::LoadedScene loaded(test::sourcePath(c.scene), 160);
  Stats stats;
  StepRecorder recorder;
  pipeline::render(loaded.prepared, configuration, 2, stats, nullptr, &recorder);
  const std::vector<Step>& recorded = recorder.steps();
  const std::size_t count = recorded.size() + 1;  // and the finished image
  std::vector<PixelWitness::Pixel> pixels;  // every ninth pixel of every ninth row
  for (int y = 4; y < loaded.prepared.height(); y += 9)
    for (int x = 4; x < loaded.prepared.width(); x += 9) pixels.push_back({x, y});
  const auto eventsBy = [&](std::size_t number) {
    pipeline::StepAsked step;
    step.number = number;
    const std::vector<pipeline::PixelAnswer> answers = pipeline::explainPixels(loaded.prepared, configuration, pixels, 2, stats, &step);
    EXPECT_EQ(step.recorded, count);
    EXPECT_EQ(step.caption, number == count ? pipeline::kFinishedImageStep : recorded[number - 1].caption) << number;
    std::vector<std::size_t> events;
    for (const pipeline::PixelAnswer& answer : answers) events.push_back(answer.eventsByStep);
    return std::pair(events, answers);
  };
  const auto [first, answers] = eventsBy(1);
  const std::vector<std::size_t> half = eventsBy((count + 1) / 2).first;
  const auto [last, whole] = eventsBy(count);
  std::size_t before = 0, all = 0;
  for (std::size_t p = 0; p < pixels.size(); ++p) {
    EXPECT_LE(first[p], half[p]) << p;
    EXPECT_LE(half[p], last[p]) << p;
    EXPECT_EQ(last[p], whole[p].history.size()) << p;
    EXPECT_EQ(answers[p].history.size(), whole[p].history.size()) << "the same run, whatever step is asked";
    before += first[p], all += last[p];
  }
  EXPECT_LT(before, all) << "the first step comes before the loops are done";
  pipeline::StepAsked beyond;
  beyond.number = count + 1;
  EXPECT_THROW(pipeline::explainPixels(loaded.prepared, configuration, pixels, 1, stats, &beyond), InputError);
}

// What each algorithm records, in its own words.
std::vector<Step> stepsOf(const std::string& scene, const std::string& algorithm, const KnobSettings& knobs = {},
                          const std::string& cull = "") {
  const test::LoadedScene loaded(test::sourcePath(scene), 160);
  pipeline::Configuration configuration = pipeline::configurationOf(findAlgorithm(algorithm), knobs);
  if (!cull.empty()) configuration.culling = culling::parsePipeline(cull);
  Stats stats;
  StepRecorder steps;
  pipeline::render(loaded.prepared, configuration, 1, stats, nullptr, &steps);
  return steps.steps();
}

std::size_t countCaptions(const std::vector<Step>& steps, const std::string& text) {
  return std::size_t(std::count_if(steps.begin(), steps.end(), [&](const Step& s) { return s.caption.find(text) != std::string::npos; }));
}

TEST(Steps, TheZBufferEndsOnItsOverdrawWhoseTotalIsItsFragmentsTested) {
  const test::LoadedScene loaded(test::sourcePath("scenes/counters.toml"), 160);
  Stats stats;
  StepRecorder steps;
  pipeline::render(loaded.prepared, pipeline::configurationOf(findAlgorithm("zbuffer"), {}), 1, stats, nullptr, &steps);
  const Step& overdraw = steps.steps().back();
  EXPECT_NE(overdraw.caption.find("overdraw: fragments tested per pixel (" + std::to_string(stats.counter("fragments tested")) + " in all"),
            std::string::npos)
      << overdraw.caption;
  // Below the heat map, its legend: the picture is taller than the image.
  EXPECT_GT(overdraw.picture.height, loaded.prepared.height());
  EXPECT_GT(countCaptions(steps.steps(), "step 2, depth test"), 10u);
}

TEST(Steps, NewellShowsItsSplitsAndEachCullingStageWhatItRemoved) {
  EXPECT_GT(countCaptions(stepsOf("scenes/hard/cyclic_overlap.toml", "painter", {{"variant", "newell"}}), "split"), 0u);
  const std::vector<Step> culled = stepsOf("scenes/city.toml", "zbuffer", {}, "frustum,occlusion:pyramid=on");
  EXPECT_EQ(countCaptions(culled, "culling stage frustum"), 1u);
  EXPECT_EQ(countCaptions(culled, "culling stage occlusion"), 1u);
  EXPECT_EQ(countCaptions(culled, "the occluders' depth as a"), 1u);
  EXPECT_GT(countCaptions(culled, "pyramid level"), 3u);
}

// A student follows the paint order from the captions alone: each names the polygons it
// talks about by triangle and object (and a piece by its number), and a cyclic overlap,
// where each polygon straddles the other's plane without piercing it, is not called a
// piercing. --stats lists Newell's tests in the order they are tried, (a) to (e).
TEST(Steps, NewellsCaptionsNameTheirPolygonsAndItsTestsAreCountedInOrder) {
  const test::LoadedScene loaded(test::sourcePath("scenes/hard/cyclic_overlap.toml"), 160);
  Stats stats;
  StepRecorder steps;
  pipeline::render(loaded.prepared, pipeline::configurationOf(findAlgorithm("painter"), {{"variant", "newell"}}), 1, stats, nullptr, &steps);
  std::size_t conflicts = 0, painted = 0;
  for (const Step& step : steps.steps()) {
    EXPECT_EQ(step.caption.find("pierce"), std::string::npos) << step.caption;
    if (step.caption.find("split") != std::string::npos || step.caption.find("reorder") != std::string::npos) {
      ++conflicts;
      EXPECT_NE(step.caption.find("P = "), std::string::npos) << step.caption;
      EXPECT_NE(step.caption.find("Q = "), std::string::npos) << step.caption;
    }
    if (step.caption.find("painted over") != std::string::npos) {
      ++painted;
      EXPECT_NE(step.caption.find("its triangle, triangle "), std::string::npos) << step.caption;
    }
    if (step.caption.find("P = ") != std::string::npos) {
      EXPECT_TRUE(step.caption.find("of \"first\"") != std::string::npos || step.caption.find("of \"second\"") != std::string::npos ||
                  step.caption.find("of \"third\"") != std::string::npos)
          << step.caption;
    }
  }
  EXPECT_GT(conflicts, 0u);
  EXPECT_GT(painted, 0u);
  EXPECT_GT(countCaptions(steps.steps(), "piece "), 0u) << "the cycle is split, and its pieces are named";
  const std::string report = stats.report();
  std::size_t previous = 0;
  for (const char* test : {"newell test a: depth extents", "newell test b: bounding boxes", "newell test c: P behind Q's plane",
                           "newell test d: Q in front of P's plane", "newell test e: projections"}) {
    const std::size_t at = report.find(test);
    ASSERT_NE(at, std::string::npos) << test << " in\n" << report;
    EXPECT_GT(at, previous) << test;
    previous = at;
  }
}

TEST(Steps, TheCommandWritesFramesCaptionsAndAnAnimationOfThem) {
  const auto folder = test::outputPath("steps-folder");
  std::filesystem::remove_all(folder);
  const auto image = test::outputPath("steps-image.png");
  const std::string command = std::string(HSR_BINARY) + " render " + test::sourcePath("scenes/cube.toml").string() +
                              " --size 96x72 --algo ray_casting -o " + image.string() + " --steps " + folder.string();
  const test::CommandResult result = test::runCommand(command + " --every 8");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  std::vector<std::string> captions;
  std::ifstream in(folder / "captions.txt");
  for (std::string line; std::getline(in, line);) captions.push_back(line);
  // Rows 8, 16, ..., 72 and the finished image.
  ASSERT_EQ(captions.size(), 72u / 8 + 1);
  for (std::size_t s = 0; s < captions.size(); ++s) {
    char name[32];
    std::snprintf(name, sizeof name, "step-%04zu.png", s + 1);
    EXPECT_TRUE(std::filesystem::exists(folder / name)) << name;
    EXPECT_EQ(captions[s].substr(0, 5), std::string(name).substr(5, 4) + " ");
  }
  EXPECT_NE(captions.front().find("row 8 of 72"), std::string::npos) << captions.front();
  Image animation;
  ASSERT_EQ(imageLibrary().readImage((folder / "steps.gif").string(), animation), "");
  EXPECT_GT(animation.width, 2 * 96);  // the image beside its cost heat map
  // The steps page lists each picture once, in order, under the command that records them again.
  std::ifstream pageFile(folder / "steps.html");
  const std::string page((std::istreambuf_iterator<char>(pageFile)), std::istreambuf_iterator<char>());
  std::size_t listed = 0;
  for (std::size_t at = page.find("\"picture\":\"step-"); at != std::string::npos; at = page.find("\"picture\":\"step-", at + 1)) ++listed;
  EXPECT_EQ(listed, captions.size());
  EXPECT_NE(page.find("<h1>hsr render " + test::sourcePath("scenes/cube.toml").string() + " --algo ray_casting --size 96x72 --every 8 -o " +
                      image.string() + " --steps " + folder.string() + "</h1>"),
            std::string::npos);
  // A second run recording fewer frames leaves none of the first run's behind.
  ASSERT_EQ(test::runCommand(command + " --every 36").exitCode, 0);
  EXPECT_TRUE(std::filesystem::exists(folder / "step-0003.png"));
  EXPECT_FALSE(std::filesystem::exists(folder / "step-0004.png"));
}

}  // namespace
}  // namespace hsr
