#!/usr/bin/env bash
# The main job on the built-in default: set up, build, render every shipped scene into
# out/ (with the z-buffer, and as a line drawing by each line algorithm that takes the
# scene: Roberts on convex bodies, Appel on closed meshes, the floating horizon on the
# ripple), record two algorithms' steps (the z-buffer and Newell's painter) as
# animations, then run hsr compare's default study (every algorithm against the exact
# reference) into out/compare/ with its report.html, and say where everything is.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out/steps  # --steps makes its own folder, not the ones above it
for scene in scenes/*.toml; do
  name=$(basename "$scene" .toml)
  ./build/hsr render "$scene" -o "out/$name.png" --ids "out/$name-ids.png" --depth "out/$name-depth.exr"
  echo "rendered $scene -> out/$name.png (ids: out/$name-ids.png, depth: out/$name-depth.exr)"
  for algorithm in roberts appel floating_horizon; do
    # Exit status 2 is hsr refusing the scene (its one-line reason is shown); anything
    # else that fails stops the demo.
    status=0
    reason=$(./build/hsr render "$scene" --algo "$algorithm" -o "out/$name-$algorithm.svg" 2>&1 >/dev/null) || status=$?
    case $status in
      0) echo "drew $scene with $algorithm -> out/$name-$algorithm.svg" ;;
      2) echo "  $algorithm does not draw $scene: ${reason#hsr: error: }" ;;
      *) echo "$reason" >&2; exit "$status" ;;
    esac
  done
done
./build/hsr render scenes/counters.toml --size 640x360 -o out/counters-steps.png --steps out/steps/zbuffer 2> /dev/null
./build/hsr render scenes/hard/cyclic_overlap.toml --algo painter --variant newell -o out/newell-steps.png --steps out/steps/newell
echo "recorded the z-buffer's and Newell's steps -> out/steps/zbuffer/steps.gif, out/steps/newell/steps.gif"
./build/hsr compare --out out/compare
echo "images are in $(pwd)/out; the study is out/compare/report.html (its contact sheet: out/compare/contact_sheet.png)"
