// The browser edition's page: controls built from the suite's own registry (the one
// `hsr list` prints), the scene's files written into the module's memory, a render and
// its comparison with the exact reference drawn on canvases. Everything runs here.
"use strict";

const hsr = { module: null, registry: null, scenes: [], userScene: null };

const $ = (id) => document.getElementById(id);
const element = (tag, properties = {}, children = []) => {
  const made = Object.assign(document.createElement(tag), properties);
  for (const child of children) made.append(child);
  return made;
};

// ---- Files: the shipped scenes (scenes.json lists each one's files), or a student's own.

// Writes a file into the module's file system, making its folders.
function writeFile(path, bytes) {
  const folders = path.split("/").slice(1, -1);
  let folder = "";
  for (const name of folders) {
    folder += "/" + name;
    if (!hsr.module.FS.analyzePath(folder).exists) hsr.module.FS.mkdir(folder);
  }
  hsr.module.FS.writeFile(path, bytes);
}

// The shipped files, each fetched once (a promise of its bytes), and those already
// written into the module's memory.
const downloads = new Map();
const written = new Set();
function download(file) {
  if (!downloads.has(file)) {
    downloads.set(file, fetch(file).then(async (response) => {
      if (!response.ok) throw new Error(`${file}: ${response.status} ${response.statusText}`);
      return new Uint8Array(await response.arrayBuffer());
    }).catch((error) => {
      downloads.delete(file);  // the next render asks again
      throw error;
    }));
  }
  return downloads.get(file);
}

// The shipped scene's files, at /hsr/<their path in the suite>.
async function loadShipped(scene) {
  for (const file of scene.files) {
    if (written.has(file)) continue;
    writeFile("/hsr/" + file, await download(file));
    written.add(file);
  }
  return "/hsr/" + scene.files[0];
}

// A student's files, under /user/: a scene names its OBJ files by their bare names.
async function loadUserFiles(files) {
  let toml = null;
  for (const file of files) {
    writeFile("/user/" + file.name, new Uint8Array(await file.arrayBuffer()));
    if (file.name.endsWith(".toml")) toml = file.name;
  }
  if (!toml) throw new Error("no .toml among the files dropped; expected a scene file (and the .obj files it names)");
  hsr.userScene = "/user/" + toml;
  const option = element("option", { value: hsr.userScene, textContent: `your scene: ${toml}` });
  $("scene").prepend(option);
  $("scene").value = hsr.userScene;
}

// ---- Controls, from the registry.

// One knob's control: a choice list, a number, or a file name.
function knobControl(owner, knob, onChange) {
  const id = `${owner}.${knob.name}`;
  let input;
  if (knob.range) {
    input = element("input", { id, value: knob.default, size: 8, title: `${knob.range.integer ? "an integer" : "a number"} in [${knob.range.minimum}, ${knob.range.maximum}]${knob.range.percent ? ", or P%" : ""}` });
  } else if (knob.file) {
    input = element("input", { id, value: knob.default, size: 14, title: "a file in the page's memory (none: no file)" });
  } else {
    input = element("select", { id });
    knob.choices.forEach((choice, i) => input.append(element("option", { value: choice, textContent: choice, title: knob.choiceHelp[i] || "" })));
    input.value = knob.default;
  }
  input.dataset.knob = knob.name;
  input.dataset.default = knob.default;
  input.addEventListener("change", onChange);
  const wrapper = element("div", { className: "knob" }, [element("label", {}, [`${knob.name} `, input]), element("p", { className: "help", textContent: knob.help })]);
  wrapper.dataset.variants = JSON.stringify(knob.variants);
  return wrapper;
}

// Shows only the knobs of the chosen variant (a knob names the variants it applies to).
function showVariantKnobs(container) {
  const variant = container.querySelector('[data-knob="variant"]');
  for (const wrapper of container.querySelectorAll(".knob")) {
    const variants = JSON.parse(wrapper.dataset.variants);
    wrapper.hidden = variant && variants.length > 0 && !variants.includes(variant.value);
  }
}

// NAME=VALUE for each shown knob that differs from its default.
function changedKnobs(container) {
  const settings = [];
  for (const input of container.querySelectorAll("[data-knob]")) {
    if (input.closest(".knob").hidden || input.value === input.dataset.default || input.value === "") continue;
    settings.push(`${input.dataset.knob}=${input.value}`);
  }
  return settings;
}

