// Plots through gnuplot (Debian's gnuplot-nox): the script is generated, kept beside
// the plots so a reader can edit and re-run it, and run once for PNG and SVG.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "renderer/image/frame.hpp"
#include "studies/results.hpp"

namespace hsr::studies {

// `body` is the gnuplot text after the terminal and output lines, ending in a plot
// command. Adds stem.gp, stem.png and stem.svg in `folder` to `files`.
void addPlot(OutputFiles& files, const std::filesystem::path& folder, const std::string& stem, const std::string& body);
// The rule every plot's time axis follows: logarithmic when the values it shows span
// more than kLogarithmicSpan (largest over smallest positive), since below that a
// linear axis reads truer; linear otherwise, and from zero for a bar chart (`bars`),
// whose bars are read by their lengths. `axis` is 'x' or 'y'. Returns gnuplot lines.
inline constexpr double kLogarithmicSpan = 20;
std::string timeAxis(char axis, const std::vector<double>& values, bool bars);
// A histogram's plot clause over a named data block whose first column labels the
// x axis and whose next columns are the bars, one title each, `columnsPerBar` columns
// a bar (3 for a histogram with error bars: the value, its low and its high):
// "$block using 2:xtic(1) title 'a', $block using 3 title 'b'".
std::string histogramBars(const std::string& block, const std::vector<std::string>& titles, std::size_t columnsPerBar = 1);
// A timing's median, fastest and slowest as three columns of a plot's data block, each
// multiplied by `scale` and led by a space: " 8.73 8.7 9.02" (a point and its error bar).
std::string timingColumns(const Timing& time, double scale);
// A study's results: FOLDER/STEM.csv and its plot (addPlot), written together.
void writeStudy(const std::filesystem::path& folder, const std::string& stem, const std::string& csv, const std::string& plotBody);

// The end of a study measured row by row under an InterruptibleRun (cli/interrupt): all
// of writeStudy when it ran to the end (returns 0); when Ctrl-C cut it short, the CSV of
// the rows measured, complete, and no plot, since a plot of part of a study misleads
// (returns kInterruptedExit).
int finishStudy(const std::filesystem::path& folder, const std::string& stem, const std::vector<CsvRow>& rows,
                std::size_t plannedRows, const std::string& plotBody);

// A bar on stderr, shown only on a terminal and only once the work has taken a second.
class Progress {
 public:
  explicit Progress(std::size_t total);
  ~Progress();
  void update(std::size_t done, const std::string& label);

 private:
  std::size_t total_;
  double start_;
  bool shown_ = false;
};

}  // namespace hsr::studies
