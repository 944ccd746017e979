// report.html: the page hsr compare, hsr sweep and hsr study write beside their files,
// for a person to read in a browser: the command line that produced it, the machine,
// every CSV the run wrote as a table that sorts by any column on a click, and every
// image and plot, each opening full size on a click. Self-contained: no network, no
// files but the run's own (a few lines of inline script and style).
#pragma once

#include <filesystem>
#include <string>


namespace hsr::studies {

// Who asked for the run, as the command line gave it.
struct Invocation {
  std::string commandLine;  // the arguments as typed, quoted where they hold a space
  std::string version;      // hsr --version's first line
};

// Writes folder/report.html describing the files of the folder this run wrote (those
// modified since `runStart`; older ones, from earlier runs into the same folder, are
// left out): every CSV as a table, every PNG and SVG as a picture (a plot's PNG beside
// its SVG shown once, as the SVG), and a list of them all.
void writeReport(const std::filesystem::path& folder, const std::string& title, const Invocation& invocation,
                 std::filesystem::file_time_type runStart);

// The machine the report names: the processor and how many cores the program may use.
std::string machineDescription();

}  // namespace hsr::studies
