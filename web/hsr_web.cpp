// The browser edition's bridge (scripts/web.sh builds it into WebAssembly): what the page
// (web/app.js) asks of the suite, as functions it calls through embind. Everything runs in
// the page; the page first writes the files a scene needs (the shipped scenes and models,
// or a student's own TOML and OBJ files) into the module's in-memory file system.
//
//   registry()            the algorithms, their knobs and the culling stages, from the
//                         same registry `hsr list` prints: the page builds its controls
//                         from it, so a new algorithm or knob needs no change to the page
//   render(request)       one render: the images (colour, ids, depth) as views of the
//                         module's memory, and the counters and times as JSON; after bad
//                         input the render before stays (hasRender())
//   compare()             that render against the exact reference: the metrics hsr
//                         compare prints, as JSON, the error heat map, and the
//                         reference's ids (the page toggles between them and the render's)
//   why(x, y, step)       how that render decided pixel (x, y), beside the exact
//                         reference's answer: what hsr why prints, and its --json (for
//                         a line drawing, the edge nearest the pixel: hsr why --edge X,Y);
//                         with a step (from 1), the history up to it (hsr why --step)
//   recordSteps(every)    that render's steps, as hsr render --steps records them; then
//   stepPicture(i)        each step's picture, which the page makes an image of, and
//   stepsPage(title, pictures)  the steps page (renderer/steps/steps_page.hpp) showing
//                         those images, whose pixel clicks the page answers with why()
//   identity(width, N)    every render's line of hashes (tests/identity): the same bits
//                         as native, checked in the page
//
// Bad input (a broken TOML, an OBJ with a bad face, an absurd size) comes back as the one
// line the command line prints ("hsr: error: ..."), and the module stays usable.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <chrono>
#include <memory>
#include <new>
#include <set>
#include <sstream>
#include <utility>
#include <string>
#include <vector>

#include "algorithms/culling/culling.hpp"
#include "algorithms/registry.hpp"
#include "identity/identity.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/why.hpp"
#include "renderer/reference/metrics.hpp"
#include "renderer/reference/reference.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/steps/steps.hpp"
#include "renderer/util/error.hpp"
#include "renderer/util/markup.hpp"

