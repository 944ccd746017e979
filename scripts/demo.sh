#!/usr/bin/env bash
# The main job on the built-in default: set up, build, render every shipped scene with
# the z-buffer into out/, then run hsr compare's default study (every algorithm against
# the exact reference) into out/compare/, and say where everything is.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
for scene in scenes/*.toml; do
  name=$(basename "$scene" .toml)
  ./build/hsr render "$scene" -o "out/$name.png" --ids "out/$name-ids.png" --depth "out/$name-depth.exr"
  echo "rendered $scene -> out/$name.png (ids: out/$name-ids.png, depth: out/$name-depth.exr)"
done
./build/hsr compare --out out/compare
echo "images are in $(pwd)/out; the study's contact sheet is out/compare/contact_sheet.png"
