#!/usr/bin/env bash
# Regenerates the figures the READMEs show (images/figures/), from the current code.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p images/figures/zbuffer
./build/hsr render scenes/dragons.toml --size 960x540 -o images/figures/dragons.png
for format in float32 reversed-float32 unorm24 unorm16; do
  ./build/hsr render scenes/hard/coplanar.toml --depth-format "$format" -o "images/figures/zbuffer/coplanar-$format.png"
done
# hsr compare's contact sheet on two scenes, and hsr sweep's depth-precision plot.
study=$(mktemp -d)
./build/hsr compare scenes/bunny.toml scenes/hard/coplanar.toml --out "$study" > /dev/null
cp "$study/contact_sheet.png" images/figures/compare.png
./build/hsr sweep scenes/hard/coplanar.toml --algo zbuffer \
  --knob depth-format=unorm16,unorm24,float32,reversed-float32 --repeat 5 --out "$study" > /dev/null
cp "$study/sweep.png" images/figures/sweep-coplanar-depth.png
rm -r "$study"
echo "figures are in images/figures/"
