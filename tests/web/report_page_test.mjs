// hsr compare's report.html in a real browser (Debian's chromium, headless), opened from
// its folder as a student opens it:
//   - per scene, the scatter of error against time (a point per surface configuration)
//     and a card per configuration, the exact reference first;
//   - a picture enlarged at 4x, pixels as squares; a click on a pixel names the pixel under
//     the pointer and gives the hsr why command for it, which runs and answers for that pixel;
//   - a card's "its steps" gives the command that records them, which writes steps.html;
//   - each README link leads to a file that is there;
//   - the table leads with the key columns, the rest shown on asking;
//   - a screenshot into out/web/report.png (README's figure).
//   node tests/web/report_page_test.mjs            (build/hsr must be built)
import { spawnSync } from "node:child_process";
import { existsSync, mkdirSync, readFileSync, rmSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";
import { Checks, launchBrowser, openPage, root } from "./browser.mjs";

const checks = new Checks();
const check = (condition, what) => checks.check(condition, what);
const out = join(root, "out", "web");
const folder = join(out, "report");
mkdirSync(out, { recursive: true });
rmSync(folder, { recursive: true, force: true });
// hsr run from the suite's folder, as README's commands are; the commands the page gives too.
const hsr = (command) => spawnSync("bash", ["-c", `./build/${command}`], { encoding: "utf8", cwd: root });
const compared = hsr(`hsr compare scenes/counters.toml scenes/hard/coplanar.toml --algos zbuffer,painter:variant=sort,abuffer --size 320x180 --repeat 1 --out out/web/report`);
if (compared.status !== 0) throw new Error(`hsr compare failed: ${compared.stderr}`);
const gallery = JSON.parse(readFileSync(join(folder, "gallery.json"), "utf8"));

const browser = await launchBrowser();
try {
  const { page, consoleErrors } = await openPage(browser, { width: 1400, height: 900 });
  await page.goto(pathToFileURL(join(folder, "report.html")).href);
  const scenes = await page.$$eval("#gallery section.scene", (sections) => sections.map((section) => ({
    heading: section.querySelector("h2").textContent,
    points: section.querySelectorAll("svg.scatter g.point").length,
    cards: [...section.querySelectorAll("article.card")].map((card) => card.querySelector("h3").textContent.trim()),
  })));
  check(scenes.length === 2 && scenes[0].heading === "scenes/counters.toml" && scenes[1].heading === "scenes/hard/coplanar.toml",
        `a section per scene, named from the suite's folder (${scenes.map((s) => s.heading).join(", ")})`);
  check(scenes.every((scene) => scene.cards.length === 4 && scene.cards[0] === "1. the exact reference" && scene.points === 4),
        `the reference and three configurations, a card and a point each (${scenes[0].cards.join("; ")})`);

  // Enlarged, a pixel clicked: the command it gives asks about that very pixel.
  const wrong = gallery.scenes[1].entries.findIndex((entry) => entry.wrongPixels > 0);
  await page.click(`#card-1-${wrong + 1} figure:nth-child(2) img`);
  await page.click('#zoom [data-scale="4"]');
  await page.waitForFunction(() => document.getElementById("zoomImage").complete);
  const shownWidth = await page.$eval("#zoomImage", (image) => image.getBoundingClientRect().width);
  check(Math.round(shownWidth) === 4 * 320, `at 4x the error map is ${Math.round(shownWidth)} pixels wide, four to a pixel`);
  const [x, y] = [201, 97];
  await page.click("#zoomImage", { position: { x: 4 * x + 2, y: 4 * y + 2 } });
  const said = await page.textContent("#zoomPixel");
  const command = await page.textContent("#zoomPixel code");
  check(said.startsWith(`pixel (${x}, ${y}).`) && command.endsWith(`--pixel ${x},${y}`), `a click names the pixel under the pointer: ${said}`);
  const answered = hsr(command);
  check(answered.status === 0 && answered.stdout.includes(`pixel (${x}, ${y})`), `and its command runs and answers for it: ${command}`);
  await page.screenshot({ path: join(out, "report-zoom.png") });
  await page.keyboard.press("Escape");
  check(await page.$eval("#zoom", (zoom) => zoom.hidden), "Escape puts the enlarged picture away");

  // The steps: the command a card gives records them.
  await page.click("#card-0-2 .links a:text('its steps')");
  const stepsCommand = await page.textContent("#card-0-2 p.links:not([hidden]) code");
  const stepsFolder = join(out, "report-steps");
  rmSync(stepsFolder, { recursive: true, force: true });
  const recorded = hsr(stepsCommand.replace(/ -o \S+/, ` -o ${join(out, "report-steps.png")}`).replace(/--steps \S+/, `--steps ${stepsFolder}`));
  check(recorded.status === 0 && existsSync(join(stepsFolder, "steps.html")), `"its steps" gives a command that records them: ${stepsCommand}`);
  const readmes = await page.$$eval("#gallery .links a", (links) => links.filter((link) => link.textContent === "README").map((link) => link.getAttribute("href")));
  const missing = readmes.filter((link) => !existsSync(join(folder, link)));
  check(readmes.length === 8 && missing.length === 0, `every card's README is there (${readmes.length}; ${[...new Set(readmes)].join(", ")})`);

  // The table: the key columns, the others on asking.
  const visible = () => page.$$eval("table.sortable th", (cells) => cells.filter((cell) => cell.offsetParent !== null).map((cell) => cell.textContent));
  const key = await visible();
  check(JSON.stringify(key) === JSON.stringify(["scene", "algorithm", "knobs", "visibility_median_ms", "pixel_error", "wrong_pixels", "coverage_error", "line_error"]),
        `the table leads with the key columns (${key.join(", ")})`);
  await page.click("label.columns input");
  check((await visible()).length > key.length + 10, "and shows every column on asking");
  await page.click("label.columns input");

  await page.evaluate(() => window.scrollTo(0, 0));
  await page.screenshot({ path: join(out, "report.png") });
  check(consoleErrors.length === 0, `no error in the console${consoleErrors.length ? ": " + consoleErrors.join("; ") : ""}`);
} finally {
  await browser.close();
}
checks.finish("the report page");
