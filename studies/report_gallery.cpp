#include "studies/report_gallery.hpp"

#include "renderer/util/markup.hpp"

namespace hsr::studies {
namespace {

constexpr const char* kGalleryStyle = R"css(
.scene { margin: 1.5em 0 2.5em; }
.scene h2 { margin-bottom: 0.2em; }
.scene > p { margin: 0.2em 0 0.6em; color: #555; }
svg.scatter { max-width: 100%; height: auto; background: #fff; border: 1px solid #ddd; }
svg.scatter text { font: 11px "DejaVu Sans", sans-serif; fill: #333; }
svg.scatter .axis { stroke: #888; } svg.scatter .grid { stroke: #eee; }
svg.scatter .spread { stroke: #3a7; stroke-width: 2; } svg.scatter circle { fill: #264; }
svg.scatter g.point:hover circle { fill: #c30; } svg.scatter g.point:hover .spread { stroke: #c30; }
.cards { display: grid; grid-template-columns: repeat(auto-fill, minmax(330px, 1fr)); gap: 12px; margin-top: 0.8em; }
.card { border: 1px solid #ddd; border-radius: 6px; padding: 6px 8px; background: #fff; }
.card.wrong { border-left: 5px solid #c30; } .card.right { border-left: 5px solid #3a7; } .card.exact { border-left: 5px solid #447; }
.card h3 { font-size: 0.95em; margin: 0.1em 0 0.2em; } .card h3 .knobs { font-weight: normal; color: #555; }
.card .figures { font-size: 0.85em; margin: 0 0 0.4em; }
.card .pair { display: grid; grid-template-columns: 1fr 1fr; gap: 4px; }
.card figure { margin: 0; } .card figcaption { font-size: 0.75em; color: #666; }
.card img { width: 100%; cursor: zoom-in; image-rendering: pixelated; border: 1px solid #ddd; }
.card .links { font-size: 0.85em; margin: 0.3em 0 0; }
#zoom { position: fixed; inset: 0; background: #1b1b1b; color: #eee; z-index: 10; display: flex; flex-direction: column; }
#zoom[hidden] { display: none; }
#zoom .bar { padding: 0.5em 1em; display: flex; gap: 0.6em; align-items: center; flex-wrap: wrap; }
#zoom .bar button { font: inherit; padding: 0.1em 0.7em; background: #333; color: #eee; border: 1px solid #777; border-radius: 4px; cursor: pointer; }
#zoom .bar button[aria-pressed=true] { background: #3a7; border-color: #3a7; }
#zoom .view { flex: 1; overflow: auto; position: relative; }
#zoom .view img { image-rendering: pixelated; cursor: crosshair; display: block; margin: 0 auto; max-width: none; border: none; }
#zoom .pixel { padding: 0.5em 1em; font-size: 0.9em; min-height: 3em; }
#zoom code { background: #333; color: #fff; user-select: all; }
#zoomRing { position: absolute; border: 2px solid #f0f; border-radius: 50%; pointer-events: none; }
)css";

constexpr const char* kGalleryScript = R"js(
(() => {  // the gallery's names stay its own
const gallery = JSON.parse(document.getElementById("galleryData").textContent);
const make = (tag, properties = {}, ...children) => { const made = Object.assign(document.createElement(tag), properties); made.append(...children); return made; };
const svgMake = (tag, attributes = {}) => { const made = document.createElementNS("http://www.w3.org/2000/svg", tag); for (const [k, v] of Object.entries(attributes)) made.setAttribute(k, v); return made; };
const ms = (value) => (value < 10 ? value.toFixed(2) : value < 100 ? value.toFixed(1) : value.toFixed(0));
const percent = (fraction) => `${(100 * fraction).toPrecision(3)}%`;
const label = (entry) => entry.knobs === "exact" ? "the exact reference" : `${entry.algorithm}${entry.knobs === "defaults" ? "" : " " + entry.knobs}`;
const coverageText = (entry) => entry.coverageError === null ? "" : ` · coverage error ${percent(entry.coverageError)}`;
const errorText = (entry) => (entry.knobs === "exact" ? `${entry.ambiguousPixels.toLocaleString("en")} ambiguous pixels (certified ties)`
  : entry.lines ? `line error ${percent(entry.error)}` : entry.wrongPixels === 0 ? "no wrong pixel"
  : `pixel error ${percent(entry.error)}: ${entry.wrongPixels.toLocaleString("en")} wrong pixels`) + coverageText(entry);

// Ticks from 0 to `top` a round step apart (1, 2 or 5 times a power of ten), five or more.
function niceTicks(top) {
  const rough = top / 4, power = 10 ** Math.floor(Math.log10(rough));
  const step = [5, 2, 1].map((m) => m * power).find((s) => s <= rough);
  return Array.from({ length: Math.floor(top / step) + 1 }, (_, k) => k * step);
}

// Error against visibility time, each configuration's fastest to slowest run as a bar.
// The time axis is logarithmic when the times span more than 20 times, as in hsr sweep's plots.
function scatter(scene) {
  const points = scene.entries.map((entry, i) => ({ entry, number: i + 1 })).filter(({ entry }) => !entry.lines);
  const width = 620, height = 250, left = 70, right = 20, top = 14, bottom = 42;
  const svg = svgMake("svg", { class: "scatter", viewBox: `0 0 ${width} ${height}`, width, height, role: "img",
                               "aria-label": `pixel error against visibility time on ${scene.scene}` });
  const times = points.flatMap(({ entry }) => entry.visibilityMs.slice(1)).filter((t) => t > 0);
  const low = Math.min(...times), high = Math.max(...times);
  const logarithmic = high / low > 20;
  const [t0, t1] = logarithmic ? [Math.log10(low / 1.3), Math.log10(high * 1.3)] : [0, high * 1.08];
  const x = (t) => left + ((logarithmic ? Math.log10(Math.max(t, low / 1.3)) : t) - t0) / (t1 - t0) * (width - left - right);
  const worst = Math.max(...points.map(({ entry }) => entry.error)) || 0.001;
  const y = (e) => height - bottom - (e / (worst * 1.1)) * (height - top - bottom);
  const ticks = logarithmic
    ? [0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000].filter((t) => Math.log10(t) >= t0 && Math.log10(t) <= t1)
    : niceTicks(high);
  for (const t of ticks) {
    svg.append(svgMake("line", { class: "grid", x1: x(t), x2: x(t), y1: top, y2: height - bottom }));
    const text = svgMake("text", { x: x(t), y: height - bottom + 14, "text-anchor": "middle" });
    text.textContent = ms(t);
    svg.append(text);
  }
  for (const e of [0, worst / 2, worst]) {
    svg.append(svgMake("line", { class: "grid", x1: left, x2: width - right, y1: y(e), y2: y(e) }));
    const text = svgMake("text", { x: left - 6, y: y(e) + 4, "text-anchor": "end" });
    text.textContent = e === 0 ? "0" : percent(e);
    svg.append(text);
  }
  svg.append(svgMake("line", { class: "axis", x1: left, x2: width - right, y1: height - bottom, y2: height - bottom }));
  svg.append(svgMake("line", { class: "axis", x1: left, x2: left, y1: top, y2: height - bottom }));
  const xLabel = svgMake("text", { x: (left + width - right) / 2, y: height - 8, "text-anchor": "middle" });
  xLabel.textContent = `visibility time, ms${logarithmic ? " (logarithmic)" : ""}: the dot the median, the bar fastest to slowest run`;
  const yLabel = svgMake("text", { x: 14, y: (top + height - bottom) / 2, transform: `rotate(-90 14 ${(top + height - bottom) / 2})`, "text-anchor": "middle" });
  yLabel.textContent = "pixel error";
  svg.append(xLabel, yLabel);
  // A point's number beside it, unless another number is already there (pointing at a
  // point names it in any case).
  const labelled = [];
  for (const { entry, number } of points) {
    const [median, fastest, slowest] = entry.visibilityMs;
    const point = svgMake("g", { class: "point" });
    const title = svgMake("title");
    title.textContent = `${number}. ${label(entry)}: ${ms(median)} ms [${ms(fastest)}-${ms(slowest)}], ${errorText(entry)}`;
    point.append(title, svgMake("line", { class: "spread", x1: x(fastest), x2: x(slowest), y1: y(entry.error), y2: y(entry.error) }),
                 svgMake("circle", { cx: x(median), cy: y(entry.error), r: 4 }));
    const [labelX, labelY] = [x(median) + 6, y(entry.error) - 5];
    if (!labelled.some(([otherX, otherY]) => Math.abs(otherX - labelX) < 16 && Math.abs(otherY - labelY) < 11)) {
      const text = svgMake("text", { x: labelX, y: labelY });
      text.textContent = number;
      point.append(text);
      labelled.push([labelX, labelY]);
    }
    point.addEventListener("click", () => document.getElementById(`card-${scene.index}-${number}`).scrollIntoView({ behavior: "smooth", block: "center" }));
    svg.append(point);
  }
  return svg;
}

// The commands a student runs next: record the steps, ask why about a pixel.
const stepsCommand = (scene, entry, number) =>
  `hsr render ${scene.scene} ${entry.options} --size ${scene.width}x${scene.height} -o ${entry.algorithm}.png --steps ${entry.algorithm}-${number}-steps`;
const whyCommand = (scene, entry, x, y) =>
  `hsr why ${scene.scene} ${entry.answersWhy ? entry.options : "--algo zbuffer"} --size ${scene.width}x${scene.height} --pixel ${x},${y}`;

// The enlarged view: one card's picture or error map at a whole number of screen pixels
// per pixel; a click on a pixel names it and gives the command that asks why.
const zoom = { scene: null, entry: null, which: "errorMap", scale: 2 };
function showZoom() {
  const { scene, entry, which, scale } = zoom;
  document.getElementById("zoomTitle").textContent = `${scene.scene}: ${label(entry)}, ${which === "picture" ? "its picture" : "its error map: " + entry.errorLegend}`;
  const image = document.getElementById("zoomImage");
  image.src = entry[which];
  image.style.width = `${scene.width * scale}px`;
  for (const button of document.querySelectorAll("#zoom [data-scale]")) button.setAttribute("aria-pressed", String(Number(button.dataset.scale) === scale));
  for (const button of document.querySelectorAll("#zoom [data-which]")) button.setAttribute("aria-pressed", String(button.dataset.which === which));
  document.getElementById("zoomRing").hidden = true;
  document.getElementById("zoomPixel").textContent = "Click a pixel to name it and get the command that asks why it came out as it did.";
  document.getElementById("zoom").hidden = false;
}
function openZoom(scene, entry, which) { Object.assign(zoom, { scene, entry, which }); showZoom(); }
document.getElementById("zoomImage").addEventListener("click", (event) => {
  const image = event.currentTarget;
  const x = Math.min(zoom.scene.width - 1, Math.floor(event.offsetX / zoom.scale)), y = Math.min(zoom.scene.height - 1, Math.floor(event.offsetY / zoom.scale));
  const ring = document.getElementById("zoomRing");
  const size = Math.max(10, zoom.scale + 6);
  Object.assign(ring.style, { width: `${size}px`, height: `${size}px`, left: `${image.offsetLeft + (x + 0.5) * zoom.scale - size / 2 - 2}px`, top: `${image.offsetTop + (y + 0.5) * zoom.scale - size / 2 - 2}px` });
  ring.hidden = false;
  const box = document.getElementById("zoomPixel");
  box.replaceChildren(`pixel (${x}, ${y}). Its history in ${zoom.entry.answersWhy ? label(zoom.entry) : "the z-buffer (hsr why does not follow this algorithm's loops yet)"} beside the exact reference's answer: `,
                      make("code", { textContent: whyCommand(zoom.scene, zoom.entry, x, y) }));
  box.dataset.pixel = `${x},${y}`;
});
for (const button of document.querySelectorAll("#zoom [data-scale]")) button.onclick = () => { zoom.scale = Number(button.dataset.scale); showZoom(); };
for (const button of document.querySelectorAll("#zoom [data-which]")) button.onclick = () => { zoom.which = button.dataset.which; showZoom(); };
document.getElementById("zoomClose").onclick = () => { document.getElementById("zoom").hidden = true; };
document.addEventListener("keydown", (event) => { if (event.key === "Escape") document.getElementById("zoom").hidden = true; });

const section = document.getElementById("gallery");
gallery.scenes.forEach((scene, index) => {
  scene.index = index;
  const part = make("section", { className: "scene" },
    make("h2", { textContent: scene.scene }),
    make("p", { textContent: `${scene.width} x ${scene.height} pixels, ${scene.triangles.toLocaleString("en")} triangles. The exact reference first, then each configuration: its picture beside its error map. Click a picture to enlarge it, and a pixel there to ask why.` }),
    scatter(scene));
  const cards = make("div", { className: "cards" });
  scene.entries.forEach((entry, i) => {
    const number = i + 1;
    const figure = (which, caption) => {
      const image = make("img", { src: entry[which], alt: `${label(entry)}: ${caption}`, loading: "lazy" });
      image.addEventListener("click", () => openZoom(scene, entry, which));
      return make("figure", {}, image, make("figcaption", { textContent: caption }));
    };
    const steps = make("a", { href: "#", textContent: "its steps" });
    const command = make("p", { className: "links", hidden: true }, "Record them, then open the folder's steps.html: ", make("code", { textContent: stepsCommand(scene, entry, number) }));
    steps.addEventListener("click", (event) => { event.preventDefault(); command.hidden = !command.hidden; });
    const links = make("p", { className: "links" });
    const parts = [...(entry.readme ? [make("a", { href: entry.readme, textContent: "README" })] : []), ...(entry.knobs === "exact" ? [] : [steps])];
    parts.forEach((part, k) => links.append(...(k > 0 ? [" · ", part] : [part])));
    const verdict = entry.knobs === "exact" ? "exact" : entry.error > 0 ? "wrong" : "right";
    cards.append(make("article", { className: `card ${verdict}`, id: `card-${index}-${number}` },
      make("h3", {}, `${number}. ${entry.knobs === "exact" ? "the exact reference" : entry.algorithm} `,
           make("span", { className: "knobs", textContent: entry.knobs === "exact" || entry.knobs === "defaults" ? "" : entry.knobs })),
      make("p", { className: "figures", textContent: `visibility ${ms(entry.visibilityMs[0])} ms [${ms(entry.visibilityMs[1])}-${ms(entry.visibilityMs[2])}] · ${errorText(entry)}` }),
      make("div", { className: "pair" }, figure("picture", "its picture"), figure("errorMap", entry.errorLegend)),
      links, command));
  });
  part.append(cards);
  section.append(part);
});
})();
)js";

}  // namespace

std::string galleryHtml(const std::string& galleryJson) {
  return std::string("<style>") + kGalleryStyle + "</style>\n<section id=\"gallery\" aria-label=\"each scene: the reference and every configuration\"></section>\n"
         "<div id=\"zoom\" hidden role=\"dialog\" aria-label=\"a picture enlarged\">\n<div class=\"bar\"><strong id=\"zoomTitle\"></strong>\n"
         "<button data-which=\"picture\">picture</button><button data-which=\"errorMap\">error map</button>\n"
         "<button data-scale=\"1\">1x</button><button data-scale=\"2\">2x</button><button data-scale=\"4\">4x</button><button data-scale=\"8\">8x</button>\n"
         "<button id=\"zoomClose\" title=\"Esc\">close</button></div>\n"
         "<div class=\"view\"><img id=\"zoomImage\" alt=\"the picture enlarged\"><div id=\"zoomRing\" hidden></div></div>\n"
         "<div class=\"pixel\" id=\"zoomPixel\"></div>\n</div>\n"
         "<script type=\"application/json\" id=\"galleryData\">" + jsonInScript(galleryJson) + "</script>\n<script>" + kGalleryScript + "</script>\n";
}

}  // namespace hsr::studies
