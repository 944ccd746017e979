#!/usr/bin/env bash
# The main job on the built-in default: set up, build, and render every shipped scene
# with the z-buffer into out/, then say where the images are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
for scene in scenes/*.toml; do
  name=$(basename "$scene" .toml)
  ./build/hsr render "$scene" -o "out/$name.png" --ids "out/$name-ids.png" --depth "out/$name-depth.exr"
  echo "rendered $scene -> out/$name.png (ids: out/$name-ids.png, depth: out/$name-depth.exr)"
done
echo "images are in $(pwd)/out"
