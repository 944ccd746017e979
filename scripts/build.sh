#!/usr/bin/env bash
# Installs what is missing (scripts/setup.sh tests), then configures and builds one of
# the CMake presets (CMakePresets.json) with every core: release by default, in build/,
# with the tests and the benchmarks.
#   scripts/build.sh                          the release build (build/)
#   scripts/build.sh debug                    -Og, floating-point traps in the tests (build-debug/)
#   scripts/build.sh release -DHSR_WERROR=ON  any further arguments go to the configure step
# Safe to run again: each step does only what is left to do. (The demo, scripts/demo.sh,
# builds the hsr program alone in the same folder; this builds the rest beside it.)
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
[ $# -gt 0 ] && shift
bash scripts/setup.sh tests
# The demo switched the tests and benchmarks off in build/'s cache, and scripts/test.sh
# the benchmarks and the standalone headers; switch them back on (the debug and sanitize
# presets leave those out themselves).
everything=(-DHSR_BUILD_TESTS=ON)
[ "$preset" = release ] && everything+=(-DHSR_BUILD_BENCH=ON -DHSR_STANDALONE_HEADERS=ON)
cmake --preset "$preset" "${everything[@]}" "$@" >/dev/null
cmake --build --preset "$preset" -j"$(nproc)"
