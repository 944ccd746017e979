#!/usr/bin/env bash
# Installs what is missing (scripts/setup.sh), then configures and builds hsr in build/
# (Release, every core). Safe to run again: both steps do only what is left to do.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
