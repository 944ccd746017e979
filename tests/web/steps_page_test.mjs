// The steps page (hsr render --steps DIR writes DIR/steps.html) in a real browser
// (Debian's chromium, headless), opened from the folder as a student opens it:
//   - first / previous / next / last, the slider, the keys and a link to a step each
//     show the step asked for: "step N of M", its caption as captions.txt has it, its
//     picture, the buttons that cannot go further disabled;
//   - every step's code is the algorithm's own line that recorded it, marked;
//   - play runs through the steps and pauses;
//   - a click on a pixel of a step's picture gives the hsr why command for its history
//     up to the step, which the native program answers with that step's caption;
//   - a scene whose names hold markup and a closing </script> shows them as text;
//   - a screenshot into out/web/steps.png (README's figure).
//   node tests/web/steps_page_test.mjs            (build/hsr must be built)
import { spawnSync } from "node:child_process";
import { copyFileSync, mkdirSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { pathToFileURL } from "node:url";
import { Checks, launchBrowser, openPage, root } from "./browser.mjs";

const checks = new Checks();
const check = (condition, what) => checks.check(condition, what);
const out = join(root, "out", "web");
mkdirSync(out, { recursive: true });

// Steps recorded by the native program, run from the suite's folder as README's commands
// are, into out/web/NAME/: the page's address and the captions.
function recordSteps(name, args) {
  const folder = join(out, name);
  rmSync(folder, { recursive: true, force: true });
  const run = spawnSync(join(root, "build", "hsr"), ["render", ...args, "-o", `out/web/${name}.png`, "--steps", `out/web/${name}`], { encoding: "utf8", cwd: root });
  if (run.status !== 0) throw new Error(`hsr render ${args.join(" ")} --steps failed: ${run.stderr}`);
  const captions = readFileSync(join(folder, "captions.txt"), "utf8").trimEnd().split("\n").map((line) => line.slice(5));
  return { url: pathToFileURL(join(folder, "steps.html")).href, captions };
}

// What the page shows now.
const shown = (page) => page.evaluate(() => ({
  position: document.getElementById("position").textContent,
  caption: document.getElementById("caption").textContent,
  picture: document.getElementById("picture").getAttribute("src"),
  loaded: document.getElementById("picture").complete && document.getElementById("picture").naturalWidth > 0,
  disabled: ["first", "previous", "next", "last"].filter((id) => document.getElementById(id).disabled),
  sourceTitle: document.getElementById("sourceTitle").textContent,
  marked: [...document.querySelectorAll("#code span.marked")].map((line) => ({ number: Number(line.dataset.line), text: line.textContent })),
  hash: location.hash,
}));

// The page shows step `n` (from 1) of `captions`, as it should.
async function expectStep(page, n, captions, how) {
  await page.waitForFunction(() => document.getElementById("picture").complete);
  const now = await shown(page);
  const m = captions.length;
  const disabled = [...(n === 1 ? ["first", "previous"] : []), ...(n === m ? ["next", "last"] : [])];
  check(now.position === `step ${n} of ${m}` && now.caption === captions[n - 1] && now.picture === `step-${String(n).padStart(4, "0")}.png` &&
        now.loaded && now.hash === `#step=${n}` && JSON.stringify(now.disabled) === JSON.stringify(disabled),
        `${how}: step ${n} of ${m} (${now.position}; "${now.caption.slice(0, 50)}"; ${now.picture}; disabled ${now.disabled.join(" ") || "none"})`);
  return now;
}

const browser = await launchBrowser();
try {
  const { page, consoleErrors } = await openPage(browser);
  // Clicks pixel (x, y) of the step's picture as shown (inside its border, at least one
  // CSS pixel a pixel), at the whole CSS pixel nearest its center that lies in it: a
  // mouse event's position is whole CSS pixels.
  const clickPicture = async (x, y) => {
    const [left, top, scale] = await page.$eval("#picture", (picture) => {
      const r = picture.getBoundingClientRect();
      return [r.left + picture.clientLeft, r.top + picture.clientTop, (r.width - 2 * picture.clientLeft) / picture.naturalWidth];
    });
    const within = (start, n) => {
      const from = start + n * scale, nearest = Math.round(from + scale / 2);
      return Math.min(Math.max(nearest, Math.ceil(from)), Math.ceil(from + scale) - 1);
    };
    await page.mouse.click(within(left, x), within(top, y));
  };

  // Newell's algorithm on the cyclic overlap: reorders and splits (newell.cpp), pieces
  // painted (painter.cpp), the finished image (cli/render.cpp).
  const newell = recordSteps("steps-newell", ["scenes/hard/cyclic_overlap.toml", "--algo", "painter", "--variant", "newell"]);
  const m = newell.captions.length;
  await page.goto(newell.url);
  await expectStep(page, 1, newell.captions, "opened");
  await page.click("#next");
  await page.click("#next");
  await expectStep(page, 3, newell.captions, "next twice");
  await page.click("#previous");
  await expectStep(page, 2, newell.captions, "previous");
  const last = await (async () => { await page.click("#last"); return expectStep(page, m, newell.captions, "last"); })();
  check(last.sourceTitle.startsWith("recorded at cli/render.cpp:"), `the finished image is recorded by the command: ${last.sourceTitle}`);
  await page.click("#first");
  await expectStep(page, 1, newell.captions, "first");
  await page.keyboard.press("ArrowRight");
  await expectStep(page, 2, newell.captions, "the right arrow key");
  await page.keyboard.press("End");
  await expectStep(page, m, newell.captions, "the End key");
  await page.keyboard.press("ArrowRight");
  await expectStep(page, m, newell.captions, "the right arrow key at the last step");
  await page.keyboard.press("Home");
  await expectStep(page, 1, newell.captions, "the Home key");
  await page.$eval("#slider", (slider, value) => { slider.value = value; slider.dispatchEvent(new Event("input")); }, "7");
  await expectStep(page, 7, newell.captions, "the slider at 7");
  await page.goto(`${newell.url}#step=5`);
  await page.reload();
  await expectStep(page, 5, newell.captions, "a link to step 5");
  await page.evaluate(() => { location.hash = "#step=9"; });
  await page.waitForFunction(() => document.getElementById("position").textContent.startsWith("step 9 "));
  await expectStep(page, 9, newell.captions, "#step=9 put into the open page's address");

  // Every step's code: the algorithm's line that recorded it, marked, in the file it names.
  const wrongSources = [];
  const files = new Set();
  await page.keyboard.press("Home");
  for (let n = 1; n <= m; ++n) {
    const now = await shown(page);
    const place = /^recorded at ((?:algorithms|cli)\/[\w/]+\.(?:cpp|hpp)):(\d+)$/.exec(now.sourceTitle);
    const markedText = now.marked.map((line) => line.text).join("\n");
    files.add(place?.[1]);
    if (!place || now.marked.length === 0 || now.marked[0].number !== Number(place[2]) || !/record\w*\(|->drawn\(/.test(markedText)) wrongSources.push(`${n}: ${now.sourceTitle}`);
    await page.keyboard.press("ArrowRight");
  }
  check(wrongSources.length === 0, `every step's code is the recording call, marked (${wrongSources.join("; ") || [...files].join(", ")})`);
  check(["algorithms/painter/newell.cpp", "algorithms/painter/painter.cpp", "cli/render.cpp"].every((file) => files.has(file)),
        "the reorders and splits from newell.cpp, the pieces from painter.cpp, the finished image from cli/render.cpp");

  // Play: on from the first step, then paused.
  await page.keyboard.press("Home");
  await page.click("#play");
  await page.waitForTimeout(1500);
  await page.click("#play");
  const paused = await shown(page);
  const at = Number(/^step (\d+) of/.exec(paused.position)[1]);
  await page.waitForTimeout(1000);
  check(at >= 2 && at < m && (await shown(page)).position === paused.position && (await page.textContent("#play")) === "play",
        `play went on to step ${at}, and pause stayed there`);
  await page.dblclick("#picture");
  check(await page.$eval("#picture", (picture) => picture.classList.contains("actual")), "a double click on the picture shows it at its actual size");
  await page.dblclick("#picture");

  // A click on a pixel of a step's picture: the hsr why command for that pixel up to the
  // step, which answers with the events before the step and the step's caption.
  const askAt = async (n, x, y) => {
    await page.goto(`${newell.url}#step=${n}`);
    await page.reload();
    await page.waitForFunction(() => document.getElementById("picture").complete);
    await clickPicture(x, y);
    return page.evaluate(() => ({ hidden: document.getElementById("pixel").hidden, title: document.getElementById("pixelTitle").textContent,
                                  command: document.getElementById("whyCommand").textContent, ring: !document.getElementById("ring").hidden }));
  };
  const middle = Math.ceil(m / 2);
  const asked = await askAt(middle, 98, 44);
  const expectedCommand = `./build/hsr why scenes/hard/cyclic_overlap.toml --algo painter --variant newell --pixel 98,44 --step ${middle}`;
  check(!asked.hidden && asked.ring && asked.title === `Pixel (98, 44) up to step ${middle}` && asked.command === expectedCommand,
        `a click on pixel (98, 44) at step ${middle} gives its command (${asked.command})`);
  const answered = spawnSync(asked.command.split(" ")[0], asked.command.split(" ").slice(1), { encoding: "utf8", cwd: root });
  check(answered.status === 0 && answered.stdout.includes(`up to step ${middle} of ${m}: ${newell.captions[middle - 1]}\n`) &&
        /pixel \(98, 44\): \d+ events? by step \d+ \(of \d+ in all\)/.test(answered.stdout) && answered.stdout.includes(`  by step ${middle} it shows `),
        `the command answers with the history up to step ${middle} and that step's caption${answered.status === 0 ? "" : ": " + answered.stderr}`);
  await page.click("#next");
  check((await page.textContent("#whyCommand")).endsWith(`--pixel 98,44 --step ${middle + 1}`), "the next step asks the same pixel up to that step");
  // A picture of panels side by side: a click on the second asks about the same pixel.
  const panels = await page.$eval("#picture", (picture) => picture.naturalWidth);
  if (panels > 2 * 200) {
    const second = await askAt(middle, 200 + 6 + 98, 44);
    check(second.command === expectedCommand, `a click on the second panel asks about the same pixel (${second.command})`);
  }

  // A picture that is not the render (the occluder map of the occlusion stage's first
  // step) asks nothing: no pixel, no ring; on the render's pictures the clicks ask again.
  const occlusion = recordSteps("steps-occlusion", ["scenes/city.toml", "--size", "320x180", "--cull", "occlusion"]);
  await page.goto(`${occlusion.url}#step=1`);
  await page.waitForFunction(() => document.getElementById("picture").complete);
  const map = await page.$eval("#picture", (picture) => [picture.naturalWidth, picture.naturalHeight, picture.classList.contains("asks")]);
  await clickPicture(100, 60);
  const onMap = await page.evaluate(() => ({ hidden: document.getElementById("pixel").hidden, ring: !document.getElementById("ring").hidden }));
  await page.keyboard.press("End");
  await page.waitForFunction(() => document.getElementById("picture").complete);
  await clickPicture(100, 60);
  const onImage = await page.evaluate(() => ({ hidden: document.getElementById("pixel").hidden, title: document.getElementById("pixelTitle").textContent }));
  check(occlusion.captions[0].includes("map") && map[0] !== 320 && !map[2] && onMap.hidden && !onMap.ring &&
        !onImage.hidden && onImage.title === `Pixel (100, 60) up to step ${occlusion.captions.length}`,
        `a click on the occluder map (${map[0]} x ${map[1]}, step 1) asks nothing; on the finished image it asks (${onImage.title})`);

  // Names with markup: shown as written, the page still working.
  const folder = join(out, "steps-markup-scene");
  mkdirSync(folder, { recursive: true });
  copyFileSync(join(root, "scenes", "hard", "cyclic_overlap.obj"), join(folder, "cyclic_overlap.obj"));
  const name = `</script><img src=x onerror="document.title='broken'">`;
  writeFileSync(join(folder, "scene.toml"), readFileSync(join(root, "scenes", "hard", "cyclic_overlap.toml"), "utf8")
    .replace('name = "third"', `name = ${JSON.stringify(name)}`));
  const markup = recordSteps("steps-markup", [join(folder, "scene.toml"), "--algo", "painter", "--variant", "newell"]);
  await page.goto(markup.url);
  const first = await expectStep(page, 1, markup.captions, "a scene whose names hold markup");
  check(first.caption.includes(name) && (await page.title()).startsWith("Steps: hsr render") && (await page.$$("img")).length === 1,
        "its names shown as text, nothing of them run or drawn");

  // README's figure: the z-buffer on counters at its sixth step.
  const zbuffer = recordSteps("steps-zbuffer", ["scenes/counters.toml", "--size", "320x180"]);
  await page.goto(`${zbuffer.url}#step=6`);
  await expectStep(page, 6, zbuffer.captions, "the z-buffer's steps");
  await page.setViewportSize({ width: 1300, height: 560 });
  await page.dblclick("#picture");  // at its actual size: a CSS pixel is one of its pixels
  await clickPicture(160, 90);
  const zbufferCommand = await page.textContent("#whyCommand");
  check(zbufferCommand === "./build/hsr why scenes/counters.toml --algo zbuffer --size 320x180 --pixel 160,90 --step 6",
        `the z-buffer's steps: a click asks about the pixel at the step shown (${zbufferCommand})`);
  await page.screenshot({ path: join(out, "steps.png") });
  check(consoleErrors.length === 0, `no error in the console${consoleErrors.length ? ": " + consoleErrors.join("; ") : ""}`);
} finally {
  await browser.close();
}
checks.finish("the steps page");
