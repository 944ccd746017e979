// The steps page (steps.html, written beside the step pictures by hsr render --steps):
// a student goes through an algorithm's steps by hand, first / previous / next / last,
// a slider, "step N of M", the caption, and beside each picture the lines of the
// algorithm's code that recorded it, read from the file at the line the recording call
// captured (std::source_location, or its stand-in: renderer/util/source_location.hpp);
// and, for an algorithm that answers why, a click on a pixel gives the hsr why command
// that shows the pixel's history up to the step. One self-contained HTML file: it opens from the folder with no server and nothing to
// install.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "renderer/util/source_location.hpp"

namespace hsr {

// The lines of code around a recording call, as the page shows them.
struct SourceExcerpt {
  std::string file;      // relative to the suite's folder where it is in it: algorithms/zbuffer/full_frame.cpp
  std::string function;  // the function the call is in, as the compiler names it
  int line = 0;          // the recording statement's first line
  int firstLine = 0;     // the line lines[0] is
  int markedTo = 0;      // its last line (it may span several)
  std::vector<std::string> lines;  // empty when the file cannot be read (the program moved away from its sources)
};

// From the top of the enclosing function (the last line before the call that starts at
// column 0, at most kLinesBefore lines up) to the end of the recording statement and two
// lines more. The suite's files are read from `sourceRoot`: the folder the program was
// built from by default.
SourceExcerpt sourceExcerpt(const SourceLocation& where, const std::filesystem::path& sourceRoot = "");
// The file alone, as the excerpt names it (nothing is read).
std::string recordedIn(const SourceLocation& where);
inline constexpr int kLinesBefore = 24;

struct PageStep {
  std::string picture;  // the picture's file name, beside the page
  std::string caption;
  SourceExcerpt source;
};

// The page's steps: each step's caption and where it was recorded, with its picture's
// address. A loop's steps share their recording place, whose lines are read once (from
// `sourceRoot`, as sourceExcerpt reads them).
std::vector<PageStep> pageSteps(const std::vector<std::pair<std::string, SourceLocation>>& recorded, const std::vector<std::string>& pictures,
                                const std::filesystem::path& sourceRoot = "");

// What a click on a pixel of a step's picture asks about: `command` is hsr why's for the
// render the steps are of, without --pixel and --step (which the page adds: the pixel's
// history up to the step shown), and the render is width x height, whose pixels each
// panel of a picture shows from its top left. An empty command: the algorithm does not
// answer why at a pixel, and a click asks nothing.
//
// In the browser edition the page is shown inside the edition's own page, which answers
// the click itself (`host`): the steps page posts it {kind: "hsr-why", x, y, step} and
// shows the text of the {kind: "hsr-why-answer", text} it posts back, the history up to
// the step as hsr why prints it; `command` then only says that a click asks.
struct PixelQuestion {
  std::string command;
  int width = 0, height = 0;
  bool host = false;
};
// The white gap between pictures placed side by side (besideEachOther), which a click on
// a later panel steps over.
inline constexpr int kPanelGap = 6;

// The page: `title` heads it; the steps in order.
std::string stepsPage(const std::string& title, const std::vector<PageStep>& steps, const PixelQuestion& question = {});

}  // namespace hsr
