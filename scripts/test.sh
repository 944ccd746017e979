#!/usr/bin/env bash
# Set up, build with warnings as errors, and run the whole test suite (ctest, every
# label, two jobs at a time); then the unit and hard-case tests again in the debug build
# with floating-point exceptions trapped (scripts/debug.sh), and under AddressSanitizer
# and UndefinedBehaviorSanitizer (scripts/sanitize.sh); then each fuzz target for 10
# seconds under both (scripts/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh release -DHSR_WERROR=ON
ctest --preset release
bash scripts/debug.sh -DHSR_WERROR=ON
bash scripts/sanitize.sh -DHSR_WERROR=ON
bash scripts/fuzz.sh 10
