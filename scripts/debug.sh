#!/usr/bin/env bash
# Builds the debug preset (-Og with the standard library's assertions, in build-debug/)
# and runs the unit and hard-case tests with floating-point exceptions trapped: an
# invalid operation, a division by zero or an overflow anywhere fails the test it
# happens in (tests/floating_point_traps.hpp). CI (scripts/test.sh) traps the same
# exceptions in the sanitizer build instead; this is GCC's view of them, at -Og, for
# stepping through a trap in a debugger.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh debug "$@"
ctest --preset debug
