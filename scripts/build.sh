#!/usr/bin/env bash
# Installs what is missing (scripts/setup.sh), then configures and builds one of the
# CMake presets (CMakePresets.json) with every core: release by default, in build/.
#   scripts/build.sh                          the release build (build/)
#   scripts/build.sh debug                    -Og, floating-point traps in the tests (build-debug/)
#   scripts/build.sh release -DHSR_WERROR=ON  any further arguments go to the configure step
# Safe to run again: each step does only what is left to do.
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
[ $# -gt 0 ] && shift
bash scripts/setup.sh
cmake --preset "$preset" "$@" >/dev/null
cmake --build --preset "$preset" -j"$(nproc)"
