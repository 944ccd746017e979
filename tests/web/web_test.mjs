// The browser edition in a real browser (Debian's chromium, headless, driven by
// playwright-core): the site web/dist (scripts/web.sh) served by python3 -m http.server as
// README says, then
//   - the first render (counters at 640x360) drawn, then its error against the exact
//     reference, each with the time it took from asking for the page (reported, not
//     asserted: speed is for benchmarks, and this machine is shared);
//   - a pixel clicked: the page's answer to "why" is hsr why's, line for line (a line
//     drawing's, hsr why --edge's for the edge nearest the pixel);
//   - "quiz me": each question judged as the algorithm decided (the native hsr why
//     --json's answer), a wrong answer said to be wrong, any tied triangle right at a
//     certified tie, then the whole answer;
//   - the controls clicked through: another algorithm and its variant, a knob, a culling
//     stage, each rendering without an error;
//   - bad input (a broken TOML, an OBJ with a bad face, an absurd size): the one-line
//     message the command line prints, and the page still rendering afterwards;
//   - the same bits as native: every render's hashes (tests/identity) computed in the
//     page, against tests/identity/expected.txt, the native build's;
//   - screenshots of the page into out/web/.
//   node tests/web/web_test.mjs [--full]     --full: every scene and 100 random scenes
//                                            (default: the hard cases and 10 random scenes)
import { spawn, spawnSync } from "node:child_process";
import { mkdirSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { createServer } from "node:net";
import { join } from "node:path";
import { Checks, launchBrowser, openPage, root } from "./browser.mjs";

const full = process.argv.includes("--full");
const out = join(root, "out", "web");
mkdirSync(out, { recursive: true });

const checks = new Checks();
const check = (condition, what) => checks.check(condition, what);

// A free port on the loopback interface, for the static server.
const port = await new Promise((resolve) => {
  const probe = createServer().listen(0, "127.0.0.1", () => {
    const { port } = probe.address();
    probe.close(() => resolve(port));
  });
});
const server = spawn("python3", ["-m", "http.server", String(port), "--bind", "127.0.0.1", "-d", join(root, "web", "dist")], { stdio: "ignore" });
await new Promise((resolve) => setTimeout(resolve, 800));

const browser = await launchBrowser();
try {
  const { page, consoleErrors } = await openPage(browser);
  await page.goto(`http://127.0.0.1:${port}/`);
  await page.waitForSelector("body[data-ready=true]", { timeout: 60000 });
  // The page's clock starts when the page was asked for (performance.timeOrigin).
  const parts = await page.evaluate(() => window.hsrPage.started);
  const seconds = (ms) => (ms / 1000).toFixed(2);
  console.log(`first render of counters at 640x360: the module ready at ${seconds(parts.module)} s, the picture drawn at ` +
              `${seconds(parts.firstPicture)} s, its comparison with the exact reference at ${seconds(parts.firstComparison)} s after the page was asked for`);
  writeFileSync(join(out, "first-render-seconds.txt"), `${seconds(parts.firstPicture)} ${seconds(parts.firstComparison)}\n`);

  const text = (selector) => page.$eval(selector, (node) => node.textContent);
  // Whether a canvas holds more than one colour: something was drawn.
  const drawn = (id) => page.$eval(`#${id}`, (canvas) => {
    const { data } = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height);
    for (let i = 4; i < data.length; i += 4) if (data[i] !== data[0] || data[i + 1] !== data[1] || data[i + 2] !== data[2]) return true;
    return false;
  });
  const renderWith = async () => {
    await page.click("#render");
    await page.waitForFunction(() => !document.getElementById("render").disabled);
    return { message: await text("#message"), status: await text("#status") };
  };

  check((await text("#status")).includes("zbuffer on counters.toml, 640×360"), "the first render: the z-buffer on counters at 640x360");
  for (const canvas of ["color", "ids", "depth", "error"]) check(await drawn(canvas), `the ${canvas} image is drawn`);
  check((await text("#metrics")).includes("pixel error"), "its error against the exact reference is shown");
  check((await text("#differences")).includes("one thread"), "the page says what differs from the command line (one thread, the textbook loops)");
  check((await text("#counters")).includes("fragments tested"), "and its counters");
  await page.screenshot({ path: join(out, "page.png") });
  await page.dblclick("#error");
  const large = await page.$eval("#error", (canvas) => [canvas.closest("figure").classList.contains("large"), canvas.getBoundingClientRect().width, canvas.width]);
  check(large[0] && Math.round(large[1]) === large[2], `a double click shows the error image at its own size (${Math.round(large[1])} of ${large[2]} pixels wide)`);
  await page.screenshot({ path: join(out, "error-large.png"), fullPage: true });
  await page.dblclick("#error");

  // Why: a click on a pixel of an image, shown at its own size or scaled down (where a
  // CSS pixel spans several of the image's), answers for the pixel under the pointer as
  // hsr why does on the command line, line for line but the scene's name.
  // What hsr why prints for the scene with these options, without its first line (which
  // names the scene by its path): for a pixel, and along the edge nearest a pixel.
  const whyPrints = (scene, options) => {
    const run = spawnSync(join(root, "build", "hsr"), ["why", join(root, "scenes", scene), ...options], { encoding: "utf8" });
    return run.stdout.split("\n").slice(1).join("\n").trim();
  };
  const nativeWhy = (scene, pixel, extra = []) => whyPrints(scene, ["--pixel", pixel, ...extra]);
  const nativeEdge = (scene, pixel, algorithm) => whyPrints(scene, ["--size", "320x240", "--algo", algorithm, "--edge", pixel]);
  const clickPixel = async (canvas, x, y) => {
    const scale = await page.$eval(`#${canvas}`, (c) => [c.getBoundingClientRect().width / c.width, c.getBoundingClientRect().height / c.height]);
    await page.click(`#${canvas}`, { position: { x: (x + 0.5) * scale[0], y: (y + 0.5) * scale[1] } });
    await page.waitForFunction(() => !document.getElementById("whyBox").hidden);
    const [answeredX, answeredY] = (await text("#whyPixel")).match(/\d+/g).map(Number);
    const within = Math.abs(answeredX - x) <= Math.ceil(1 / scale[0]) && Math.abs(answeredY - y) <= Math.ceil(1 / scale[1]);
    return { shown: (await text("#why")).split("\n").slice(1).join("\n").trim(), pixel: `${answeredX},${answeredY}`, within, scale: scale[0] };
  };
  await page.dblclick("#color");  // at its own size: a CSS pixel is an image pixel
  for (const [canvas, x, y] of [["color", 320, 180], ["color", 101, 250], ["depth", 500, 60]]) {
    const answered = await clickPixel(canvas, x, y);
    const native = nativeWhy("counters.toml", answered.pixel, ["--size", "640x360"]);
    check(answered.shown === native && answered.within && answered.shown.includes("=> "),
          `a click near pixel (${x}, ${y}) of the ${canvas} image shown at ${answered.scale.toFixed(2)}x answers for pixel (${answered.pixel}) as hsr why does`);
    if (answered.shown !== native) console.log(`  page:\n${answered.shown}\n  hsr why:\n${native}`);
  }
  const exact = await clickPixel("color", 77, 33);
  check(exact.pixel === "77,33", `at its own size, the click answers for the pixel under the pointer exactly (${exact.pixel})`);
  await page.dblclick("#color");
  await clickPixel("ids", 320, 180);
  await page.locator("#results").screenshot({ path: join(out, "why.png") });

  // The controls: built from the registry, so every algorithm is there.
  const algorithms = await page.$$eval("#algorithm option", (options) => options.map((o) => o.value));
  check(["zbuffer", "ray_casting", "painter", "warnock", "watkins", "weiler_atherton", "abuffer", "roberts", "appel", "floating_horizon", "reference"].every((a) => algorithms.includes(a)),
        `every algorithm of the registry is offered (${algorithms.length})`);
  await page.selectOption("#algorithm", "painter");
  await page.selectOption('[id="painter.variant"]', "newell");
  await page.selectOption("#scene", "hard/cyclic_overlap.toml");
  await page.fill("#size", "");
  let result = await renderWith();
  check(result.message === "" && result.status.includes("painter on hard/cyclic_overlap.toml"), "the painter's newell variant on the cyclic overlap");
  check((await text("#counters")).includes("newell splits"), "with Newell's counters");
  check(await page.$eval("#whyBox", (box) => box.hidden), "a new render puts away the last render's answer to why");
  const painted = await clickPixel("color", 98, 44);
  check(painted.shown === nativeWhy("hard/cyclic_overlap.toml", painted.pixel, ["--algo", "painter", "--variant", "newell"]) &&
        painted.shown.includes("painted over what the pixel showed"), `the painter's answer to why, as hsr why's (pixel ${painted.pixel})`);
  await page.screenshot({ path: join(out, "painter.png") });

  await page.selectOption("#algorithm", "warnock");
  result = await renderWith();
  const subdivided = await clickPixel("color", 98, 44);
  check(subdivided.shown === nativeWhy("hard/cyclic_overlap.toml", subdivided.pixel, ["--algo", "warnock"]) && subdivided.shown.includes("window 200 x 200 at (0, 0)"),
        `Warnock's answer to why, its windows down to the pixel, as hsr why's (pixel ${subdivided.pixel})`);
  await page.selectOption("#algorithm", "watkins");
  result = await renderWith();
  const spans = await clickPixel("color", 98, 44);
  check(spans.shown === nativeWhy("hard/cyclic_overlap.toml", spans.pixel, ["--algo", "watkins"]) && spans.shown.includes(": cut into spans where the polygons"),
        `Watkins's answer to why, its row and span, as hsr why's (pixel ${spans.pixel})`);

  // Predict, then reveal: with "quiz me" ticked a click asks before it shows. Each answer
  // is judged by what the algorithm recorded; the test answers from the native program's
  // hsr why --json for the same pixel, wrongly once on purpose.
  const nativeJson = (scene, pixel, extra) => {
    const run = spawnSync(join(root, "build", "hsr"), ["why", join(root, "scenes", scene), "--pixel", pixel, "--json", ...extra], { encoding: "utf8" });
    return JSON.parse(run.stdout).pixels[0];
  };
  const quizShown = () => page.evaluate(() => ({
    progress: document.getElementById("quizProgress").textContent,
    prompt: document.getElementById("quizQuestion").textContent,
    context: document.getElementById("quizContext").textContent,
    choices: [...document.querySelectorAll("#quizChoices button")].map((button) => button.textContent),
    feedback: document.getElementById("quizFeedback").textContent,
    whyHidden: document.getElementById("why").hidden,
    quizHidden: document.getElementById("quiz").hidden,
  }));
  // A choice of triangle: its name, and where the loop met it, its distance.
  const names = (choice, name) => choice === name || choice.startsWith(`${name}, `);
  // The choices the native answer makes right for the question shown: the triangle shown
  // (or a tied one), whether the pixel shows the event's triangle after it, or the
  // decision at the event.
  const rightChoices = (asked, pixel) => {
    if (asked.prompt.startsWith("Which triangle")) {
      const right = [pixel.shows.name, ...(pixel.reference.ambiguous ? pixel.reference.tied.map((t) => t.name) : [])];
      return asked.choices.filter((choice) => right.some((name) => names(choice, name)));
    }
    const event = pixel.history[Number(/event (\d+)/i.exec(asked.prompt)[1]) - 1];
    if (asked.prompt.startsWith("After event")) return [event.shown ? "yes" : "no"];
    if (asked.prompt.includes("which piece does the painter paint")) return asked.choices.filter((choice) => names(choice, event.name));
    return [event.outcome.split(": ")[0]];
  };
  // Answers the questions left, each rightly, after `before` were answered (and `wrong`
  // of them wrongly): how many were asked in all, and what went differently from the
  // native answer.
  const takeQuiz = async (pixel, before, wrongBefore) => {
    const problems = [];
    let asked = before, wrong = wrongBefore;
    for (;;) {
      const now = await quizShown();
      if (now.choices.length === 0) break;
      asked += 1;
      const right = rightChoices(now, pixel);
      const choice = now.choices.find((c) => right.includes(c));
      if (choice === undefined) { problems.push(`no right choice offered for "${now.prompt}" (${now.choices.join(" | ")})`); break; }
      await page.click(`#quizChoices button:nth-child(${now.choices.indexOf(choice) + 1})`);
      const judged = (await quizShown()).feedback;
      const meant = right.includes(choice) ? "Right." : "Not quite.";
      wrong += meant === "Not quite.";
      if (!judged.startsWith(meant)) problems.push(`"${now.prompt}" answered "${choice}": ${judged}`);
      await page.click("#quizNext");
    }
    const end = await quizShown();
    if (end.progress !== `${asked - wrong} of ${asked} predicted right; the whole answer:` || end.whyHidden) problems.push(`the end: ${end.progress}`);
    return { asked, wrong, problems };
  };
  await page.check("#quizMode");
  await page.selectOption("#algorithm", "warnock");
  result = await renderWith();
  await page.dblclick("#color");  // at its own size: the click asks about the pixel under it exactly
  const quizzed = await clickPixel("color", 98, 44);
  const warnockPixel = nativeJson("hard/cyclic_overlap.toml", "98,44", ["--algo", "warnock"]);
  const opened = await quizShown();
  check(quizzed.pixel === "98,44" && !opened.quizHidden && opened.whyHidden && opened.progress === "question 1 of 9" &&
        opened.prompt === "Which triangle will pixel (98, 44) show?" && opened.choices.some((c) => names(c, warnockPixel.shows.name)) &&
        opened.choices.includes(`${warnockPixel.shows.name}, ${warnockPixel.shows.distance.toPrecision(6)} away`),
        `quiz me: a click asks first which triangle the pixel will show, then about 8 of Warnock's 9 events (${opened.progress})`);
  await page.click(`#quizChoices button:nth-child(${opened.choices.findIndex((c) => !names(c, warnockPixel.shows.name)) + 1})`);
  const wrongly = await quizShown();
  check(wrongly.feedback === `Not quite. It shows ${warnockPixel.shows.name}, as the exact reference does.` &&
        (await page.$$eval("#quizChoices button", (buttons) => buttons.every((b) => b.disabled))),
        `a wrong answer is said to be wrong, with what the algorithm did (${wrongly.feedback})`);
  check(await page.$eval("#whyBox", (box) => box.className === ""), "the box does not say whether the algorithm agrees with the reference until the end");
  await page.locator("#whyBox").screenshot({ path: join(out, "quiz.png") });
  await page.click("#quizNext");
  const windowQuestion = await quizShown();
  check(windowQuestion.prompt === "What does the loop decide at event 2?" &&
        windowQuestion.choices.join(" | ") === "rule 1, empty | rule 2, one polygon | rule 3, surrounded | the smallest window | subdivided into four",
        `a window's question offers every rule of Warnock's (${windowQuestion.choices.join(" | ")})`);
  // A double click on the quiz's pixel (it enlarges the image, and back) leaves the quiz as it was.
  const before = await quizShown();
  // At the whole CSS pixel nearest the pixel's center that lies in it (a mouse event's
  // position is whole CSS pixels; the image is shown at least at its own size).
  const dblclickPixel = async (canvas, x, y) => {
    const [left, top, scale] = await page.$eval(`#${canvas}`, (c) => {
      const box = c.getBoundingClientRect();
      return [box.left, box.top, box.width / c.width];
    });
    const within = (start, n) => Math.min(Math.max(Math.round(start + (n + 0.5) * scale), Math.ceil(start + n * scale)), Math.ceil(start + (n + 1) * scale) - 1);
    await page.mouse.dblclick(within(left, x), within(top, y));
  };
  await dblclickPixel("ids", 98, 44);
  await dblclickPixel("ids", 98, 44);
  check((await quizShown()).progress === before.progress, `a double click on the quiz's pixel leaves the quiz where it was (${before.progress})`);
  const warnockQuiz = await takeQuiz(warnockPixel, 1, 1);
  const kinds = await text("#why");
  check(warnockQuiz.problems.length === 0 && warnockQuiz.asked === 9 && (await text("#quizProgress")) === "8 of 9 predicted right; the whole answer:" &&
        (await text("#why")).split("\n").slice(1).join("\n").trim() === nativeWhy("hard/cyclic_overlap.toml", "98,44", ["--algo", "warnock"]) &&
        kinds.includes("rule 3, surrounded") && (await page.$eval("#whyBox", (box) => box.className)) === "agrees",
        `Warnock's windows and its rule asked one by one, each judged as the algorithm decided, then hsr why's answer (${warnockQuiz.problems.join("; ") || "8 of 9"})`);
  // At a certified tie any of the tied triangles is right: the coplanar case's left pair.
  await page.selectOption("#algorithm", "zbuffer");
  await page.selectOption("#scene", "hard/coplanar.toml");
  await page.fill("#size", "320x180");
  result = await renderWith();
  const tie = await clickPixel("color", 125, 95);
  const tiedPixel = nativeJson("hard/coplanar.toml", "125,95", ["--size", "320x180"]);
  const other = tiedPixel.reference.tied.map((t) => t.name).find((name) => name !== tiedPixel.shows.name);
  const tieQuestion = await quizShown();
  const otherChoice = tieQuestion.choices.findIndex((c) => names(c, other));
  await page.click(`#quizChoices button:nth-child(${otherChoice + 1})`);
  const tieAnswer = (await quizShown()).feedback;
  check(tie.pixel === "125,95" && tiedPixel.reference.ambiguous && otherChoice >= 0 && tieAnswer.startsWith("Right.") && tieAnswer.includes("a certified tie"),
        `at a certified tie the tied triangle the z-buffer did not show is right too (${other}: ${tieAnswer})`);
  await page.click("#quizNext");
  const zbufferQuiz = await takeQuiz(tiedPixel, 1, 0);
  check(zbufferQuiz.problems.length === 0 && zbufferQuiz.asked === 1 + tiedPixel.history.length,
        `and each fragment: does the pixel show it after the depth test (${zbufferQuiz.problems.join("; ") || zbufferQuiz.asked + " asked"})`);
  // The painter paints every piece that reaches the pixel: what it decides, and what the
  // quiz asks, is the order. On the cyclic overlap Newell's test cuts "third", and its cut
  // piece is painted first, under "second", though nearer along this sight line.
  await page.selectOption("#algorithm", "painter");
  await page.selectOption('[id="painter.variant"]', "newell");
  await page.selectOption("#scene", "hard/cyclic_overlap.toml");
  await page.fill("#size", "");
  result = await renderWith();
  await clickPixel("color", 98, 44);
  const paintedPixel = nativeJson("hard/cyclic_overlap.toml", "98,44", ["--algo", "painter", "--variant", "newell"]);
  await page.click(`#quizChoices button:nth-child(${(await quizShown()).choices.findIndex((c) => names(c, paintedPixel.shows.name)) + 1})`);
  await page.click("#quizNext");
  const order = await quizShown();
  check(order.prompt === "Event 1: which piece does the painter paint first at this pixel?" && order.choices.length === 2 &&
        order.choices.some((c) => c.startsWith(`${paintedPixel.history[0].name}, 8.54104 away (the part of its triangle cut out by 1 plane)`)),
        `the painter's quiz asks which piece it paints first, each choice with its distance and whether it was cut (${order.choices.join(" | ")})`);
  await page.locator("#whyBox").screenshot({ path: join(out, "quiz-painter.png") });
  const painterQuiz = await takeQuiz(paintedPixel, 1, 0);
  check(painterQuiz.problems.length === 0 && painterQuiz.asked === 2 && (await text("#quizProgress")) === "2 of 2 predicted right; the whole answer:",
        `and the last piece, forced, is not asked (${painterQuiz.problems.join("; ") || painterQuiz.asked + " asked"})`);
  // Ray casting: at a BVH node the quiz asks what the traversal decides there.
  await page.selectOption("#algorithm", "ray_casting");
  await page.selectOption("#scene", "counters.toml");
  await page.fill("#size", "320x180");
  result = await renderWith();
  await clickPixel("color", 160, 90);
  let nodeQuestion = null;
  for (let asked = 0; asked < 10 && !nodeQuestion; ++asked) {
    const now = await quizShown();
    if (now.choices.length === 0) break;
    if (now.prompt.startsWith("What does the loop decide")) nodeQuestion = now;
    else {
      await page.click("#quizChoices button:nth-child(1)");
      await page.click("#quizNext");
    }
  }
  check(nodeQuestion !== null && nodeQuestion.context.includes("BVH node") && nodeQuestion.choices.includes("the nearer child first, the farther stacked") &&
        !nodeQuestion.choices.some((choice) => choice.startsWith("entered")),
        `ray casting's quiz asks what the traversal decides at a BVH node (${nodeQuestion ? nodeQuestion.choices.join(" | ") : "not asked"})`);
  await page.uncheck("#quizMode");
  await page.fill("#size", "");
  await page.dblclick("#color");

  // A line drawing answers along the edge nearest the pixel clicked, as hsr why --edge
  // X,Y does; an algorithm whose walk it does not follow, with the command line's line.
  await page.selectOption("#algorithm", "appel");
  await page.selectOption("#scene", "blocks.toml");
  await page.fill("#size", "320x240");
  result = await renderWith();
  const edgeAnswer = await clickPixel("color", 108, 123);
  const appelEdge = nativeEdge("blocks.toml", edgeAnswer.pixel, "appel");
  check(result.message === "" && edgeAnswer.shown === appelEdge && edgeAnswer.shown.includes("edge 2, the contour edge of \"slab\""),
        `a click on Appel's drawing answers along the edge nearest it, as hsr why --edge ${edgeAnswer.pixel} does`);
  const drawnEdge = await page.$eval("#color + .marker + svg.edge", (svg) => ({
    line: ["x1", "y1", "x2", "y2"].map((name) => Number(svg.querySelector("line").getAttribute(name))),
    changes: svg.querySelectorAll("circle.change").length,
  }));
  // blocks' edge 2 runs from (142.018, 111.719) to (74.226, 135.645), and the walk starts at its end (u = 1).
  check(Math.abs(drawnEdge.line[0] - 74.226) < 0.01 && Math.abs(drawnEdge.line[1] - 135.645) < 0.01 && Math.abs(drawnEdge.line[2] - 142.018) < 0.01 &&
        drawnEdge.changes === 3, `the edge is drawn over the drawing from where the walk starts, a ring at each of its 3 changes (${drawnEdge.line.join(", ")})`);
  await page.locator("#results .images figure").first().screenshot({ path: join(out, "edge.png") });
  const ringed = await page.$$eval(".marker:not([hidden])", (markers) => markers.map((m) => m.previousElementSibling.id));
  check(JSON.stringify(ringed) === '["color","error"]', `a line drawing's pixel is ringed on the drawing and its difference only, which have it (${ringed.join(", ")})`);
  await page.check("#quizMode");
  await clickPixel("color", 108, 123);
  const crossing = await quizShown();
  check(crossing.progress === "question 1 of 3" && crossing.prompt.includes("How does the edge's QI change?") &&
        crossing.choices.join(" | ") === "+1: it passes behind | -1: it comes out from behind",
        `quiz me on an edge: how its QI changes at each of the walk's 3 crossings (${crossing.prompt})`);
  await page.uncheck("#quizMode");
  // Roberts along the same edge: each body's test, as hsr why --edge prints it; a ring
  // where each of the two bodies that hide a part of it begins to.
  await page.selectOption("#algorithm", "roberts");
  result = await renderWith();
  const robertsAnswer = await clickPixel("color", 108, 123);
  const nativeRoberts = nativeEdge("blocks.toml", robertsAnswer.pixel, "roberts");
  const robertsRings = await page.$$eval("#color + .marker + svg.edge circle.change", (rings) => rings.length);
  await page.locator("#results").screenshot({ path: join(out, "edge-roberts.png") });
  check(result.message === "" && robertsAnswer.shown === nativeRoberts && robertsAnswer.shown.includes('body "ball": hides part of it') && robertsRings === 2,
        `a click on Roberts' drawing answers with its test of each body, as hsr why --edge ${robertsAnswer.pixel} does, a ring where each hidden part begins (${robertsRings})`);
  await page.check("#quizMode");
  await clickPixel("color", 108, 123);
  const body = await quizShown();
  check(body.progress === "question 1 of 4" && body.prompt === 'body "slab": what does the algorithm decide there?' &&
        body.choices.join(" | ") === "hidden by its own body (step 1) | not tested | ruled out by the minimax test | hides none of it | hides part of it",
        `quiz me on Roberts' edge: what the test of each body decided, among all Roberts declares (${body.progress}: ${body.prompt})`);
  // The floating horizon along the segment nearest the pixel: where it lies against the
  // horizons at its start and each column center, as hsr why --edge says; the quiz asks
  // each place among the places the algorithm declares.
  await page.selectOption("#algorithm", "floating_horizon");
  await page.selectOption("#scene", "ripple.toml");
  result = await renderWith();
  const horizonAnswer = await clickPixel("color", 160, 120);
  const nativeHorizon = nativeEdge("ripple.toml", horizonAnswer.pixel, "floating_horizon");
  const place = await quizShown();
  check(result.message === "" && horizonAnswer.shown === nativeHorizon && horizonAnswer.shown.includes("its start: above the upper horizon") &&
        place.prompt === "its start: what does the algorithm decide there?" &&
        place.choices.join(" | ") === "no curve drawn there yet | above the upper horizon | below the lower horizon | between the horizons | under the upper horizon",
        `a click on the floating horizon's drawing answers along the segment nearest it, as hsr why --edge ${horizonAnswer.pixel} does, and the quiz asks where it lies (${place.prompt})`);
  await page.uncheck("#quizMode");
  await page.fill("#size", "");

  await page.selectOption("#algorithm", "zbuffer");
  await page.selectOption('[id="zbuffer.depth-format"]', "unorm16");
  await page.selectOption("#scene", "hard/coplanar.toml");
  result = await renderWith();
  check(result.message === "" && Number((await text("#metrics")).match(/pixel error(\d+\.\d+)%/)?.[1]) > 0, "unorm16 on the coplanar case: a knob, and an error above zero");

  // Mine against the reference, in one view: the render's visible triangles, the
  // reference's in the same colours, the error map, and the two in turn.
  const differingPixels = (a, b) => page.evaluate(([a, b]) => {
    const data = (id) => { const c = document.getElementById(id); return c.getContext("2d").getImageData(0, 0, c.width, c.height).data; };
    const first = data(a), second = b === "errorPixels" ? window.hsrPage.state.module.errorPixels() : data(b);
    if (first.length !== second.length) return -1;
    let differing = 0;
    for (let p = 0; p < first.length; p += 4) differing += first[p] !== second[p] || first[p + 1] !== second[p + 1] || first[p + 2] !== second[p + 2];
    return differing;
  }, [a, b]);
  const showing = () => page.$eval("#against", (figure) => figure.dataset.showing);
  const measured = await page.evaluate(() => window.hsrPage.state.lastComparison.error);
  check(await differingPixels("error", "errorPixels") === 0 && (await showing()) === "difference", "the view against the reference opens on the error map");
  await page.click('#against button[data-view="mine"]');
  check(await differingPixels("error", "ids") === 0 && (await showing()) === "mine", "mine: the render's visible triangles, coloured as ids colours them");
  await page.click('#against button[data-view="reference"]');
  const unlikeMine = await differingPixels("error", "ids");
  check((await showing()) === "reference" && unlikeMine >= measured.wrongPixels && unlikeMine <= measured.wrongPixels + measured.ambiguousPixels,
        `the reference: it differs from mine at ${unlikeMine} pixels, the ${measured.wrongPixels} wrong ones and at most the ${measured.ambiguousPixels} ambiguous`);
  await page.locator("#against").screenshot({ path: join(out, "against-reference.png") });
  await page.click('#against button[data-view="blink"]');
  const seen = new Set();
  for (let sample = 0; sample < 6; ++sample, await page.waitForTimeout(230)) seen.add(await showing());
  check(seen.has("mine") && seen.has("reference") && seen.size === 2, `blink: mine and the reference in turn (${[...seen].join(", ")})`);
  await page.click('#against button[data-view="difference"]');
  await page.waitForTimeout(600);
  check(await differingPixels("error", "errorPixels") === 0 && (await showing()) === "difference", "and back to the difference, the blinking stopped");
  await page.click('#against button[data-view="mine"]');
  result = await renderWith();
  check(await differingPixels("error", "ids") === 0 && (await showing()) === "mine", "the view chosen stays chosen for the next render");
  await page.selectOption("#algorithm", "appel");
  await page.selectOption("#scene", "blocks.toml");
  result = await renderWith();
  const offered = await page.$$eval("#against .toggle button:not(:disabled)", (buttons) => buttons.map((b) => b.dataset.view));
  check(result.message === "" && JSON.stringify(offered) === '["difference"]' && (await showing()) === "difference" &&
        await differingPixels("error", "errorPixels") === 0, `a line drawing has only its difference against the reference (offered: ${offered.join(", ")})`);
  await page.selectOption("#algorithm", "zbuffer");
  await page.selectOption("#scene", "hard/coplanar.toml");

  await page.selectOption('[id="zbuffer.depth-format"]', "float32");
  await page.selectOption("#scene", "city.toml");
  await page.fill("#size", "480x270");
  await page.check('[id="use.frustum"]');
  await page.check('[id="use.occlusion"]');
  result = await renderWith();
  const counters = await text("#counters");
  check(result.message === "" && counters.includes("frustum") && counters.includes("occlusion"), "culling stages (frustum, then occlusion) before the z-buffer");
  await page.uncheck('[id="use.frustum"]');
  await page.uncheck('[id="use.occlusion"]');

  // The steps, recorded in the page and gone through in the steps page inside it: the
  // same steps as hsr render --steps records (their captions, and their pictures bit for
  // bit, labels too), each with the code that recorded it; a click on a pixel of a step's
  // picture answers with its history up to that step, as hsr why --step does.
  await page.selectOption("#algorithm", "zbuffer");
  await page.selectOption("#scene", "counters.toml");
  await page.fill("#size", "320x180");
  result = await renderWith();
  const recordInPage = async (every) => {
    await page.fill("#every", every);
    await page.click("#recordSteps");
    await page.waitForFunction(() => !document.getElementById("recordSteps").disabled);
    return { message: await text("#stepsMessage"), status: await text("#stepsStatus") };
  };
  const recordingStarted = Date.now();
  let recorded = await recordInPage("");
  console.log(`record its steps: the z-buffer on counters at 320x180, ${recorded.status} recorded and shown in ${((Date.now() - recordingStarted) / 1000).toFixed(2)} s`);
  const nativeSteps = join(out, "steps-native");
  rmSync(nativeSteps, { recursive: true, force: true });
  spawnSync(join(root, "build", "hsr"), ["render", "scenes/counters.toml", "--size", "320x180", "-o", join(out, "steps-native.png"), "--steps", nativeSteps], { cwd: root });
  const nativeCaptions = readFileSync(join(nativeSteps, "captions.txt"), "utf8").trimEnd().split("\n").map((line) => line.slice(5));
  const frame = page.frames().find((f) => f.parentFrame() === page.mainFrame());
  const stepShown = () => frame.evaluate(() => ({
    position: document.getElementById("position").textContent,
    caption: document.getElementById("caption").textContent,
    sourceTitle: document.getElementById("sourceTitle").textContent,
    marked: [...document.querySelectorAll("#code span.marked")].map((line) => line.textContent).join("\n"),
  }));
  const m = nativeCaptions.length;
  let now = await stepShown();
  check(recorded.message === "" && recorded.status === `${m} steps` && now.position === `step 1 of ${m}` && now.caption === nativeCaptions[0],
        `record its steps: the z-buffer's ${m} steps on counters, as hsr render --steps records them (${recorded.status}; ${now.position})`);
  const pictures = await page.evaluate(async (natives) => {
    const pixelsOf = async (blob) => {
      const bitmap = await createImageBitmap(blob);
      const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
      const context = canvas.getContext("2d");
      context.drawImage(bitmap, 0, 0);
      return context.getImageData(0, 0, bitmap.width, bitmap.height).data;
    };
    const differing = [];
    for (const [index, address] of window.hsrPage.stepPictures.addresses.entries()) {
      const mine = await pixelsOf(await (await fetch(address)).blob());
      const native = await pixelsOf(new Blob([Uint8Array.from(atob(natives[index]), (c) => c.charCodeAt(0))], { type: "image/png" }));
      if (mine.length !== native.length || mine.some((value, i) => value !== native[i])) differing.push(index + 1);
    }
    return { count: window.hsrPage.stepPictures.addresses.length, differing };
  }, nativeCaptions.map((_, index) => readFileSync(join(nativeSteps, `step-${String(index + 1).padStart(4, "0")}.png`)).toString("base64")));
  check(pictures.count === m && pictures.differing.length === 0,
        `every step's picture is the native one bit for bit, its labels too (${pictures.count} pictures; differing: ${pictures.differing.join(", ") || "none"})`);
  const captionsMatch = [];
  for (const [button, n] of [["next", 2], ["next", 3], ["previous", 2], ["last", m], ["first", 1]]) {
    await frame.click(`#${button}`);
    now = await stepShown();
    captionsMatch.push(now.position === `step ${n} of ${m}` && now.caption === nativeCaptions[n - 1]);
    if (n === m) check(now.sourceTitle.startsWith("recorded at web/hsr_web.cpp:") && now.marked.includes("recordFinishedStep("),
                       `the finished image, the last step, is recorded by the page's bridge, its lines shown (${now.sourceTitle})`);
  }
  check(captionsMatch.every(Boolean), `next, next, previous, last, first: each step and its caption as captions.txt has them (${captionsMatch.join(", ")})`);
  check(now.sourceTitle.startsWith("recorded at algorithms/zbuffer/") && now.marked.length > 0,
        `each step beside the code that recorded it, read from the site's copy of the suite (${now.sourceTitle})`);
  // Step 6, pixel (160, 90): the history up to the step.
  await frame.$eval("#slider", (slider) => { slider.value = "6"; slider.dispatchEvent(new Event("input")); });
  // A click at the whole CSS pixel (of the steps page's own coordinates: the frame sits at
  // a fraction of a pixel in this page's) nearest the pixel's center that lies in it.
  await frame.$eval("#picture", (picture, [x, y]) => {
    const box = picture.getBoundingClientRect(), scale = (box.width - 2 * picture.clientLeft) / picture.naturalWidth;
    const within = (start, n) => Math.min(Math.max(Math.round(start + (n + 0.5) * scale), Math.ceil(start + n * scale)), Math.ceil(start + (n + 1) * scale) - 1);
    picture.dispatchEvent(new MouseEvent("click", { bubbles: true, clientX: within(box.left + picture.clientLeft, x), clientY: within(box.top + picture.clientTop, y) }));
  }, [160, 90]);
  await frame.waitForFunction(() => !document.getElementById("whyAnswer").textContent.startsWith("asking") && document.getElementById("whyAnswer").textContent !== "");
  const answeredAtStep = await frame.evaluate(() => ({ title: document.getElementById("pixelTitle").textContent, answer: document.getElementById("whyAnswer").textContent }));
  const nativeAtStep = whyPrints("counters.toml", ["--size", "320x180", "--pixel", "160,90", "--step", "6"]);
  check(answeredAtStep.title === "Pixel (160, 90) up to step 6" && answeredAtStep.answer.split("\n").slice(1).join("\n").trim() === nativeAtStep,
        `a click on pixel (160, 90) of step 6's picture: its history up to step 6, as hsr why --step 6 prints it (${answeredAtStep.title})`);
  if (answeredAtStep.answer.split("\n").slice(1).join("\n").trim() !== nativeAtStep) console.log(`  page:\n${answeredAtStep.answer}\n  hsr why:\n${nativeAtStep}`);
  // README's figure, on a screen wide enough for the code to sit beside the picture.
  await page.setViewportSize({ width: 1900, height: 1150 });
  await page.locator("#stepsBox").screenshot({ path: join(out, "web-steps.png") });
  await page.setViewportSize({ width: 1400, height: 1000 });
  // --every as typed: a bad value is the command line's line; the page records again after it.
  recorded = await recordInPage("abc");
  const nativeEvery = spawnSync(join(root, "build", "hsr"), ["render", "scenes/counters.toml", "-o", join(out, "x.png"), "--steps", join(out, "steps-bad"), "--every", "abc"], { cwd: root, encoding: "utf8" });
  check(recorded.message === "hsr: error: --every: abc: expected a whole number from 0 to 999999999" && nativeEvery.status === 2 &&
        nativeEvery.stderr.trim() === `${recorded.message} (see --help)`, `--every abc: one line, the command line's (${recorded.message})`);
  // Every triangle's step at 640x360: refused as soon as the pictures would pass the
  // page's budget for them, not when the page runs out of memory.
  await page.fill("#size", "640x360");
  result = await renderWith();
  recorded = await recordInPage("1");
  check(/^hsr: error: --every 1: the steps would take more than 512 MiB of the page's memory \(\d+ recorded so far, 1286x360 pixels each\); expected a larger --every, or a smaller --size$/.test(recorded.message),
        `--every 1 at 640x360: one line, before the page runs out of memory (${recorded.message})`);
  await page.fill("#size", "320x180");
  result = await renderWith();
  recorded = await recordInPage("5");
  const everyFifth = spawnSync(join(root, "build", "hsr"), ["why", "scenes/counters.toml", "--size", "320x180", "--pixel", "1,1", "--every", "5", "--step", "999"], { cwd: root, encoding: "utf8" });
  check(recorded.message === "" && everyFifth.stderr.includes(`records ${Number(recorded.status.split(" ")[0])} steps here`),
        `and records again after it: every 5th step, as many as the command line's --every 5 (${recorded.status})`);
  // A line algorithm's steps, and the BSP painter's, whose tree the command line draws with Graphviz.
  await page.selectOption("#algorithm", "appel");
  await page.selectOption("#scene", "blocks.toml");
  result = await renderWith();
  recorded = await recordInPage("");
  check(recorded.message === "" && Number(recorded.status.split(" ")[0]) > 2, `Appel's steps on blocks (${recorded.status})`);
  await page.selectOption("#algorithm", "painter");
  await page.selectOption('[id="painter.variant"]', "bsp");
  result = await renderWith();
  recorded = await recordInPage("");
  const treeStep = await frame.evaluate(() => [...JSON.parse(document.getElementById("steps").textContent)].findIndex((step) => step.caption.startsWith("step 2: the BSP tree")));
  check(recorded.message === "" && Number(recorded.status.split(" ")[0]) > 2 && treeStep >= 0,
        `the BSP painter's steps, its tree's step with a picture saying Graphviz draws it on the command line (${recorded.status}; the tree at step ${treeStep + 1})`);
  await page.selectOption('[id="painter.variant"]', "newell");

  // Bad input: the command line's one line, and the page renders again afterwards.
  const nativeMessage = (files, scene, extra = []) => {
    const folder = join(out, "bad");
    mkdirSync(folder, { recursive: true });
    for (const [name, content] of Object.entries(files)) writeFileSync(join(folder, name), content);
    const run = spawnSync(join(root, "build", "hsr"), ["render", join(folder, scene), "-o", join(folder, "x.png"), ...extra], { encoding: "utf8" });
    return run.stderr.trim().replaceAll(`${folder}/`, "");
  };
  const badCases = [
    { what: "a broken TOML", files: { "broken.toml": "[camera\neye = [0, 0, 5]\n" } },
    { what: "a non-ASCII character outside a string", files: { "accent.toml": "a = [1\u00a7]\n" } },
    { what: "an OBJ with a bad face", files: { "bad.toml": '[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\n[[objects]]\nshape = "mesh"\nfile = "bad.obj"\n', "bad.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n" } },
  ];
  for (const bad of badCases) {
    const names = Object.keys(bad.files);
    await page.setInputFiles("#files", names.map((name) => ({ name, mimeType: "text/plain", buffer: Buffer.from(bad.files[name]) })));
    await page.waitForFunction(() => document.getElementById("message").textContent !== "" && !document.getElementById("render").disabled);
    const shown = await text("#message");
    const native = nativeMessage(bad.files, names[0]);
    check(shown.startsWith("hsr: error: ") && !shown.includes("\n"), `${bad.what}: one line (${shown})`);
    check(native === "" || shown === native, `${bad.what}: the same line as the command line's (${native})`);
  }
  await page.selectOption("#scene", "counters.toml");
  await page.fill("#size", "16384x16384");
  result = await renderWith();
  check(/^hsr: error: out of memory rendering 16384x16384 with \w+: the frame alone needs 3\.0 GiB/.test(result.message) &&
        result.message.endsWith("(a browser gives a page at most 2 GiB)"), `a size larger than a page's memory: ${result.message}`);
  await page.fill("#size", "100000x100000");
  result = await renderWith();
  check(result.message.startsWith("hsr: error: --size 100000x100000: ") && result.message.includes("16384"), `an absurd size: ${result.message}`);
  await page.fill("#size", "320x180");
  result = await renderWith();
  check(result.message === "" && result.status.includes("counters.toml, 320×180"), "and the page renders again afterwards");
  await page.screenshot({ path: join(out, "after-bad-input.png") });

  // The same bits as native.
  const only = full ? "" : "hard/";
  const randomScenes = full ? 100 : 10;
  const identityStarted = Date.now();
  const lines = (await page.evaluate(([o, r]) => window.hsrPage.identity(320, r, o), [only, randomScenes])).trim().split("\n");
  const expected = readFileSync(join(root, "tests", "identity", "expected.txt"), "utf8").trim().split("\n")
    .filter((line) => (line.startsWith("random/") ? Number(line.split(" ")[0].split("/")[1]) <= randomScenes : line.startsWith(only)));
  const differing = lines.filter((line, i) => line !== expected[i]);
  check(lines.length === expected.length && differing.length === 0,
        `the same bits as native: ${lines.length} renders in the page (${only || "every scene"}, ${randomScenes} random scenes; ${((Date.now() - identityStarted) / 1000).toFixed(0)} s), ${differing.length} differing`);
  for (const line of differing.slice(0, 10)) console.log(`  page:   ${line}\n  native: ${expected[lines.indexOf(line)]}`);
  check(consoleErrors.length === 0, `no error in the console${consoleErrors.length ? ": " + consoleErrors.join("; ") : ""}`);
} finally {
  await browser.close();
  server.kill();
}
checks.finish("the browser edition");
