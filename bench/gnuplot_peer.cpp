// The peer for the floating horizon: gnuplot's `set hidden3d` (Debian's gnuplot) on the
// same function (4 sin r / r), grid (40 x 40 and 100 x 100 lines each way) and view
// (azimuth 30, elevation 30), both drawing a 640 x 480 PNG, timed in one run, interleaved.
//
//   build/bench/gnuplot_peer [--runs R] [--out FOLDER]
//
// Each side is timed as the whole command a user would run: `gnuplot script.gp` and
// `hsr render ripple.toml --algo floating_horizon --knob mesh=on -o x.png`, process start,
// drawing and PNG writing included. gnuplot tests each grid edge against the surface's
// polygons (it is not a floating horizon), so its picture shows what should be visible;
// its screen mapping is its own, so the pictures are compared by eye, not by pixel.
// --out keeps both pictures of each grid (the README's side-by-side figure).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "peer_timing.hpp"

namespace {

using hsr::bench::millisecondsOf;
using hsr::bench::Timing;

void write(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

std::string rippleScene(int grid) {
  return R"([image]
width = 640
height = 480
background = [1, 1, 1]

[camera]
type = "orthographic"
target = [0, 0, 0]
azimuth = 30
elevation = 30
distance = 40
height = 21

[[objects]]
shape = "heightfield"
function = "ripple"
size = [20, 20]
amplitude = 4
segments = [)" + std::to_string(grid - 1) + ", " + std::to_string(grid - 1) + "]\n";
}

std::string gnuplotScript(int grid, const std::filesystem::path& png) {
  return "set terminal pngcairo size 640,480\nset output '" + png.string() +
         "'\nunset key; unset border; unset tics\nset hidden3d\nset isosamples " + std::to_string(grid) + "," +
         std::to_string(grid) + "\nset samples " + std::to_string(grid) + "," + std::to_string(grid) +
         "\nset xrange [-10:10]; set yrange [-10:10]\nset view 60, 30\nset view equal xyz\n"
         "r(x,y) = sqrt(x*x+y*y)\nf(x,y) = r(x,y) < 1e-9 ? 4 : 4*sin(r(x,y))/r(x,y)\n"
         "splot f(x,y) with lines lc rgb 'black'\n";
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 11;
  std::filesystem::path out;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--runs" && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
    else if (argument == "--out" && i + 1 < argc) out = argv[++i];
    else {
      std::fprintf(stderr, "usage: gnuplot_peer [--runs R] [--out FOLDER]\n");
      return 2;
    }
  }
  if (std::system("gnuplot --version > /dev/null 2>&1") != 0) {
    std::fprintf(stderr, "gnuplot_peer: gnuplot is not installed (scripts/setup.sh installs gnuplot-nox)\n");
    return 1;
  }
  const std::filesystem::path work = std::filesystem::temp_directory_path() / "hsr_gnuplot_peer";
  std::filesystem::create_directories(work);
  if (!out.empty()) std::filesystem::create_directories(out);
  std::printf("whole commands, ms: median [min-max]; hsr = floating_horizon mesh=on at its defaults (640 samples per curve)\n");
  for (const int grid : {40, 100}) {
    const std::string name = "ripple" + std::to_string(grid);
    const std::filesystem::path scene = work / (name + ".toml"), script = work / (name + ".gp");
    const std::filesystem::path gnuplotPng = (out.empty() ? work : out) / (name + "_gnuplot.png");
    const std::filesystem::path hsrPng = (out.empty() ? work : out) / (name + "_hsr.png");
    write(scene, rippleScene(grid));
    write(script, gnuplotScript(grid, gnuplotPng));
    const std::string gnuplot = "gnuplot " + script.string();
    const std::string hsr = std::string(HSR_BINARY) + " render " + scene.string() +
                            " --algo floating_horizon --knob mesh=on --threads 1 -o " + hsrPng.string();
    // gnuplot samples each line at its grid points (set samples); hsr at the same count too.
    const std::string hsrAtGrid = hsr + " --knob samples=" + std::to_string(grid);
    // What any hsr command costs before it draws: the cube with the z-buffer.
    const std::string hsrStart = std::string(HSR_BINARY) + " render " + HSR_SOURCE_DIR + "/scenes/cube.toml --threads 1 -o " +
                                 (work / "cube.png").string();
    Timing gnuplotTime, hsrTime, hsrAtGridTime, hsrStartTime;
    for (int run = 0; run <= runs; ++run) {  // run 0 warms the file cache and is not counted
      int status = 0;
      const double g = millisecondsOf([&] { status |= std::system(gnuplot.c_str()); });
      const double h = millisecondsOf([&] { status |= std::system(hsr.c_str()); });
      const double a = millisecondsOf([&] { status |= std::system(hsrAtGrid.c_str()); });
      const double c = millisecondsOf([&] { status |= std::system(hsrStart.c_str()); });
      if (status != 0) {
        std::fprintf(stderr, "gnuplot_peer: a command failed:\n  %s\n  %s\n", gnuplot.c_str(), hsr.c_str());
        return 1;
      }
      if (run > 0) {
        gnuplotTime.milliseconds.push_back(g);
        hsrTime.milliseconds.push_back(h);
        hsrAtGridTime.milliseconds.push_back(a);
        hsrStartTime.milliseconds.push_back(c);
      }
    }
    std::printf("%3d x %-3d   gnuplot %6.1f [%.1f-%.1f]   hsr %6.1f [%.1f-%.1f]   hsr samples=%d %6.1f [%.1f-%.1f]   hsr on a cube %6.1f\n",
                grid, grid, gnuplotTime.median(), gnuplotTime.min(), gnuplotTime.max(), hsrTime.median(), hsrTime.min(),
                hsrTime.max(), grid, hsrAtGridTime.median(), hsrAtGridTime.min(), hsrAtGridTime.max(), hsrStartTime.median());
  }
  return 0;
}
