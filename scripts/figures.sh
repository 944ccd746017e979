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
echo "figures are in images/figures/"
