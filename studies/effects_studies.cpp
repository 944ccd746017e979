// The effects studies (README "Effects on demand"):
//   effects     the showcase (scenes/effects.toml) with each effect added in turn, drawn
//               by the z-buffer: the time of each pass (median of --frames renders), a
//               contact sheet of the steps with what each changed, and the pass plan
//   shadow-map  the shadow map's resolution against its bias: the fraction of shadow
//               decisions that differ from exact shadow rays (acne and peter-panning
//               apart), and the time of the shadow pass
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "algorithms/zbuffer/zbuffer.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/shadow_maps.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "studies/common.hpp"
#include "studies/contact_sheet.hpp"
#include "studies/effect_ladder.hpp"
#include "studies/interrupt.hpp"
#include "studies/plot.hpp"
#include "studies/results.hpp"
#include "studies/studies.hpp"

namespace hsr::studies {
namespace {

const char* const kShowcase = "effects.toml";

// --------------------------------------------------------------------------------
// effects

int effectsLadder(const StudyOptions& options, const std::filesystem::path& folder) {
  const LoadedScene showcase = loadPrepared((std::filesystem::path(HSR_SCENES_DIR) / kShowcase).string(), options.size);
  const int width = showcase.prepared->width(), height = showcase.prepared->height();
  const int repeats = options.frames > 0 ? options.frames : 9;
  const pipeline::Configuration zbuffer = pipeline::configurationOf(zbuffer::entry, zbuffer::knobTable());
  const std::vector<std::string> passes = {"visibility", "shadow maps", "shading", "transparency", "fog", "outline"};

  std::printf("effects added in turn to %s, %dx%d, z-buffer, %d renders on %d thread(s), ms: median [fastest-slowest]:\n  %-16s",
              kShowcase, width, height, repeats, options.threads, "step");
  for (const std::string& pass : passes) std::printf(" %21s", pass.c_str());
  std::printf(" %21s %8s\n", "total", "x none");
  std::vector<CsvRow> rows;
  std::vector<std::pair<std::string, Timing>> measured;  // for the busy-machine warning
  std::string data = "$steps << EOD\n";
  SheetSection section;
  section.heading = std::string(kShowcase) + ", each effect added in turn (z-buffer; red: the pixels the step changed)";
  PixelBuffer<std::uint8_t> previous;
  double noneTotal = 0;
  for (const EffectStep& step : effectLadder(*showcase.scene)) {
    PreparedScene prepared(step.scene);
    prepared.setSize(width, height);
    std::vector<std::vector<double>> samples(passes.size());
    std::vector<double> totals;
    Frame frame;
    for (int r = -1; r < repeats; ++r) {  // r = -1: a warm-up render, untimed (caches cold, normals' index built)
      Stats stats;
      const auto start = std::chrono::steady_clock::now();
      frame = pipeline::render(prepared, zbuffer, options.threads, stats).frame;
      if (r < 0) continue;
      totals.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      const std::vector<pipeline::PassTime> times = pipeline::passTimes(stats);
      for (std::size_t p = 0; p < passes.size(); ++p) {
        const auto found = std::find_if(times.begin(), times.end(), [&](const pipeline::PassTime& t) { return t.pass == passes[p]; });
        samples[p].push_back(found == times.end() ? 0.0 : found->seconds);
      }
    }
    const Timing total = summarize(totals);
    measured.emplace_back(step.name, total);
    if (rows.empty()) noneTotal = total.median;
    std::printf("  %-16s", step.name.c_str());
    CsvRow row = {{"step", step.name}};
    data += "\"" + step.name + "\"";
    for (std::size_t p = 0; p < passes.size(); ++p) {
      const Timing pass = summarize(samples[p]);
      std::printf(" %21s", formattedRange(pass, 1e3).c_str());
      row.emplace_back(passes[p] + "_ms", formatted(pass.median * 1e3, "%.4f"));
      row.emplace_back(passes[p] + "_min_ms", formatted(pass.min * 1e3, "%.4f"));
      row.emplace_back(passes[p] + "_max_ms", formatted(pass.max * 1e3, "%.4f"));
      data += ' ';
      data += formatted(pass.median * 1e3, "%.4g");
    }
    std::printf(" %21s %8.2f\n", formattedRange(total, 1e3).c_str(), total.median / noneTotal);
    row.emplace_back("total_ms", formatted(total.median * 1e3, "%.4f"));
    row.emplace_back("total_min_ms", formatted(total.min * 1e3, "%.4f"));
    row.emplace_back("total_max_ms", formatted(total.max * 1e3, "%.4f"));
    row.emplace_back("ratio_to_none", formatted(total.median / noneTotal, "%.3f"));
    rows.push_back(row);
    data += timingColumns(total, 1e3);
    data += "\n";

    // The step's image, and where it differs from the step before.
    PixelBuffer<std::uint8_t> changed = frame.color;
    for (std::size_t pixel = 0; pixel < frame.pixelCount(); ++pixel) {
      const bool differs = !previous.empty() && !std::equal(&frame.color[4 * pixel], &frame.color[4 * pixel + 3], &previous[4 * pixel]);
      const std::uint8_t grey = static_cast<std::uint8_t>(frame.color[4 * pixel + 1] / 3 + 150);
      const std::uint8_t marked[4] = {differs ? std::uint8_t(220) : grey, differs ? std::uint8_t(30) : grey,
                                      differs ? std::uint8_t(30) : grey, 255};
      std::copy(marked, marked + 4, &changed[4 * pixel]);
    }
    section.images.push_back({width, height, frame.color, {step.name, formatted(total.median * 1e3, "%.1f") + " ms"}});
    section.heatMaps.push_back({width, height, changed, {previous.empty() ? "the start" : "what it changed"}});
    previous = frame.color;
  }
  const Image sheet = composeContactSheet({section});
  OutputFiles files;
  files.addRgbaPng(folder / "effects_steps.png", sheet.width, sheet.height, sheet.pixels);
  files.commit();
  std::printf("wrote %s/effects_steps.png\n", folder.string().c_str());
  data += "EOD\nset title 'Each effect added in turn: time per pass (z-buffer, median; bar: the total, fastest to slowest)'\n"
          "set xlabel 'effects listed (one more per bar)'\nset ylabel 'ms'\nset yrange [0:*]\nset style data histogram\nset style histogram rowstacked\nset style fill solid 0.85 border -1\n"
          "set boxwidth 0.7\nset grid ytics\nset xtics rotate by -25\nset key outside right font ',9'\nplot ";
  data += histogramBars("$steps", passes);
  const std::string total = std::to_string(passes.size() + 2);
  data += ", $steps using 0:" + total + ":" + std::to_string(passes.size() + 3) + ":" + std::to_string(passes.size() + 4) +
          " with yerrorbars lc rgb 'black' pt 7 ps 0.6 title 'total'";
  warnIfBusy(measured, "--frames " + std::to_string(std::max(9, 3 * repeats)));
  writeStudy(folder, "effects", csvOf(rows), data + "\n");
  return 0;
}

// --------------------------------------------------------------------------------
// shadow-map

int shadowMapSweep(const StudyOptions& options, const std::filesystem::path& folder) {
  const LoadedScene showcase = loadPrepared((std::filesystem::path(HSR_SCENES_DIR) / kShowcase).string(), options.size);
  // The shadows step of the ladder: lit, shadowed, nothing else.
  Scene scene;
  for (const EffectStep& step : effectLadder(*showcase.scene))
    if (step.name == "+ shadows") scene = step.scene;
  PreparedScene prepared(scene);
  prepared.setSize(showcase.prepared->width(), showcase.prepared->height());
  Stats stats;
  const Frame frame = pipeline::render(prepared, pipeline::configurationOf(zbuffer::entry, zbuffer::knobTable()), options.threads, stats).frame;
  const ExactShadows exact(prepared, stats);
  const std::vector<int> resolutions = {128, 256, 512, 1024, 2048, 4096};
  const std::vector<double> biases = {0, 0.5, 1, 1.5, 3, 6, 12};
  const int repeats = options.frames > 0 ? options.frames : 3;

  std::printf("shadow map resolution x bias on %s (%dx%d): %% of shadow decisions that differ from exact shadow rays "
              "(falsely shadowed + falsely lit)\n  %-8s", kShowcase, prepared.width(), prepared.height(), "bias");
  for (const int resolution : resolutions) std::printf(" %16d", resolution);
  std::printf("\n");
  std::vector<CsvRow> rows;
  std::string data = "$errors << EOD\n";
  std::vector<Timing> passTime(resolutions.size());  // seconds; the last bias's runs
  const InterruptibleRun interruptible;
  for (const double bias : biases) {
    if (InterruptibleRun::requested()) break;
    std::printf("  %-8g", bias);
    data += formatted(bias, "%g");
    for (std::size_t r = 0; r < resolutions.size(); ++r) {
      if (InterruptibleRun::requested()) break;
      std::vector<double> times;
      std::optional<pipeline::ShadowMaps> maps;
      for (int k = -1; k < repeats; ++k) {  // k = -1: a warm-up, untimed
        Stats mapStats;
        maps.emplace(prepared, ShadowSettings{resolutions[r], bias}, options.threads, mapStats);
        if (k >= 0) times.push_back(mapStats.seconds("shadow maps"));
      }
      passTime[r] = summarize(times);
      const ShadowError error = shadowError(prepared, frame, *maps, exact, options.threads);
      std::printf(" %7.3f=%4.2f+%4.2f", 100 * error.fraction, 100.0 * double(error.falselyShadowed) / double(error.lookups),
                  100.0 * double(error.falselyLit) / double(error.lookups));
      rows.push_back({{"resolution", std::to_string(resolutions[r])},
                      {"bias_texels", formatted(bias, "%g")},
                      {"lookups", std::to_string(error.lookups)},
                      {"falsely_shadowed", std::to_string(error.falselyShadowed)},
                      {"falsely_lit", std::to_string(error.falselyLit)},
                      {"error_fraction", formatted(error.fraction, "%.6f")},
                      {"shadow_pass_ms_median", formatted(passTime[r].median * 1e3, "%.4f")},
                      {"shadow_pass_ms_min", formatted(passTime[r].min * 1e3, "%.4f")},
                      {"shadow_pass_ms_max", formatted(passTime[r].max * 1e3, "%.4f")}});
      data += ' ';
      data += formatted(100 * error.fraction, "%.5g");
    }
    data += "\n";
    std::printf("\n");
    std::fflush(stdout);  // a line per bias as it is measured, also through a pipe
  }
  std::printf("  %-8s", "pass ms");
  for (const Timing& time : passTime) std::printf(" %16s", formattedRange(time, 1e3).c_str());
  std::printf("\n");
  std::vector<std::pair<std::string, Timing>> measured;
  for (std::size_t r = 0; r < resolutions.size(); ++r) measured.emplace_back("the shadow pass at " + std::to_string(resolutions[r]), passTime[r]);
  warnIfBusy(measured, "--frames " + std::to_string(std::max(9, 3 * repeats)));
  data += "EOD\n$times << EOD\n";
  for (std::size_t r = 0; r < resolutions.size(); ++r) {
    data += std::to_string(resolutions[r]);
    data += timingColumns(passTime[r], 1e3);
    data += "\n";
  }
  data += "EOD\nset multiplot layout 1,2\nset title 'Shadow decisions off the exact rays'\nset ylabel '% of lookups'\n"
          "set xlabel 'bias (texels at the receiver)'\nset logscale y\nset grid\nset key top right title 'resolution' font ',9'\n"
          "set style data linespoints\nplot ";
  for (std::size_t r = 0; r < resolutions.size(); ++r) {
    if (r > 0) data += ", ";
    data += "$errors using 1:" + std::to_string(r + 2) + " title '" + std::to_string(resolutions[r]) + "'";
  }
  data += "\nunset logscale y\nset logscale x 2\nset title 'Shadow pass time'\nset xlabel 'resolution (texels per side)'\n"
          "set ylabel 'ms (median, bar: fastest to slowest)'\nset key off\nplot $times using 1:2:3:4 with yerrorlines\nunset multiplot\n";
  return finishStudy(folder, "shadow_map", rows, biases.size() * resolutions.size(), data);
}

}  // namespace

int effectsStudy(const StudyOptions& options, const std::filesystem::path& folder) {
  if (options.name == "effects") return effectsLadder(options, folder);
  return shadowMapSweep(options, folder);
}

}  // namespace hsr::studies