function buildAlgorithmControls() {
  const algorithm = hsr.registry.algorithms.find((a) => a.name === $("algorithm").value);
  $("summary").textContent = algorithm.summary;
  const knobs = $("knobs");
  knobs.replaceChildren(...algorithm.knobs.map((knob) => knobControl(algorithm.name, knob, () => showVariantKnobs(knobs))));
  showVariantKnobs(knobs);
  $("culling").disabled = !algorithm.takesCulling;
  $("culling").title = algorithm.takesCulling ? "" : `${algorithm.name} does not draw from a culled set of triangles`;
}

function buildStageControls() {
  const stages = $("stages");
  for (const stage of hsr.registry.stages) {
    const box = element("input", { type: "checkbox", id: `use.${stage.name}` });
    const knobs = element("div", { hidden: true });
    knobs.append(...stage.knobs.map((knob) => knobControl(stage.name, knob, () => showVariantKnobs(knobs))));
    box.addEventListener("change", () => { knobs.hidden = !box.checked; showVariantKnobs(knobs); });
    const row = element("div", { className: "stage" }, [element("label", { title: stage.summary }, [box, ` ${stage.name}`]), knobs]);
    row.dataset.stage = stage.name;
    stages.append(row);
  }
}

// The stages ticked, as --cull spells them: STAGE:VARIANT:KNOB=VALUE,...
function cullingSpec() {
  if ($("culling").disabled) return "";
  const parts = [];
  for (const row of $("stages").children) {
    if (!row.querySelector('input[type="checkbox"]').checked) continue;
    const variant = row.querySelector('[data-knob="variant"]');
    const settings = changedKnobs(row).filter((setting) => !setting.startsWith("variant="));
    parts.push([row.dataset.stage, variant ? variant.value : null, ...settings].filter(Boolean).join(":"));
  }
  return parts.join(",");
}

// ---- Rendering and drawing.

function canvasOf(id, width, height) {
  const canvas = $(id);
  canvas.width = width;
  canvas.height = height;
  return canvas.getContext("2d");
}

function drawRgba(id, width, height, rgba) {
  const context = canvasOf(id, width, height);
  if (rgba.length !== width * height * 4) return;
  context.putImageData(new ImageData(new Uint8ClampedArray(rgba), width, height), 0, 0);
}

// Visible triangles' ids as colours, each id a colour of its own (the background black).
function idColours(ids) {
  const rgba = new Uint8ClampedArray(ids.length * 4);
  for (let p = 0; p < ids.length; ++p) {
    const id = ids[p];
    if (id === 0) { rgba[4 * p + 3] = 255; continue; }
    const h = Math.imul(id, 2654435761) >>> 0;
    rgba[4 * p] = 64 + (h & 127);
    rgba[4 * p + 1] = 64 + ((h >>> 8) & 127);
    rgba[4 * p + 2] = 64 + ((h >>> 16) & 127);
    rgba[4 * p + 3] = 255;
  }
  return rgba;
}

// ---- Mine against the reference, in one view: the error map, the render's visible
// triangles, the reference's in the same colours (so that the two match wherever the
// render is right), or the two in turn.
const against = { width: 0, height: 0, views: {}, chosen: "difference", blinking: null };
const againstCaptions = {
  difference: "error against the exact reference: the reference dimmed, wrong pixels red, ambiguous blue",
  mine: "mine: the visible triangles as this render decided them (colours as in ids)",
  reference: "the exact reference's visible triangles, in the same colours",
  blink: "mine and the reference in turn, twice a second: what changes is what differs",
};

function drawAgainst(view) {
  $("against").dataset.showing = view;
  drawRgba("error", against.width, against.height, against.views[view]);
}

// Shows the view chosen, or the difference where this render has no such view (a line
// drawing has only its difference); the choice stays for the next render.
function showAgainst(chosen) {
  clearInterval(against.blinking);
  against.blinking = null;
  const has = (name) => (name === "blink" ? Boolean(against.views.mine && against.views.reference) : Boolean(against.views[name]));
  against.chosen = chosen;
  const view = has(chosen) ? chosen : "difference";
  for (const button of document.querySelectorAll("#against .toggle button")) {
    button.setAttribute("aria-pressed", String(button.dataset.view === view));
    button.disabled = !has(button.dataset.view);
  }
  $("againstCaption").textContent = has(view) ? againstCaptions[view] : "";
  if (!has(view)) return canvasOf("error", 1, 1);
  if (view !== "blink") return drawAgainst(view);
  drawAgainst("mine");
  against.blinking = setInterval(() => drawAgainst($("against").dataset.showing === "mine" ? "reference" : "mine"), 500);
}