namespace hsr::web {
namespace {

std::string knobsJson(const std::vector<KnobSpec>& knobs) {
  std::string json = "[";
  for (const KnobSpec& knob : knobs) {
    json += std::string(json.size() > 1 ? "," : "") + "{\"name\":" + jsonString(knob.name) + ",\"help\":" + jsonString(knob.help) +
            ",\"default\":" + jsonString(knob.defaultValue) + ",\"file\":" + (knob.file ? "true" : "false") + ",\"choices\":[";
    for (std::size_t c = 0; c < knob.choices.size(); ++c) json += (c ? "," : "") + jsonString(knob.choices[c]);
    json += "],\"choiceHelp\":[";
    for (std::size_t c = 0; c < knob.choiceHelp.size(); ++c) json += (c ? "," : "") + jsonString(knob.choiceHelp[c]);
    json += "],\"variants\":[";
    for (std::size_t v = 0; v < knob.variants.size(); ++v) json += (v ? "," : "") + jsonString(knob.variants[v]);
    json += "]";
    if (knob.range)
      json += ",\"range\":{\"minimum\":" + jsonNumber(knob.range->minimum) + ",\"maximum\":" + jsonNumber(knob.range->maximum) +
              ",\"integer\":" + (knob.range->integer ? "true" : "false") + ",\"percent\":" + (knob.range->percent ? "true" : "false") + "}";
    json += "}";
  }
  return json + "]";
}

std::string registry() {
  std::string json = "{\"algorithms\":[";
  bool first = true;
  for (const AlgorithmEntry& algorithm : algorithms()) {
    json += std::string(first ? "" : ",") + "{\"name\":" + jsonString(algorithm.name) + ",\"kind\":" + jsonString(algorithmKindName(algorithm.kind)) +
            ",\"summary\":" + jsonString(algorithm.summary) + ",\"takesCulling\":" + (algorithm.takesTriangleSubsets ? "true" : "false") +
            ",\"knobs\":" + knobsJson(algorithm.knobs) + "}";
    first = false;
  }
  json += "],\"stages\":[";
  first = true;
  for (const culling::StageEntry& stage : culling::stages()) {
    json += std::string(first ? "" : ",") + "{\"name\":" + jsonString(stage.name) + ",\"summary\":" + jsonString(stage.summary) +
            ",\"needsCells\":" + (stage.needsCells ? "true" : "false") + ",\"knobs\":" + knobsJson(stage.knobs) + "}";
    first = false;
  }
  return json + "]}";
}

// What the last render left for the page: its images (views of these stay valid until
// the next render), and what comparing it with the exact reference needs.
struct Shown {
  std::string sceneName;               // as the page named it
  std::unique_ptr<const Scene> scene;  // the prepared scene points into it
  std::unique_ptr<PreparedScene> prepared;
  const AlgorithmEntry* algorithm = nullptr;
  pipeline::Configuration configuration;
  Frame frame;
  LineSet drawing;
  std::vector<std::uint8_t> error;  // RGBA: the reference dimmed, wrong pixels red, ambiguous blue
  PixelBuffer<std::uint32_t> referenceIds;  // the exact reference's visible triangle per pixel, as frame.ids
  std::vector<Step> steps;                  // its steps, from recordSteps() until stepsPage() is made
  std::size_t stepsEvery = 0;               // their stride, which why() at a step records with again
};
Shown& shown() {
  static Shown last;
  return last;
}

std::string messageJson(const std::string& what) { return "{\"message\":" + jsonString("hsr: error: " + what) + "}"; }
// The command line's out-of-memory messages (cli/main.cpp, pipeline::outOfMemory), with
// the browser's limit.
const char* const kPageMemory = " (a browser gives a page at most 2 GiB)";
std::string outOfMemoryJson() { return messageJson(std::string(pipeline::kOutOfMemory) + kPageMemory); }

// request: "scene", "algorithm", "knobs" (NAME=VALUE;...), "cull" (as --cull), "size"
// (WxH or empty). The render alone, so that the page shows it at once; compare() then
// measures it against the exact reference.
std::string render(const emscripten::val& request) {
  const auto text = [&](const char* key) { return request[key].isUndefined() ? std::string() : request[key].as<std::string>(); };
  Shown& last = shown();
  try {
    const AlgorithmEntry& algorithm = findAlgorithm(text("algorithm"));
    KnobSettings settings;
    std::istringstream knobs(text("knobs"));
    for (std::string setting; std::getline(knobs, setting, ';');)
      if (!setting.empty()) settings.push_back(parseKnobSetting(setting, "--knob"));
    pipeline::Configuration configuration = pipeline::configurationOf(algorithm, settings);
    configuration.culling = pipeline::cullingOf(text("cull"), algorithm);
    auto scene = std::make_unique<const Scene>(loadScene(text("scene")));
    auto prepared = std::make_unique<PreparedScene>(*scene);
    if (const std::string size = text("size"); !size.empty()) {
      const auto [width, height] = parseSize(size, "--size");
      prepared->setSize(width, height);
    }
    pipeline::checkRenders(configuration, text("scene"), *prepared);

    // Bad input stops above, and the last render stays, still shown and asked about; it
    // is let go here, before this one takes its memory.
    last = Shown();
    Stats stats;
    const auto start = std::chrono::steady_clock::now();
    pipeline::Rendered rendered;
    try {
      rendered = pipeline::render(*prepared, configuration, 1, stats);
    } catch (const std::bad_alloc&) {
      return messageJson(pipeline::outOfMemory(prepared->width(), prepared->height(), algorithm.name) + kPageMemory);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double visibility = 0, effects = 0;
    std::string passes = "[";
    for (const pipeline::PassTime& pass : pipeline::passTimes(stats)) {
      (pass.visibility ? visibility : effects) += pass.seconds;
      passes += std::string(passes.size() > 1 ? "," : "") + "{\"pass\":" + jsonString(pass.pass) + ",\"ms\":" + jsonNumber(pass.seconds * 1e3) + "}";
    }
    passes += "]";
    std::string json = "{\"width\":" + std::to_string(rendered.frame.width) + ",\"height\":" + std::to_string(rendered.frame.height) +
                       ",\"kind\":" + jsonString(algorithmKindName(algorithm.kind)) + ",\"ms\":" + jsonNumber(seconds * 1e3) +
                       ",\"visibilityMs\":" + jsonNumber(visibility * 1e3) + ",\"effectsMs\":" + jsonNumber(effects * 1e3) + ",\"passes\":" + passes +
                       ",\"partial\":" + jsonString(algorithm.kind == AlgorithmKind::line ? rendered.drawing.partial : rendered.frame.partial);
    json += ",\"counters\":{";
    bool first = true;
    for (const std::string& name : stats.counterNames()) {
      json += std::string(first ? "" : ",") + jsonString(name) + ":" + std::to_string(stats.counter(name));
      first = false;
    }
    json += "}";

    last.sceneName = text("scene");
    last.scene = std::move(scene);
    last.prepared = std::move(prepared);
    last.algorithm = &algorithm;
    last.configuration = std::move(configuration);
    last.frame = std::move(rendered.frame);
    last.drawing = std::move(rendered.drawing);
    return json + "}";
  } catch (const InputError& error) {
    return messageJson(error.what());
  } catch (const std::bad_alloc&) {
    return outOfMemoryJson();
  }
}

// The last render against the exact reference: the metrics hsr compare prints (a line
// algorithm's against the exact line reference) and the error heat map (errorPixels).
std::string compare() {
  Shown& last = shown();
  if (!last.algorithm) return messageJson("nothing rendered to compare");
  try {
    Stats stats;
    if (last.algorithm->kind == AlgorithmKind::line) {
      const LineJudgement judged = last.algorithm->judgeLines(*last.prepared, last.configuration.knobs, last.drawing, 1, stats);
      last.error = judged.errorMap;
      return "{\"lineError\":{\"error\":" + jsonNumber(judged.error.error) + ",\"visibleLength\":" + jsonNumber(judged.error.visibleLength) +
             ",\"wronglyDrawn\":" + jsonNumber(judged.error.wronglyDrawn) + ",\"wronglyHidden\":" + jsonNumber(judged.error.wronglyHidden) + "}}";
    }
    if (last.algorithm->kind == AlgorithmKind::reference) return "{}";  // the reference itself: nothing to compare
    ReferenceImage truth;
    try {
      truth = traceReference(*last.prepared, 1, stats);
    } catch (const std::bad_alloc&) {
      return messageJson(pipeline::outOfMemory(last.prepared->width(), last.prepared->height(), "the exact reference") + kPageMemory);
    }
    const SurfaceError error = surfaceError(last.frame, truth);
    last.error = errorHeatMap(last.frame, truth);
    last.referenceIds = std::move(truth.frame.ids);
    return "{\"error\":{\"pixelError\":" + jsonNumber(error.pixelError) + ",\"wrongPixels\":" + std::to_string(error.wrongPixels) +
           ",\"comparedPixels\":" + std::to_string(error.comparedPixels) + ",\"ambiguousPixels\":" + std::to_string(error.ambiguousPixels) +
           ",\"depthErrorMean\":" + jsonNumber(error.depthErrorMean) + ",\"depthErrorMax\":" + jsonNumber(error.depthErrorMax) +
           ",\"exactFallbacks\":" + std::to_string(truth.exactFallbacks) + "}}";
  } catch (const InputError& error) {
    return messageJson(error.what());
  } catch (const std::bad_alloc&) {
    return outOfMemoryJson();
  }
}

// The last render's pixel (x, y) asked about as hsr why asks (pipeline/why.hpp): {"text":
// the lines hsr why prints, "answer": its --json}; for a line drawing, the edge passing
// nearest the pixel's center, as hsr why --edge X,Y asks ({"text", "edge": its --json});
// or the command line's line of error.
std::string why(int x, int y, int step) {
  Shown& last = shown();
  if (!last.algorithm) return messageJson("nothing rendered to ask about");
  try {
    if (last.algorithm->kind == AlgorithmKind::line) {
      pipeline::checkAnswersWhyAlongEdges(*last.algorithm);
      const std::string edge = std::to_string(x) + "," + std::to_string(y);
      Stats stats;
      const pipeline::EdgeAnswer answer = pipeline::explainEdge(*last.prepared, last.configuration, edge, 1, stats);
      return "{\"text\":" + jsonString(pipeline::edgeText(*last.prepared, last.sceneName, last.configuration, answer)) +
             ",\"edge\":" + pipeline::edgeJson(*last.prepared, last.sceneName, last.configuration, answer) + "}";
    }
    pipeline::checkAnswersWhy(*last.algorithm);
    const PixelWitness::Pixel pixel = pipeline::pixelOf(std::to_string(x) + "," + std::to_string(y), last.prepared->width(), last.prepared->height());
    Stats stats;
    pipeline::StepAsked asked{std::size_t(step), last.stepsEvery};
    pipeline::StepAsked* atStep = step > 0 ? &asked : nullptr;
    const std::vector<pipeline::PixelAnswer> answers = pipeline::explainPixels(*last.prepared, last.configuration, {pixel}, 1, stats, atStep);
    return "{\"text\":" + jsonString(pipeline::whyText(*last.prepared, last.sceneName, last.configuration, answers, atStep)) +
           ",\"answer\":" + pipeline::whyJson(*last.prepared, last.sceneName, last.configuration, answers, atStep) + "}";
  } catch (const InputError& error) {
    return messageJson(error.what());
  } catch (const std::bad_alloc&) {
    return outOfMemoryJson();
  }
}

// Where the page writes the suite's files that recorded the steps (web/dist/src/), for
// the steps page to show their lines.
const char* const kSourceRoot = "/hsr/src";

// The last render's steps, recorded as hsr render --steps records them (one thread, every
// `every`th repeated step, empty or 0: about 40 of each run, and the finished image last), kept
// for stepPicture() and stepsPage(): {"steps": [{"width", "height", "caption"}...],
// "files": the suite's files the steps were recorded in, for the page to write under
// kSourceRoot}, or the command line's line of error.
// The most memory the steps' pictures may take in the page: a run of every triangle of a
// large render is refused as soon as it would pass this, not when the page runs out.
constexpr std::size_t kMostStepBytes = std::size_t(512) << 20;

std::string recordSteps(const std::string& everyAsTyped) {
  Shown& last = shown();
  if (!last.algorithm) return messageJson("nothing rendered to record the steps of");
  last.steps.clear();
  if (const std::string error = stepCountError(everyAsTyped); !everyAsTyped.empty() && !error.empty()) return messageJson("--every: " + error);
  const std::size_t every = everyAsTyped.empty() ? 0 : std::stoul(everyAsTyped);
  try {
    std::vector<Step> kept;
    std::size_t bytes = 0;
    StepRecorder recorder(every, [&](Step step) {
      bytes += step.picture.pixels.size();
      if (bytes > kMostStepBytes)
        throw InputError((every > 0 ? "--every " + std::to_string(every) + ": the steps" : std::string("the steps, about 40 of each run,")) + " would take more than " +
                         std::to_string(kMostStepBytes >> 20) + " MiB of the page's memory (" + std::to_string(kept.size()) + " recorded so far, " +
                         std::to_string(step.picture.width) + "x" + std::to_string(step.picture.height) +
                         " pixels each); expected a larger --every, or a smaller --size");
      kept.push_back(std::move(step));
    });
    Stats stats;
    const pipeline::Rendered rendered = pipeline::render(*last.prepared, last.configuration, 1, stats, nullptr, &recorder);
    pipeline::recordFinishedStep(recorder, rendered.frame, last.algorithm->kind == AlgorithmKind::line);
    std::string json = "{\"steps\":[";
    std::set<std::string> files;
    for (const Step& step : kept) {
      json += std::string(json.back() == '[' ? "" : ",") + "{\"width\":" + std::to_string(step.picture.width) +
              ",\"height\":" + std::to_string(step.picture.height) + ",\"caption\":" + jsonString(step.caption) + "}";
      files.insert(recordedIn(step.where));
    }
    json += "],\"files\":[";
    for (const std::string& file : files) json += std::string(json.back() == '[' ? "" : ",") + jsonString(file);
    last.steps = std::move(kept);
    last.stepsEvery = every;
    return json + "]}";
  } catch (const InputError& error) {
    return messageJson(error.what());
  } catch (const std::bad_alloc&) {
    return outOfMemoryJson();
  }
}

emscripten::val stepPicture(int index) {
  const Image& picture = shown().steps.at(std::size_t(index)).picture;
  return emscripten::val(emscripten::typed_memory_view(picture.pixels.size(), picture.pixels.data()));
}

// The steps page for the steps recorded, each picture at its address in `pictures`, a
// click on a pixel answered by the page around it (PixelQuestion::host) for an algorithm
// that answers why at a pixel. The steps are let go: the page holds their pictures now.
std::string stepsPage(const std::string& title, const emscripten::val& pictures) {
  Shown& last = shown();
  if (last.steps.empty()) return messageJson("no steps recorded to show");
  std::vector<std::pair<std::string, SourceLocation>> recorded;
  std::vector<std::string> addresses;
  for (const Step& step : last.steps) {
    addresses.push_back(pictures[addresses.size()].as<std::string>());
    recorded.emplace_back(step.caption, step.where);
  }
  last.steps.clear();
  const PixelQuestion question{last.algorithm->answersWhy ? "hsr why" : "", last.prepared->width(), last.prepared->height(), true};
  return hsr::stepsPage(title, pageSteps(recorded, addresses, kSourceRoot), question);
}

// Whether a render is kept to be compared, asked about and stepped through: after bad
// input the one before stays; a render that ran out of memory let it go.
bool hasRender() { return shown().algorithm != nullptr; }

// The last render's images, as views of the module's memory (valid until the next render).
emscripten::val colorPixels() { return emscripten::val(emscripten::typed_memory_view(shown().frame.color.size(), shown().frame.color.data())); }
emscripten::val idPixels() { return emscripten::val(emscripten::typed_memory_view(shown().frame.ids.size(), shown().frame.ids.data())); }
emscripten::val depthPixels() {
  const PixelBuffer<float>& distance = shown().frame.distances();
  return emscripten::val(emscripten::typed_memory_view(distance.size(), distance.data()));
}
emscripten::val errorPixels() { return emscripten::val(emscripten::typed_memory_view(shown().error.size(), shown().error.data())); }
emscripten::val referenceIdPixels() {
  return emscripten::val(emscripten::typed_memory_view(shown().referenceIds.size(), shown().referenceIds.data()));
}

// The identity lines of every shipped scene under /hsr/scenes (which the page fills).
std::string identity(int width, int randomScenes, const std::string& only) {
  std::string lines;
  identity::Options options;
  options.width = width;
  options.randomScenes = randomScenes;
  options.only = only;
  identity::renderLines("/hsr/scenes", options, [&](const std::string& line) { lines += line + "\n"; });
  return lines;
}

}  // namespace
}  // namespace hsr::web

EMSCRIPTEN_BINDINGS(hsr) {
  emscripten::function("registry", &hsr::web::registry);
  emscripten::function("render", &hsr::web::render);
  emscripten::function("hasRender", &hsr::web::hasRender);
  emscripten::function("compare", &hsr::web::compare);
  emscripten::function("why", &hsr::web::why);
  emscripten::function("colorPixels", &hsr::web::colorPixels);
  emscripten::function("idPixels", &hsr::web::idPixels);
  emscripten::function("depthPixels", &hsr::web::depthPixels);
  emscripten::function("errorPixels", &hsr::web::errorPixels);
  emscripten::function("referenceIdPixels", &hsr::web::referenceIdPixels);
  emscripten::function("recordSteps", &hsr::web::recordSteps);
  emscripten::function("stepPicture", &hsr::web::stepPicture);
  emscripten::function("stepsPage", &hsr::web::stepsPage);
  emscripten::function("identity", &hsr::web::identity);
}
