#!/usr/bin/env bash
# A first look, from a fresh clone: install what the hsr program needs (scripts/setup.sh),
# build the program alone (no tests, no benchmarks: scripts/build.sh builds those), render
# every shipped scene into out/ (with the z-buffer, and as a line drawing by each line
# algorithm that takes the scene: Roberts on convex bodies, Appel on closed meshes, the
# floating horizon on the ripple), record two algorithms' steps (the z-buffer and Newell's
# painter) as animations, then run hsr compare's default study (every algorithm against
# the exact reference) into out/compare/ with its report.html, and say where everything is.
set -euo pipefail
cd "$(dirname "$0")/.."
started=$SECONDS
bash scripts/setup.sh
cmake --preset release -DHSR_BUILD_TESTS=OFF -DHSR_BUILD_BENCH=OFF >/dev/null
cmake --build --preset release -j"$(nproc)" --target hsr
echo "built build/hsr in $(( SECONDS - started )) s"
mkdir -p out/steps  # --steps makes its own folder, not the ones above it
first=yes
for scene in scenes/*.toml; do
  name=$(basename "$scene" .toml)
  ./build/hsr render "$scene" -o "out/$name.png" --ids "out/$name-ids.png" --depth "out/$name-depth.exr"
  echo "rendered $scene -> out/$name.png (ids: out/$name-ids.png, depth: out/$name-depth.exr)"
  if [ "$first" = yes ]; then
    echo "the first picture, out/$name.png, $(( SECONDS - started )) s after the start"
    first=no
  fi
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
echo "demo finished in $(( SECONDS - started )) s; next: coursework.md, and bash scripts/build.sh for the tests"