// Distance along the view axis, the nearest white and the farthest dark grey; the
// background (infinity) black.
function drawDepth(width, height, depth) {
  let near = Infinity, far = -Infinity;
  for (const d of depth) if (Number.isFinite(d)) { near = Math.min(near, d); far = Math.max(far, d); }
  const rgba = new Uint8ClampedArray(width * height * 4);
  for (let p = 0; p < depth.length; ++p) {
    const d = depth[p];
    const grey = Number.isFinite(d) ? 255 - Math.round(200 * (far > near ? (d - near) / (far - near) : 0)) : 0;
    rgba[4 * p] = rgba[4 * p + 1] = rgba[4 * p + 2] = grey;
    rgba[4 * p + 3] = 255;
  }
  drawRgba("depth", width, height, rgba);
}

const format = (value, digits = 2) => (value === null || value === undefined ? "–" : Number(value).toFixed(digits));

function showMetrics(result, compared) {
  const rows = [["time", `${format(result.ms)} ms: visibility ${format(result.visibilityMs)} ms + shading, effects ${format(result.effectsMs)} ms`]];
  if (compared && compared.error) {
    const e = compared.error;
    rows.push(["pixel error", `${(100 * e.pixelError).toFixed(4)}% (${e.wrongPixels} wrong of ${e.comparedPixels} compared; ${e.ambiguousPixels} ambiguous left out)`]);
    rows.push(["depth error", `mean ${e.depthErrorMean === null ? "–" : e.depthErrorMean.toPrecision(3)}, max ${e.depthErrorMax === null ? "–" : e.depthErrorMax.toPrecision(3)} (scene units)`]);
    rows.push(["reference", `${e.exactFallbacks} rays needed exact arithmetic`]);
  }
  if (compared && compared.lineError) {
    const e = compared.lineError;
    rows.push(["line error", `${(100 * e.error).toFixed(4)}% of ${format(e.visibleLength, 1)} px visible (${format(e.wronglyDrawn, 1)} px drawn though hidden, ${format(e.wronglyHidden, 1)} px hidden though visible)`]);
  }
  if (result.partial) rows.push(["partial", result.partial]);
  $("metrics").replaceChildren(...rows.map(([name, value]) => element("tr", {}, [element("th", { textContent: name }), element("td", { textContent: value })])));
  const counters = Object.entries(result.counters).map(([name, value]) => element("tr", {}, [element("td", { textContent: name }), element("td", { className: "number", textContent: value.toLocaleString("en") })]));
  const passes = result.passes.map((pass) => element("tr", {}, [element("td", { textContent: `${pass.pass} time` }), element("td", { className: "number", textContent: `${format(pass.ms, 3)} ms` })]));
  $("counters").replaceChildren(...counters, ...passes);
}

// A message with the page's own folders left out: the files are the student's (/user/)
// or the suite's (/hsr/), named as they named them.
const asTheStudentNamesIt = (message) => message.replaceAll("/user/", "").replaceAll("/hsr/", "");

// Lets the browser paint what was just drawn before the next long call blocks it.
const paint = () => new Promise((resolve) => setTimeout(resolve, 0));

