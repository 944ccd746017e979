#!/usr/bin/env bash
# Set up, build with warnings as errors, and run the whole test suite (ctest, every
# label, two jobs at a time); then the unit and hard-case tests again under
# AddressSanitizer and UndefinedBehaviorSanitizer with floating-point exceptions trapped
# and the standard library's assertions on (scripts/sanitize.sh); then each fuzz target
# for 10 seconds under both sanitizers (scripts/fuzz.sh). The debug preset
# (scripts/debug.sh: GCC at -Og, the same traps) is not run here: the sanitizer build
# traps the same exceptions, and a third build of everything took CI past 25 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh release -DHSR_WERROR=ON
ctest --preset release
bash scripts/sanitize.sh -DHSR_WERROR=ON
bash scripts/fuzz.sh 10
