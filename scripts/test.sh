#!/usr/bin/env bash
# Set up, build, and run the whole test suite (ctest, every label, two jobs at a time),
# then the unit and hard-case tests again under AddressSanitizer and
# UndefinedBehaviorSanitizer (scripts/sanitize.sh), then each fuzz target for 10 seconds
# under both (scripts/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j2
bash scripts/sanitize.sh
bash scripts/fuzz.sh 10