// The render the controls describe, drawn at once; then, when asked for (and always for
// a line drawing, whose picture is its comparison), its comparison with the exact
// reference. Bad input: one line of error ("hsr: error: ..."), the page left as it was.
async function render() {
  $("message").textContent = "";
  $("status").textContent = "rendering…";
  hsr.lastComparison = null;
  $("render").disabled = true;
  await paint();
  try {
    const chosen = $("scene").value;
    const shipped = hsr.scenes.find((scene) => scene.name === chosen);
    const path = shipped ? await loadShipped(shipped) : chosen;
    const size = $("size").value.trim();
    const request = { scene: path, algorithm: $("algorithm").value, knobs: changedKnobs($("knobs")).join(";"), cull: cullingSpec(), size };
    const result = JSON.parse(hsr.module.render(request));
    if (result.message) {
      $("message").textContent = asTheStudentNamesIt(result.message);
      $("status").textContent = "";
      // Bad input leaves the last render shown, to be asked about still; a render that ran
      // out of memory let it go, and with it what it showed.
      if (!hsr.module.hasRender()) forgetShown();
      return result;
    }
    const { width, height } = result;
    const what = `${request.algorithm} on ${asTheStudentNamesIt(chosen)}, ${width}×${height}`;
    drawRgba("color", width, height, hsr.module.colorPixels());
    const idsShown = idColours(hsr.module.idPixels());
    drawRgba("ids", width, height, idsShown);
    drawDepth(width, height, hsr.module.depthPixels());
    Object.assign(against, { width, height, views: {} });
    showAgainst(against.chosen);
    putAnswersAway();  // they answered for the render before
    showMetrics(result, null);
    $("note").textContent = result.kind === "line" ? "A line drawing: its colour is the drawing, and it has no ids or depth." : "";
    hsr.lineDrawing = result.kind === "line";
    hsr.lastPicture = performance.now();
    if ($("reference").checked || result.kind === "line") {
      $("status").textContent = `${what}; comparing with the exact reference…`;
      await paint();
      const compared = JSON.parse(hsr.module.compare());
      if (compared.message) {
        $("message").textContent = asTheStudentNamesIt(compared.message);
      } else {
        const error = hsr.module.errorPixels();
        const referenceIds = hsr.module.referenceIdPixels();
        against.views = {
          difference: error.length ? new Uint8ClampedArray(error) : null,
          mine: referenceIds.length ? idsShown : null,
          reference: referenceIds.length ? idColours(referenceIds) : null,
        };
        showAgainst(against.chosen);
        hsr.lastComparison = compared;
        showMetrics(result, compared);
        Object.assign(result, compared);
      }
    }
    $("status").textContent = what;
    return result;
  } catch (error) {
    $("message").textContent = `hsr: error: ${error.message}`;
    $("status").textContent = "";
    return { message: error.message };
  } finally {
    $("render").disabled = false;
  }
}

// What was asked of a render put away: the answer to why, its edge and ringed pixel, and
// the steps.
function putAnswersAway() {
  $("whyBox").hidden = true;
  showEdge(null);
  for (const marker of document.querySelectorAll(".marker")) marker.hidden = true;
  putStepsAway();
}

// Nothing rendered to show: the images and metrics, and what was asked of them, put away.
function forgetShown() {
  for (const canvas of document.querySelectorAll(".images canvas")) canvasOf(canvas.id, 1, 1);
  Object.assign(against, { views: {} });
  showAgainst(against.chosen);
  $("metrics").replaceChildren();
  $("counters").replaceChildren();
  putAnswersAway();
}

// ---- Why a pixel came out as it did: hsr why's answer for the last render's pixel.

// The pixel of a canvas under a click, whatever size the canvas is shown at.
function pixelUnder(canvas, event) {
  const box = canvas.getBoundingClientRect();
  const clamp = (value, size) => Math.min(Math.max(Math.floor(value), 0), size - 1);
  return [clamp(((event.clientX - box.left) * canvas.width) / box.width, canvas.width),
          clamp(((event.clientY - box.top) * canvas.height) / box.height, canvas.height)];
}

// Asks the module why pixel (x, y) came out as it did (for a line drawing, the edge
// nearest it), and shows the answer, or with "quiz me" ticked asks the student to predict
// it first (quiz.js); an algorithm whose loops it does not follow gets the command
// line's line, in the box.
function why(x, y) {
  if ($("quizMode").checked && quizUnderWayAt(x, y)) return null;  // a double click's second click: the quiz goes on
  const result = JSON.parse(hsr.module.why(x, y, 0));
  for (const canvas of document.querySelectorAll(".images canvas")) {
    const marker = canvas.nextElementSibling;  // the pixel asked about, ringed on every image that has one
    marker.style.left = `${(100 * (x + 0.5)) / canvas.width}%`;
    marker.style.top = `${(100 * (y + 0.5)) / canvas.height}%`;
    marker.hidden = canvas.width <= 1 || (hsr.lineDrawing && (canvas.id === "ids" || canvas.id === "depth"));
  }
  showEdge(result.edge);
  $("whyBox").hidden = false;
  $("whyPixel").textContent = `(${x}, ${y})`;
  if (result.message) {
    stopQuiz();
    $("why").textContent = asTheStudentNamesIt(result.message);
    $("whyBox").className = "";
    return result;
  }
  $("why").textContent = asTheStudentNamesIt(result.text);
  $("whyBox").className = (result.edge ? result.edge.agrees : result.answer.pixels[0].agrees) ? "agrees" : "differs";
  if ($("quizMode").checked) startQuiz(result, [x, y]);
  else stopQuiz();
  return result;
}

