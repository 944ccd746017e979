// The browser edition's z-buffer against the native textbook loop, on the same scene, the
// same size and one thread: the WebAssembly module of web/dist (scripts/web.sh) run by
// Node.js (the V8 engine Chromium runs it with), and build/hsr with --knob path=scalar (the
// loop WebAssembly runs; the native fast path is x86-only). Each side renders ROUNDS
// times, alternating, and the medians of the visibility pass (the z-buffer's own time, as
// hsr compare splits it) are compared.
//   node bench/web_speed.mjs [SCENE] [WxH] [ROUNDS]     default: counters.toml 1280x720 11
import { execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { createRequire } from "node:module";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const root = join(dirname(fileURLToPath(import.meta.url)), "..");
const [scene = "counters.toml", size = "1280x720", rounds = "11"] = process.argv.slice(2);
const dist = join(root, "web", "dist");

const require = createRequire(import.meta.url);
const createHsr = require(join(dist, "hsr_web.js"));
// The module as a page gets it, but from the disk (Node.js's fetch takes no file paths).
const module = await createHsr({ wasmBinary: readFileSync(join(dist, "hsr_web.wasm")) });
const { scenes } = JSON.parse(readFileSync(join(dist, "scenes.json"), "utf8"));
const shipped = scenes.find((s) => s.name === scene);
if (!shipped) throw new Error(`${scene}: not a shipped scene of web/dist/scenes.json`);
for (const file of shipped.files) {
  const folders = file.split("/").slice(0, -1);
  for (let i = 1; i <= folders.length; ++i) {
    const folder = "/hsr/" + folders.slice(0, i).join("/");
    if (!module.FS.analyzePath(folder).exists) module.FS.mkdir(folder);
  }
  module.FS.writeFile("/hsr/" + file, readFileSync(join(dist, file)));
}

const scratch = mkdtempSync(join(tmpdir(), "hsr-web-speed-"));
const median = (values) => [...values].sort((a, b) => a - b)[values.length >> 1];
const wasm = [], native = [];
for (let round = 0; round < Number(rounds); ++round) {
  const result = JSON.parse(module.render({ scene: "/hsr/" + shipped.files[0], algorithm: "zbuffer", knobs: "", cull: "", size, reference: false }));
  if (result.message) throw new Error(result.message);
  wasm.push(result.visibilityMs);
  const stats = execFileSync(join(root, "build", "hsr"), ["render", join(root, "scenes", scene), "--size", size, "--threads", "1", "--knob", "path=scalar", "--stats", "-o", join(scratch, "image.png")],
                             { encoding: "utf8", stdio: ["ignore", "pipe", "pipe"] });
  const visibility = stats.match(/pass: visibility time\s+([\d.]+) ms/);
  if (!visibility) throw new Error(`no visibility time in hsr --stats:\n${stats}`);
  native.push(Number(visibility[1]));
}
rmSync(scratch, { recursive: true });
const w = median(wasm), n = median(native);
console.log(`${scene} ${size}, one thread, median of ${rounds}: the z-buffer's visibility pass ${w.toFixed(1)} ms in WebAssembly (Node.js ${process.version}), ` +
            `${n.toFixed(1)} ms native textbook loop (build/hsr --knob path=scalar): WebAssembly at ${(n / w).toFixed(2)} of native speed`);
