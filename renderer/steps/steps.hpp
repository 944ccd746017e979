// Steps: pictures of an algorithm's own state at its textbook steps, for a student to
// watch it work (hsr render --steps DIR). An algorithm is handed a StepRecorder only when
// steps were asked for (a null pointer otherwise, so a render without --steps does no
// step work at all); it records from its own loops, between iterations, the state those
// loops hold: never a second implementation of the algorithm.
//
// The pictures are built with the helpers below: the surfaces a buffer of triangle ids
// shows, a depth buffer, a heat map with its legend, lines drawn over a picture, and text
// (legends, labels) in the label font compiled in (label_font.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "renderer/geometry/camera.hpp"
#include "renderer/image/frame.hpp"
#include "renderer/scene/prepare.hpp"
#include "renderer/steps/label_font.hpp"
#include "renderer/steps/steps_page.hpp"
#include "renderer/util/math.hpp"
#include "renderer/util/source_location.hpp"

namespace hsr {

struct Step {
  std::string caption;         // one line: the textbook step and what it did
  Image picture;               // RGBA
  SourceLocation where;  // the algorithm's line that recorded it (the steps page shows it)
};

class StepRecorder {
 public:
  // Where the steps go: kept in steps() (no sink), or handed one by one to a sink that
  // writes them as they come (StepsWriter), so that no frame stays in memory longer
  // than it takes to write it.
  using Sink = std::function<void(Step)>;  // the step is the sink's to keep (moved in)
  // A repeated step (a triangle drawn, a row cast, a curve added) is recorded every
  // `every`th time; 0 chooses, for each run of repeated steps, the stride that records
  // about kFramesPerRun of them.
  static constexpr std::size_t kFramesPerRun = 40;
  explicit StepRecorder(std::size_t every = 0, Sink sink = nullptr) : every_(every), sink_(std::move(sink)) {}

  // Whether the index-th of `count` repeated steps is recorded: every stride-th, and
  // always the last, so that the run ends on its finished state.
  bool due(std::size_t index, std::size_t count) const;
  // Whether the index-th of an event whose count is not known ahead (a reorder, a split)
  // is recorded: every `every`th, or with every = 0 the first kFramesPerRun.
  bool due(std::size_t index) const;
  // Records a step, and where in the algorithm's code it was recorded: the line that
  // calls record(), or the line an algorithm's helper was called from when the helper
  // passes its own `where` on. Safe from any thread; the steps keep the order of the
  // calls, so an algorithm records from one thread (between its parallel loops) where
  // order matters.
  void record(std::string caption, Image picture, SourceLocation where = SourceLocation::current());
  const std::vector<Step>& steps() const { return steps_; }  // the kept ones: none with a sink

 private:
  std::size_t every_;
  Sink sink_;
  std::mutex mutex_;
  std::vector<Step> steps_;
};

// What is wrong with a number of steps as typed (--every, --step): "" for a whole number
// from 0 to kMostSteps, or the line that says what was expected.
inline constexpr int kMostSteps = 999999999;
std::string stepCountError(const std::string& text);

// Colours of the step pictures.
inline constexpr Rgb kHighlight{220, 30, 30};        // what the step just did
inline constexpr Rgb kSecondHighlight{30, 90, 220};  // what it did it against
inline constexpr Rgb kThirdHighlight{235, 140, 0};   // a third thing the step shows

// A blank RGBA picture.
Image blankPicture(int width, int height, Rgb color = {255, 255, 255});

// The surfaces a buffer of triangle ids (global index + 1, 0 = background) shows: each
// triangle in its object's colour, darker the more it turns away from a light above and
// behind the eye, so that faces read as faces before any shading pass has run.
// Background is light grey.
Image surfacePicture(const PreparedScene& scene, const CameraTransform& view, std::span<const std::uint32_t> ids, int width,
                     int height);
// A depth buffer (view distances, +infinity = background): nearest white, farthest dark
// grey over the finite depths it holds, background black.
Image depthPicture(std::span<const float> depth, int width, int height);
// Non-negative values per pixel as a heat map (black, red, yellow, white from 0 to the
// largest), with a legend band below: the colour ramp and its ends labelled in `unit`.
Image heatMapPicture(std::span<const double> values, int width, int height, const std::string& unit);
// Pictures placed left to right, tops aligned, on white.
Image besideEachOther(const std::vector<Image>& pictures);
// Some pixels (row-major indices) blended half-way toward a colour: what a step just drew.
void tint(Image& picture, std::span<const std::size_t> pixels, Rgb color);
// Draws a segment of the given width in pixels (renderer/raster/raster's line rule).
void drawSegment(Image& picture, const dvec2& a, const dvec2& b, Rgb color, double width = 1.5);
// The edges of some triangles, seen from the view (the parts nearer than the near plane cut off).
void drawWireframe(Image& picture, const PreparedScene& scene, const CameraTransform& view, std::span<const std::uint32_t> triangles,
                   Rgb color);
// A legend in the top left corner: one coloured line sample and its text per entry.
void drawLegend(Image& picture, const std::vector<std::pair<Rgb, std::string>>& entries);
// A Graphviz diagram (the text of a `dot` graph) drawn by Graphviz's dot program; where
// no program can be started (the browser edition), a picture saying so.
Image graphvizPicture(const std::string& graph);
// The picture with a white band above it holding the caption, for an animation frame.
Image withCaption(const Image& picture, const std::string& caption);

// The names of the index-th step's files (from 0): its number "0001" and its picture
// "step-0001.png".
std::string stepNumber(std::size_t index);
inline std::string stepPictureName(std::size_t index) { return "step-" + stepNumber(index) + ".png"; }

// Steps written to a folder as they are recorded (a StepRecorder's sink): step-0001.png,
// step-0002.png... at once, under temporary names (OutputFiles), while only the caption,
// where it was recorded and a small animation frame are kept; finish() adds captions.txt
// (one line per frame, "0001 caption"), steps.gif (the frames with their captions, at
// most 720 pixels wide, padded to one size, at `framesPerSecond`) and steps.html (the
// steps to go through by hand beside the code that recorded each: steps_page.hpp), and
// renames every file into place. A run that fails before finish() leaves nothing behind.
class StepsWriter {
 public:
  explicit StepsWriter(std::filesystem::path folder, int framesPerSecond = 4)
      : folder_(std::move(folder)), framesPerSecond_(framesPerSecond) {}
  void add(const Step& step);
  std::size_t count() const { return frames_.size(); }
  // `title` heads the steps page: what was run (the command that records these steps
  // again); `question`: what a click on a pixel of its pictures asks (steps_page.hpp).
  void finish(const std::string& title, const PixelQuestion& question = {});

 private:
  std::filesystem::path folder_;
  int framesPerSecond_;
  OutputFiles files_;
  std::vector<std::pair<std::string, SourceLocation>> recorded_;  // each step's caption, and where it was recorded
  std::vector<Image> frames_;
};

}  // namespace hsr