// The edge a line drawing's answer is about, drawn over the drawing and its difference
// with the reference: a line from where Appel's walk starts (a dot; the others walk
// nowhere: from the edge's start) to its other end, and a ring at each place its
// visibility may change (Appel: its QI changes; Roberts: a body's hidden part begins;
// the floating horizon: it crosses a horizon); none for a pixel's answer.
function showEdge(edge) {
  for (const overlay of document.querySelectorAll(".images svg.edge")) overlay.remove();
  if (!edge) return;
  const first = edge.walk[0];
  const start = first && first.subject === "" && Number.isFinite(first.u) ? first.u : 0;
  const at = (u) => [edge.from[0] + u * (edge.to[0] - edge.from[0]), edge.from[1] + u * (edge.to[1] - edge.from[1])];
  for (const id of ["color", "error"]) {
    const canvas = $(id);
    if (canvas.width <= 1) continue;
    const svg = document.createElementNS("http://www.w3.org/2000/svg", "svg");
    svg.setAttribute("class", "edge");
    svg.setAttribute("viewBox", `0 0 ${canvas.width} ${canvas.height}`);
    const shape = (name, attributes) => {
      const made = document.createElementNS("http://www.w3.org/2000/svg", name);
      for (const [key, value] of Object.entries(attributes)) made.setAttribute(key, value);
      svg.append(made);
    };
    const [x0, y0] = at(start), [x1, y1] = at(1 - start);
    shape("line", { x1: x0, y1: y0, x2: x1, y2: y1 });
    shape("circle", { cx: x0, cy: y0, r: 3, class: "start" });
    for (const event of edge.walk) if (event.change !== 0) shape("circle", { cx: at(event.u)[0], cy: at(event.u)[1], r: 2.5, class: "change" });
    canvas.parentElement.append(svg);
  }
}

// ---- The algorithm's steps: recorded in the page as hsr render --steps records them, and
// gone through in the steps page (the one hsr render --steps writes as steps.html, shown
// inside this one), whose clicks on a pixel this page answers with why() at the step.
const stepPictures = { addresses: [] };

// A picture (RGBA) as the address of a PNG image of it.
function pictureAddress(rgba, width, height) {
  const canvas = element("canvas", { width, height });
  canvas.getContext("2d").putImageData(new ImageData(new Uint8ClampedArray(rgba), width, height), 0, 0);
  return new Promise((resolve) => canvas.toBlob((blob) => resolve(URL.createObjectURL(blob)), "image/png"));
}

// The suite's files the steps were recorded in, written where the module reads their
// lines; a file the site lacks leaves the page saying its lines cannot be shown.
async function loadSources(files) {
  for (const file of files) {
    const shipped = `src/${file}`;
    if (file.startsWith("/") || written.has(shipped)) continue;
    try {
      writeFile(`/hsr/${shipped}`, await download(shipped));
      written.add(shipped);
    } catch { /* shown as lines that cannot be shown */ }
  }
}

async function recordSteps() {
  $("stepsMessage").textContent = "";
  $("stepsStatus").textContent = "recording the steps…";
  $("recordSteps").disabled = true;
  await paint();
  try {
    const recorded = JSON.parse(hsr.module.recordSteps($("every").value.trim()));
    if (recorded.message) {
      $("stepsMessage").textContent = asTheStudentNamesIt(recorded.message);
      $("stepsStatus").textContent = "";
      return recorded;
    }
    await loadSources(recorded.files);
    for (const address of stepPictures.addresses) URL.revokeObjectURL(address);
    stepPictures.addresses = [];
    for (const [index, step] of recorded.steps.entries()) {
      stepPictures.addresses.push(await pictureAddress(hsr.module.stepPicture(index), step.width, step.height));
    }
    const frame = $("stepsFrame");
    const shown = new Promise((resolve) => { frame.onload = resolve; });
    frame.srcdoc = hsr.module.stepsPage(`${$("status").textContent}: its steps`, stepPictures.addresses);
    frame.hidden = false;
    await shown;
    frame.contentWindow.focus();  // the arrow keys go to the steps at once
    $("stepsStatus").textContent = `${recorded.steps.length} steps`;
    return recorded;
  } finally {
    $("recordSteps").disabled = false;
  }
}

