#include "renderer/steps/steps_page.hpp"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <tuple>

#include "renderer/util/markup.hpp"

namespace hsr {

namespace {

bool startsAtColumnZero(const std::string& line) { return !line.empty() && line[0] != ' ' && line[0] != '\t'; }

// A line without its comment: up to the first // outside a string or character literal.
std::string withoutComment(const std::string& line) {
  char quote = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (quote && line[i] == '\\') ++i;
    else if (quote && line[i] == quote) quote = 0;
    else if (!quote && (line[i] == '"' || line[i] == '\'')) quote = line[i];
    else if (!quote && line.compare(i, 2, "//") == 0) return line.substr(0, i);
  }
  return line;
}

// Whether a statement cannot go on past this line: it holds no code, or its code ends a
// statement, opens or closes a block, or is a label.
bool endsStatement(const std::string& line) {
  const std::string code = withoutComment(line);
  const std::size_t last = code.find_last_not_of(" \t");
  return last == std::string::npos || code[last] == ';' || code[last] == '{' || code[last] == '}' || code[last] == ':';
}

std::string excerptJson(const SourceExcerpt& source) {
  std::string json = "{\"file\":" + jsonString(source.file) + ",\"function\":" + jsonString(source.function) +
                     ",\"line\":" + std::to_string(source.line) + ",\"firstLine\":" + std::to_string(source.firstLine) +
                     ",\"markedTo\":" + std::to_string(source.markedTo) + ",\"lines\":[";
  for (std::size_t k = 0; k < source.lines.size(); ++k) {
    if (k > 0) json += ',';
    json += jsonString(source.lines[k]);
  }
  return json + "]}";
}

// The page's look and behaviour; the steps come in as JSON (#steps).
constexpr const char* kStyle = R"(
body { font: 15px/1.45 system-ui, sans-serif; margin: 0 1.2em 2em; color: #1d1d1f; }
h1 { font-size: 1.15em; margin: .8em 0 .2em; font-weight: 600; }
header p { margin: 0 0 .6em; color: #555; }
nav { position: sticky; top: 0; background: #fff; padding: .5em 0; display: flex; gap: .4em; align-items: center;
      flex-wrap: wrap; border-bottom: 1px solid #ddd; z-index: 1; }
button { font: inherit; padding: .25em .7em; border: 1px solid #999; border-radius: 4px; background: #f6f6f6; cursor: pointer; }
button:disabled { color: #aaa; border-color: #ddd; cursor: default; }
#position { min-width: 8.5em; text-align: center; font-variant-numeric: tabular-nums; font-weight: 600; }
#slider { flex: 1; min-width: 10em; }
#caption { font-size: 1.05em; margin: .7em 0; min-height: 2.9em; }
main { display: flex; gap: 1.2em; align-items: flex-start; flex-wrap: wrap; }
figure { margin: 0; flex: 1 1 520px; min-width: 0; overflow-x: auto; position: relative; }
#picture { width: 100%; border: 1px solid #ccc; image-rendering: pixelated; }
#picture.actual { width: auto; max-width: none !important; }
#picture.asks { cursor: crosshair; }
#ring { position: absolute; width: 12px; height: 12px; margin: -8px 0 0 -8px; border: 2px solid #e0e; border-radius: 50%;
        box-shadow: 0 0 0 1px #fff, inset 0 0 0 1px #fff; pointer-events: none; }
#pixel { margin: .6em 0; padding: .3em .8em; border-left: 5px solid #e0e; background: #fdf6fd; }
#pixel h2 { font-size: .95em; margin: .2em 0; }
#pixel p { margin: .2em 0; }
[hidden] { display: none !important; }
#whyAnswer { white-space: pre-wrap; overflow-wrap: anywhere; font-size: 12.5px; background: #fff; padding: .3em .5em; max-height: 28em; overflow-y: auto; }
#whyCommand { display: block; white-space: pre-wrap; overflow-wrap: anywhere; font-size: 12.5px; background: #fff; border: 1px solid #ddd;
              padding: .3em .5em; margin: .3em 0; }
#source { flex: 1 1 480px; min-width: 0; }
#source h2 { font-size: .95em; font-weight: 600; margin: 0 0 .3em; }
#source .function { color: #555; font-size: .85em; margin: 0 0 .4em; word-break: break-all; }
pre { margin: 0; background: #fafafa; border: 1px solid #ddd; padding: .4em 0; overflow-x: auto; font-size: 12.5px; line-height: 1.4; }
pre span { display: block; padding: 0 .6em 0 0; white-space: pre; }
pre span::before { content: attr(data-line); display: inline-block; width: 3.2em; margin-right: .8em; text-align: right; color: #999; }
pre span.marked { background: #ffe9a8; }
.hint { color: #666; font-size: .85em; }
)";

constexpr const char* kScript = R"(
const steps = JSON.parse(document.getElementById("steps").textContent);
const sources = JSON.parse(document.getElementById("sources").textContent);
const question = JSON.parse(document.getElementById("question").textContent);
const $ = (id) => document.getElementById(id);
const slider = $("slider");
slider.max = steps.length;
let current = 0, playing = null;

function showSource(source) {
  $("sourceTitle").textContent = `recorded at ${source.file}:${source.line}`;
  $("function").textContent = source.function ? `in ${source.function}` : "";
  const code = $("code");
  code.replaceChildren();
  if (source.lines.length === 0) {
    code.textContent = `(${source.file} is not beside this program: the lines cannot be shown)`;
    return;
  }
  source.lines.forEach((text, k) => {
    const line = document.createElement("span");
    const number = source.firstLine + k;
    line.dataset.line = number;
    line.textContent = text;
    if (number >= source.line && number <= source.markedTo) line.className = "marked";
    code.append(line);
  });
}

function show(index) {
  current = Math.max(0, Math.min(steps.length - 1, index));
  const step = steps[current];
  $("picture").src = step.picture;
  $("picture").alt = step.caption;
  $("caption").textContent = step.caption;
  $("position").textContent = `step ${current + 1} of ${steps.length}`;
  slider.value = current + 1;
  $("first").disabled = $("previous").disabled = current === 0;
  $("next").disabled = $("last").disabled = current === steps.length - 1;
  showSource(sources[step.source]);
  if (!question.host) history.replaceState(null, "", `#step=${current + 1}`);  // a page inside another has no address of its own
  showAsked();
  // The next picture is fetched now, so that "next" shows it at once.
  if (current + 1 < steps.length) new Image().src = steps[current + 1].picture;
}

function stop() {
  clearInterval(playing);
  playing = null;
  $("play").textContent = "play";
}

function play() {
  if (playing) return stop();
  if (current === steps.length - 1) show(0);
  $("play").textContent = "pause";
  playing = setInterval(() => (current === steps.length - 1 ? stop() : show(current + 1)), 600);
}

$("first").onclick = () => { stop(); show(0); };
$("previous").onclick = () => { stop(); show(current - 1); };
$("next").onclick = () => { stop(); show(current + 1); };
$("last").onclick = () => { stop(); show(steps.length - 1); };
$("play").onclick = play;
slider.oninput = () => { stop(); show(Number(slider.value) - 1); };
// A small picture is shown up to twice its size, each pixel a square of pixels; a double
// click shows it at its actual size.
$("picture").onload = () => { $("picture").style.maxWidth = `${2 * $("picture").naturalWidth}px`; placeRing(); };
$("picture").ondblclick = () => { $("picture").classList.toggle("actual"); placeRing(); };

// A click on a pixel: the command that shows its history up to the step shown. A picture
// holds the render's pixels from its top left, or side by side panels of the render's
// size (question.panelGap pixels apart); a click elsewhere asks nothing.
let asked = null;  // [x, y, the picture's x, its y]
// How large the picture is shown, inside its border: CSS pixels per pixel of it.
function scaleOf(picture) {
  const box = picture.getBoundingClientRect();
  return [(box.width - 2 * picture.clientLeft) / picture.naturalWidth, (box.height - 2 * picture.clientTop) / picture.naturalHeight];
}
// Whether a picture shows the render: panels of its size side by side, from the top (a
// legend may follow below). Another picture (a depth map, a diagram) asks nothing.
function showsRender(picture) {
  const panels = (picture.naturalWidth + question.panelGap) / (question.width + question.panelGap);
  return Number.isInteger(panels) && picture.naturalHeight >= question.height;
}
function pixelUnder(event) {
  const picture = $("picture"), box = picture.getBoundingClientRect(), [sx, sy] = scaleOf(picture);
  const px = Math.floor((event.clientX - box.left - picture.clientLeft) / sx);
  const py = Math.floor((event.clientY - box.top - picture.clientTop) / sy);
  const x = px % (question.width + question.panelGap);
  if (!showsRender(picture) || px < 0 || py < 0 || x >= question.width || py >= question.height) return null;
  return [x, py, px, py];
}
function placeRing() {
  const picture = $("picture"), ring = $("ring");
  picture.classList.toggle("asks", Boolean(question.command) && picture.naturalWidth > 0 && showsRender(picture));
  ring.hidden = !asked || !picture.naturalWidth || !showsRender(picture);
  if (ring.hidden) return;
  const [sx, sy] = scaleOf(picture);
  ring.style.left = `${picture.offsetLeft + picture.clientLeft + (asked[2] + 0.5) * sx}px`;
  ring.style.top = `${picture.offsetTop + picture.clientTop + (asked[3] + 0.5) * sy}px`;
}
// In the browser edition the page around this one answers: the question goes to it a
// moment after the last move (a slider dragged asks once), and its answer is shown if it
// is still the one asked.
let askLater = null;
function showAsked() {
  $("pixel").hidden = !asked;
  placeRing();
  if (!asked) return;
  $("pixelTitle").textContent = `Pixel (${asked[0]}, ${asked[1]}) up to step ${current + 1}`;
  if (!question.host) {
    $("whyCommand").textContent = `${question.command} --pixel ${asked[0]},${asked[1]} --step ${current + 1}`;
    return;
  }
  $("whyAnswer").textContent = "asking…";
  clearTimeout(askLater);
  const [x, y, step] = [asked[0], asked[1], current + 1];
  askLater = setTimeout(() => parent.postMessage({ kind: "hsr-why", x, y, step }, "*"), 120);
}
window.addEventListener("message", (event) => {
  const answer = event.data;
  if (!question.host || event.source !== parent || !answer || answer.kind !== "hsr-why-answer") return;
  if (asked && answer.x === asked[0] && answer.y === asked[1] && answer.step === current + 1) $("whyAnswer").textContent = answer.text;
});
if (question.command) {
  $("picture").onclick = (event) => {
    const pixel = pixelUnder(event);
    if (!pixel) return;
    asked = pixel;
    showAsked();
  };
  $("whyCommand").hidden = $("copy").hidden = question.host;
  $("whyAnswer").hidden = !question.host;
  $("copy").onclick = async () => {
    try {
      await navigator.clipboard.writeText($("whyCommand").textContent);
      $("copy").textContent = "copied";
    } catch {
      $("copy").textContent = "select the command to copy it";  // a page opened from a file may not reach the clipboard
    }
    setTimeout(() => { $("copy").textContent = "copy"; }, 1500);
  };
}
window.addEventListener("resize", placeRing);
document.addEventListener("keydown", (event) => {
  // The slider takes the arrow keys, and a focused button space and enter, themselves.
  if (event.target === slider || (event.target.tagName === "BUTTON" && (event.key === " " || event.key === "Enter")) || event.altKey ||
      event.ctrlKey || event.metaKey)
    return;
  const moves = { ArrowLeft: current - 1, ArrowRight: current + 1, Home: 0, End: steps.length - 1 };
  if (event.key in moves) { stop(); show(moves[event.key]); event.preventDefault(); }
  else if (event.key === " ") { play(); event.preventDefault(); }
});
const fromAddress = /^#step=(\d+)$/.exec(location.hash);
if (steps.length > 0) show(fromAddress ? Number(fromAddress[1]) - 1 : 0);
else {
  $("caption").textContent = "No step was recorded.";
  for (const id of ["first", "previous", "next", "last", "play", "slider"]) $(id).disabled = true;
}
// A link to another step followed in the open page (or #step=N typed into its address).
window.addEventListener("hashchange", () => {
  const asked = /^#step=(\d+)$/.exec(location.hash);
  if (asked && steps.length > 0 && Number(asked[1]) - 1 !== current) { stop(); show(Number(asked[1]) - 1); }
});
)";

}  // namespace

namespace {

// The file a call was recorded in: relative to the suite's folder where it is in it
// (`inSuite`), else as the compiler named it, made canonical.
struct RecordedFile {
  std::filesystem::path path;
  bool inSuite = false;
};
RecordedFile recordedFile(const SourceLocation& where) {
  // A header may have been included through a build folder's view of the sources
  // (cmake/layers.cmake), whose links lead back to the suite's own file.
  std::error_code error;
  std::filesystem::path path = std::filesystem::weakly_canonical(where.file_name(), error);
  if (error) path = where.file_name();
  std::filesystem::path relative = path.lexically_relative(std::filesystem::weakly_canonical(HSR_SOURCE_DIR, error));
  // Where the links are not (the browser edition's file system), a view's path is taken
  // apart by hand: BUILD/include-views/TARGET/PATH is the suite's PATH.
  for (auto part = relative.begin(); part != relative.end(); ++part)
    if (*part == "include-views" && std::next(part) != relative.end()) {
      std::filesystem::path inView;
      for (auto rest = std::next(part, 2); rest != relative.end(); ++rest) inView /= *rest;
      relative = inView;
      break;
    }
  const bool inSuite = !relative.empty() && *relative.begin() != "..";
  return {inSuite ? relative : path, inSuite};
}

}  // namespace

std::string recordedIn(const SourceLocation& where) { return recordedFile(where).path.generic_string(); }

SourceExcerpt sourceExcerpt(const SourceLocation& where, const std::filesystem::path& sourceRoot) {
  SourceExcerpt excerpt;
  excerpt.function = where.function_name();
  excerpt.line = excerpt.firstLine = excerpt.markedTo = int(where.line());  // until the file is read
  const RecordedFile file = recordedFile(where);
  excerpt.file = file.path.generic_string();

  std::ifstream in(file.inSuite ? (sourceRoot.empty() ? std::filesystem::path(HSR_SOURCE_DIR) : sourceRoot) / file.path : file.path);
  std::vector<std::string> lines;
  for (std::string text; std::getline(in, text);) {
    if (!text.empty() && text.back() == '\r') text.pop_back();  // a file saved with Windows' line ends
    lines.push_back(text);
  }
  if (excerpt.line < 1 || excerpt.line > int(lines.size())) return excerpt;
  const auto at = [&](int number) -> const std::string& { return lines[std::size_t(number - 1)]; };
  // The compiler may name any line of a call that spans several: the recording statement
  // starts after the line before it that ends one.
  int call = excerpt.line;
  while (call > 1 && !endsStatement(at(call - 1))) --call;
  excerpt.line = call;
  // Up: to the line that starts the enclosing function (it starts at column 0) or the
  // line after the function before it closes.
  int first = call;
  while (first > 1 && call - first < kLinesBefore) {
    const std::string& above = at(first - 1);
    if (startsAtColumnZero(above) && (above[0] == '}' || above.rfind("//", 0) == 0 || above.rfind("namespace", 0) == 0)) break;
    --first;
    if (startsAtColumnZero(above)) break;
  }
  // Down: to the line that ends the recording statement, and two lines more.
  int last = call;
  while (last < int(lines.size()) && !endsStatement(at(last))) ++last;
  excerpt.markedTo = last;
  last = std::min(int(lines.size()), last + 2);
  excerpt.firstLine = first;
  excerpt.lines.assign(lines.begin() + (first - 1), lines.begin() + last);
  return excerpt;
}

std::vector<PageStep> pageSteps(const std::vector<std::pair<std::string, SourceLocation>>& recorded, const std::vector<std::string>& pictures,
                                const std::filesystem::path& sourceRoot) {
  std::vector<PageStep> steps;
  std::map<std::pair<std::string, std::uint_least32_t>, SourceExcerpt> excerpts;
  for (std::size_t s = 0; s < recorded.size(); ++s) {
    const auto& [caption, where] = recorded[s];
    auto [place, isNew] = excerpts.try_emplace({where.file_name(), where.line()});
    if (isNew) place->second = sourceExcerpt(where, sourceRoot);
    steps.push_back({pictures[s], caption, place->second});
  }
  return steps;
}

std::string stepsPage(const std::string& title, const std::vector<PageStep>& steps, const PixelQuestion& question) {
  // One excerpt per recording place: a loop's steps share theirs.
  std::map<std::tuple<std::string, int>, std::size_t> places;
  std::string sources = "[", list = "[";
  for (const PageStep& step : steps) {
    const auto [place, isNew] = places.try_emplace({step.source.file, step.source.line}, places.size());
    if (isNew && place->second > 0) sources += ',';
    if (isNew) sources += excerptJson(step.source);
    if (list.size() > 1) list += ',';
    list += "{\"picture\":" + jsonString(step.picture) + ",\"caption\":" + jsonString(step.caption) +
            ",\"source\":" + std::to_string(place->second) + "}";
  }
  sources += "]", list += "]";
  return "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
         "<title>Steps: " + escapedMarkup(title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n"
         "<header>\n<h1>" + escapedMarkup(title) + "</h1>\n"
         "<p>The algorithm's own state at its textbook steps, and the lines of its code that recorded each. " +
         (question.host ? std::string() : "Also here: <a href=\"steps.gif\">the animation</a>, <a href=\"captions.txt\">the captions</a>. ") +
         "<span class=\"hint\">Keys: &larr; &rarr; Home End, space to play; double-click the picture for its actual size and back" +
         (question.command.empty() ? "."
          : question.host         ? "; click a pixel for its history up to the step."
                                  : "; click a pixel for the command that shows its history up to the step.") +
         "</span></p>\n"
         "</header>\n"
         "<nav aria-label=\"steps\">\n"
         "<button id=\"first\" title=\"the first step (Home)\">first</button>\n"
         "<button id=\"previous\" title=\"the step before (&larr;)\">previous</button>\n"
         "<span id=\"position\" aria-live=\"polite\"></span>\n"
         "<button id=\"next\" title=\"the step after (&rarr;)\">next</button>\n"
         "<button id=\"last\" title=\"the last step (End)\">last</button>\n"
         "<button id=\"play\" title=\"play from here (space)\">play</button>\n"
         "<input id=\"slider\" type=\"range\" min=\"1\" value=\"1\" aria-label=\"step\">\n"
         "</nav>\n"
         "<p id=\"caption\"></p>\n"
         "<main>\n<figure><img id=\"picture\" alt=\"\"><div id=\"ring\" hidden></div>\n"
         "<section id=\"pixel\" hidden aria-live=\"polite\">\n<h2 id=\"pixelTitle\"></h2>\n"
         "<p>Every event the algorithm's own loops met at this pixel up to this step, and the exact reference's answer "
         "beside the algorithm's" + (question.host ? ":" : ", from the suite's folder:") + "</p>\n"
         "<code id=\"whyCommand\"></code>\n<button id=\"copy\" title=\"copy the command\">copy</button>\n"
         "<pre id=\"whyAnswer\" hidden></pre>\n</section></figure>\n"
         "<section id=\"source\" aria-label=\"the code that recorded the step\">\n<h2 id=\"sourceTitle\"></h2>\n"
         "<p class=\"function\" id=\"function\"></p>\n<pre id=\"code\"></pre>\n</section>\n</main>\n"
         "<script type=\"application/json\" id=\"steps\">" + jsonInScript(list) + "</script>\n"
         "<script type=\"application/json\" id=\"sources\">" + jsonInScript(sources) + "</script>\n"
         "<script type=\"application/json\" id=\"question\">" +
         jsonInScript("{\"command\":" + jsonString(question.command) + ",\"width\":" + std::to_string(question.width) +
                      ",\"height\":" + std::to_string(question.height) + ",\"panelGap\":" + std::to_string(kPanelGap) +
                      ",\"host\":" + (question.host ? "true" : "false") + "}") +
         "</script>\n"
         "<script>" + kScript + "</script>\n</body>\n</html>\n";
}

}  // namespace hsr
