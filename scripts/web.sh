#!/usr/bin/env bash
# The browser edition: builds the core, every algorithm, the culling stages, the exact
# reference and the pipeline into WebAssembly with Debian's emscripten (no emscripten
# "ports": nothing is downloaded), single-threaded, and lays out a static site in
# web/dist/: index.html, app.js, quiz.js, style.css, hsr_web.js and .wasm, the shipped
# scenes and models, scenes.json (each scene's files), and under src/ the suite's code
# (algorithms/, renderer/, pipeline/ and this bridge), whose lines the steps page shows beside each step
# (fetched only for the files that recorded the steps shown). Serve it with any static
# file server:
#   python3 -m http.server -d web/dist     then open http://localhost:8000
#   bash scripts/web.sh            the site
#   bash scripts/web.sh --node     also hsr_identity for Node.js, the same-bits check without
#                                  a browser: node build-web/tests/identity/hsr_identity.js scenes
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh web  # emscripten, and the header-only libraries the core is read with
# Debian's emscripten runs its JavaScript optimizer with Node.js, which finds Debian's
# acorn only when told where Debian keeps Node.js modules.
export NODE_PATH=/usr/share/nodejs
targets=(hsr_web)
[ "${1:-}" = --node ] && targets+=(hsr_identity)
emcmake cmake -S . -B build-web -DCMAKE_BUILD_TYPE=Release -DHSR_CORE_ONLY=ON -DCMAKE_CXX_FLAGS="-fwasm-exceptions" >/dev/null
cmake --build build-web -j"$(nproc)" --target "${targets[@]}"

dist=web/dist
rm -rf "$dist"
mkdir -p "$dist"
cp web/index.html web/app.js web/quiz.js web/style.css build-web/web/hsr_web.js build-web/web/hsr_web.wasm "$dist/"
# The shipped scenes (the study levels aside: too large for a page) and the models they
# name, and the list of each scene's files, the scene first.
python3 - "$dist" <<'PYTHON'
import json, os, shutil, sys, tomllib
dist = sys.argv[1]
scenes = []
for folder, _, files in sorted(os.walk("scenes")):
    if os.path.basename(folder) == "study":
        continue
    for name in sorted(files):
        if not name.endswith(".toml"):
            continue
        path = os.path.join(folder, name)
        needed = [path]
        with open(path, "rb") as scene:
            for obj in tomllib.load(scene).get("objects", []):
                if "file" in obj:
                    needed.append(os.path.normpath(os.path.join(folder, obj["file"])))
        for file in needed:
            os.makedirs(os.path.join(dist, os.path.dirname(file)), exist_ok=True)
            shutil.copyfile(file, os.path.join(dist, file))
        scenes.append({"name": os.path.relpath(path, "scenes"), "files": needed})
with open(os.path.join(dist, "scenes.json"), "w") as out:
    json.dump({"scenes": scenes}, out, indent=1)
print(f"{len(scenes)} scenes")
PYTHON
# The code the steps are recorded in, as the steps page reads it beside a native build.
find algorithms renderer pipeline web -name '*.cpp' -o -name '*.hpp' | grep -v '^web/dist/' | while read -r file; do
  mkdir -p "$dist/src/$(dirname "$file")"
  cp "$file" "$dist/src/$file"
done
size() { stat -c %s "$1"; }
echo "web/dist: hsr_web.wasm $(( $(size "$dist/hsr_web.wasm") / 1024 )) KiB ($(( $(gzip -9c "$dist/hsr_web.wasm" | wc -c) / 1024 )) KiB gzipped), hsr_web.js $(( $(size "$dist/hsr_web.js") / 1024 )) KiB"
echo "serve it: python3 -m http.server -d $dist"