// The steps page asks about a pixel at a step: the history up to it, as hsr why --step prints it.
window.addEventListener("message", (event) => {
  const asked = event.data;
  const frame = $("stepsFrame");
  if (event.source !== frame.contentWindow || !asked || asked.kind !== "hsr-why") return;
  const result = JSON.parse(hsr.module.why(asked.x, asked.y, asked.step));
  const text = asTheStudentNamesIt(result.message || result.text);
  frame.contentWindow.postMessage({ kind: "hsr-why-answer", x: asked.x, y: asked.y, step: asked.step, text }, "*");
});

// Steps shown are the last render's: a new render puts them away.
function putStepsAway() {
  $("stepsFrame").hidden = true;
  $("stepsFrame").removeAttribute("srcdoc");
  $("stepsStatus").textContent = "";
  $("stepsMessage").textContent = "";
}

// ---- The same bits as native: every render's line of hashes (tests/identity), which a
// test compares with the native build's.
async function identity(width = 320, randomScenes = 0, only = "") {
  for (const scene of hsr.scenes) await loadShipped(scene);
  return hsr.module.identity(width, randomScenes, only);
}

// What the page shows first: the z-buffer on counters at 640x360.
const kFirstScene = "counters.toml";

// When each part of starting was done, in ms since the page was asked for.
const started = {};

async function start() {
  $("status").textContent = "loading…";
  // The module, and meanwhile the list of scenes and the first scene's files.
  const listed = fetch("scenes.json").then((response) => response.json()).then((listing) => {
    for (const file of listing.scenes.find((scene) => scene.name === kFirstScene).files) download(file);
    return listing;
  });
  const [module, listing] = await Promise.all([createHsr(), listed]);
  hsr.module = module;
  started.module = performance.now();
  hsr.registry = JSON.parse(hsr.module.registry());
  hsr.scenes = listing.scenes;
  for (const scene of hsr.scenes) $("scene").append(element("option", { value: scene.name, textContent: scene.name.replace(/\.toml$/, "") }));
  for (const algorithm of hsr.registry.algorithms) $("algorithm").append(element("option", { value: algorithm.name, textContent: algorithm.name }));
  buildStageControls();
  $("algorithm").value = "zbuffer";
  buildAlgorithmControls();
  $("algorithm").addEventListener("change", buildAlgorithmControls);
  $("scene").value = kFirstScene;
  $("size").value = "640x360";
  $("controls").addEventListener("submit", (event) => { event.preventDefault(); render(); });
  $("recordSteps").addEventListener("click", () => recordSteps().catch((error) => { $("stepsMessage").textContent = `hsr: error: ${error.message}`; }));
  // A click asks why about the pixel under it; a double click shows the image at its own
  // size (a wrong pixel is one pixel), and back.
  for (const figure of document.querySelectorAll(".images figure")) {
    const canvas = figure.querySelector("canvas");
    canvas.addEventListener("click", (event) => { if (hsr.module && canvas.width > 1) why(...pixelUnder(canvas, event)); });
    // The pixel under the pointer, named, so that a student can aim at one.
    canvas.addEventListener("mousemove", (event) => {
      if (canvas.width > 1) $("hover").textContent = `pixel (${pixelUnder(canvas, event).join(", ")}) under the pointer`;
    });
    canvas.addEventListener("mouseleave", () => { $("hover").textContent = ""; });
    figure.addEventListener("dblclick", () => figure.classList.toggle("large"));
  }
  for (const button of document.querySelectorAll("#against .toggle button")) {
    button.addEventListener("click", () => showAgainst(button.dataset.view));
    button.addEventListener("dblclick", (event) => event.stopPropagation());  // not the figure's enlarging
  }
  $("files").addEventListener("change", async () => {
    try { await loadUserFiles([...$("files").files]); await render(); } catch (error) { $("message").textContent = `hsr: error: ${error.message}`; }
  });
  const drop = $("drop");
  drop.addEventListener("dragover", (event) => { event.preventDefault(); drop.classList.add("over"); });
  drop.addEventListener("dragleave", () => drop.classList.remove("over"));
  drop.addEventListener("drop", async (event) => {
    event.preventDefault();
    drop.classList.remove("over");
    try { await loadUserFiles([...event.dataTransfer.files]); await render(); } catch (error) { $("message").textContent = `hsr: error: ${error.message}`; }
  });
  await render();
  started.firstPicture = hsr.lastPicture;
  started.firstComparison = performance.now();
  document.body.dataset.ready = "true";  // the page's first render is done (the tests wait for it)
}

window.hsrPage = { render, why, recordSteps, stepPictures, identity, state: hsr, started };
start().catch((error) => { $("message").textContent = `hsr: error: the page could not start: ${error.message}`; });
