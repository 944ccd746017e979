#include "studies/plot.hpp"

#include <cmath>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include <unistd.h>

#include "studies/interrupt.hpp"

namespace hsr::studies {
namespace {

std::string script(const std::string& png, const std::string& svg, const std::string& body) {
  return "set terminal pngcairo noenhanced size 960,640 font 'DejaVu Sans,11'\nset output '" + png + "'\n" + body +
         "\nset terminal svg noenhanced size 960,640 font 'DejaVu Sans,11'\nset output '" + svg + "'\nreplot\n";
}

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

void addPlot(OutputFiles& files, const std::filesystem::path& folder, const std::string& stem, const std::string& body) {
  files.addText(folder / (stem + ".gp"), script(stem + ".png", stem + ".svg", body));
  const std::filesystem::path png = files.addWrittenElsewhere(folder / (stem + ".png"));
  const std::filesystem::path svg = files.addWrittenElsewhere(folder / (stem + ".svg"));
  const std::filesystem::path runnable = std::filesystem::temp_directory_path() / ("hsr-plot-" + std::to_string(::getpid()) + ".gp");
  {
    std::ofstream file(runnable);
    file << script(png.string(), svg.string(), body);
  }
  const std::string command = "gnuplot '" + runnable.string() + "' 2>&1";
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe) {
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  }
  const int status = pipe ? pclose(pipe) : -1;
  std::filesystem::remove(runnable);
  if (status != 0 || !std::filesystem::exists(png) || !std::filesystem::exists(svg))
    throw std::runtime_error("gnuplot failed (is it installed? scripts/setup.sh installs gnuplot-nox): " + output);
}

Progress::Progress(std::size_t total) : total_(total), start_(now()) {}

Progress::~Progress() {
  if (shown_) std::fprintf(stderr, "\n");
}

void Progress::update(std::size_t done, const std::string& label) {
  const double elapsed = now() - start_;
  if (!isatty(STDERR_FILENO) || elapsed < 1.0) return;
  shown_ = true;
  constexpr int kWidth = 30;
  const int filled = int(kWidth * done / std::max<std::size_t>(total_, 1));
  std::fprintf(stderr, "\r  [%s%s] %zu/%zu  %.1f s  %-40.40s", std::string(std::size_t(filled), '#').c_str(),
               std::string(std::size_t(kWidth - filled), '.').c_str(), done, total_, elapsed, label.c_str());
  std::fflush(stderr);
}

void writeStudy(const std::filesystem::path& folder, const std::string& stem, const std::string& csv, const std::string& plotBody) {
  OutputFiles files;
  files.addText(folder / (stem + ".csv"), csv);
  addPlot(files, folder, stem, plotBody);
  files.commit();
  std::printf("wrote %s/%s.{csv,png,svg,gp}\n", folder.string().c_str(), stem.c_str());
}

int finishStudy(const std::filesystem::path& folder, const std::string& stem, const std::vector<CsvRow>& rows,
                std::size_t plannedRows, const std::string& plotBody) {
  if (!InterruptibleRun::requested()) {
    writeStudy(folder, stem, csvOf(rows), plotBody);
    return 0;
  }
  reportInterrupted(rows.size(), plannedRows, "rows");
  if (rows.empty()) return kInterruptedExit;
  OutputFiles files;
  files.addText(folder / (stem + ".csv"), csvOf(rows));
  files.commit();
  std::printf("wrote %s/%s.csv (no plot: the study was cut short)\n", folder.string().c_str(), stem.c_str());
  return kInterruptedExit;
}

std::string timeAxis(char axis, const std::vector<double>& values, bool bars) {
  double smallest = INFINITY, largest = 0;
  for (const double value : values)
    if (value > 0 && std::isfinite(value)) smallest = std::min(smallest, value), largest = std::max(largest, value);
  if (largest > kLogarithmicSpan * smallest) return std::string("set logscale ") + axis + "\n";
  return bars ? std::string("set ") + axis + "range [0:*]\n" : "";
}

std::string timingColumns(const Timing& time, double scale) {
  char text[96];
  std::snprintf(text, sizeof text, " %.5g %.5g %.5g", time.median * scale, time.min * scale, time.max * scale);
  return text;
}

std::string histogramBars(const std::string& block, const std::vector<std::string>& titles, std::size_t columnsPerBar) {
  std::string clause;
  for (std::size_t c = 0; c < titles.size(); ++c) {
    if (c > 0) clause += ", ";
    clause += block + " using ";
    for (std::size_t k = 0; k < columnsPerBar; ++k) {
      if (k > 0) clause += ':';
      clause += std::to_string(2 + c * columnsPerBar + k);
    }
    if (c == 0) clause += ":xtic(1)";
    clause += " title '" + titles[c] + "'";
  }
  return clause;
}

}  // namespace hsr::studies
