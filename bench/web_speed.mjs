// The browser edition's z-buffer against the native textbook loop, on the same scene, the
// same size and one thread: the WebAssembly module of web/dist (scripts/web.sh) run by
// Node.js (the V8 engine Chromium runs it with), and build/hsr compare with --algos
// zbuffer:path=scalar (the loop WebAssembly runs; the native fast path is x86-only). Each
// side warms up (hsr compare renders once; WebAssembly five times, below), then renders
// ROUNDS times, and the medians of the visibility pass (the z-buffer's own time, as hsr
// compare splits it) are compared.
//   node bench/web_speed.mjs [SCENE] [WxH] [ROUNDS]     default: counters.toml 1280x720 21
import { execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { createRequire } from "node:module";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const root = join(dirname(fileURLToPath(import.meta.url)), "..");
const [scene = "counters.toml", size = "1280x720", rounds = "21"] = process.argv.slice(2);
const dist = join(root, "web", "dist");

const require = createRequire(import.meta.url);
const createHsr = require(join(dist, "hsr_web.js"));
// The module as a page gets it, but from the disk (Node.js's fetch takes no file paths).
const module = await createHsr({ wasmBinary: readFileSync(join(dist, "hsr_web.wasm")) });
const { scenes } = JSON.parse(readFileSync(join(dist, "scenes.json"), "utf8"));
const shipped = scenes.find((s) => s.name === scene);
if (!shipped) throw new Error(`${scene}: not a shipped scene of web/dist/scenes.json`);
for (const file of shipped.files) {
  let folder = "";
  for (const name of ["hsr", ...file.split("/").slice(0, -1)]) {
    folder += "/" + name;
    if (!module.FS.analyzePath(folder).exists) module.FS.mkdir(folder);
  }
  module.FS.writeFile("/hsr/" + file, readFileSync(join(dist, file)));
}

const median = (values) => [...values].sort((a, b) => a - b)[values.length >> 1];

// WebAssembly: five renders to warm up (V8 compiles a function first with its baseline
// compiler and again, optimized, once it is hot), then ROUNDS timed.
const kWarmUp = 5;
const wasm = [];
for (let round = 0; round < kWarmUp + Number(rounds); ++round) {
  const result = JSON.parse(module.render({ scene: "/hsr/" + shipped.files[0], algorithm: "zbuffer", knobs: "", cull: "", size }));
  if (result.message) throw new Error(result.message);
  if (round >= kWarmUp) wasm.push(result.visibilityMs);
}

// Native: hsr compare does the same (a warm-up, then ROUNDS timed) and writes the median.
const scratch = mkdtempSync(join(tmpdir(), "hsr-web-speed-"));
execFileSync(join(root, "build", "hsr"), ["compare", join(root, "scenes", scene), "--algos", "zbuffer:path=scalar", "--size", size, "--threads", "1",
                                          "--repeat", rounds, "--out", scratch], { stdio: "ignore" });
// Its table also holds the reference, which it measures every algorithm against.
const [header, ...rows] = readFileSync(join(scratch, "results.csv"), "utf8").trim().split("\n").map((line) => line.split(","));
const row = rows.find((cells) => cells[header.indexOf("algorithm")] === "zbuffer");
const native = Number(row[header.indexOf("visibility_median_ms")]);
rmSync(scratch, { recursive: true });

const w = median(wasm);
console.log(`${scene} ${size}, one thread, median of ${rounds} after warming up: the z-buffer's visibility pass ${w.toFixed(1)} ms in WebAssembly ` +
            `(Node.js ${process.version}), ${native.toFixed(1)} ms native textbook loop (hsr compare --algos zbuffer:path=scalar): ` +
            `WebAssembly at ${(native / w).toFixed(2)} of native speed`);
