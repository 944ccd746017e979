#!/usr/bin/env bash
# Builds the unit and hard-case tests (not the hsr program, which none of them runs) with
# AddressSanitizer and UndefinedBehaviorSanitizer (clang, the "sanitize" preset, in
# build-sanitize/) and runs them under the sanitizers. Any report fails the test it
# happens in: undefined behaviour aborts (-fno-sanitize-recover), as do memory errors and
# leaks. The same run traps
# floating-point exceptions (tests/floating_point_traps.hpp) with the standard library's
# assertions on, as the debug preset does; -ffp-exception-behavior=maytrap keeps clang
# from computing a division the code chose to skip (by default it assumes nothing
# traps). Left out: the golden images and the line algorithms' sweep over every shipped
# scene (3.5 minutes under the sanitizers, half of this run), which run the same code
# the hard cases do and run in the suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh sanitize "$@"
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:check_initialization_order=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --preset sanitize
