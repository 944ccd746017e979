#!/usr/bin/env bash
# Set up, build with warnings as errors, and run the whole test suite (ctest, every
# label, two jobs at a time); then the unit and hard-case tests again under
# AddressSanitizer and UndefinedBehaviorSanitizer with floating-point exceptions trapped
# and the standard library's assertions on (scripts/sanitize.sh); then each fuzz target
# for 10 seconds under both sanitizers (scripts/fuzz.sh); then the other targets: the
# browser edition built into WebAssembly and tested in headless chromium, the same bits as
# native on the hard cases and 10 random scenes (scripts/web_test.sh), and beside its page
# tests an arm64 build under qemu-user against this machine's on every render at 48 pixels
# wide (scripts/cross.sh arm64 --quick). The benchmarks and the check that every header
# compiles on its own are not built (scripts/build.sh builds them). The debug preset
# (scripts/debug.sh: GCC at -Og, the same traps) is not run here: the sanitizer build
# traps the same exceptions, and a third build of everything took CI past 25 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
started=$SECONDS
lap() { echo "test.sh: $1 done, $(( (SECONDS - started) / 60 )) min $(( (SECONDS - started) % 60 )) s in"; }
# The benchmarks and the check that every header compiles on its own (156 translation
# units) are built by scripts/build.sh, every developer's build, not here: CI runs no
# benchmark, and their build is the time the other targets' checks take.
bash scripts/build.sh release -DHSR_WERROR=ON -DHSR_BUILD_BENCH=OFF -DHSR_STANDALONE_HEADERS=OFF
lap "release build"
ctest --preset release
lap "release tests"
# The same bits through the command line, fresh processes on one and two threads, ids and
# colour, every surface algorithm and Roberts on counters and the city (bench/scaling.sh
# small and once each; its full run is a benchmark).
bash bench/scaling.sh --scenes counters,city --threads 1,2 --runs 1 --size 480x270 --out out/scaling-ci \
  --algos reference,zbuffer,ray_casting,painter,warnock,watkins,weiler_atherton,abuffer,roberts > /dev/null
lap "the same bits on one and two threads"
bash scripts/sanitize.sh -DHSR_WERROR=ON
lap "sanitizer build and tests"
bash scripts/fuzz.sh 10
lap "fuzzing"
# The browser edition: built into WebAssembly and clicked through in headless Chromium,
# its renders checked against this machine's bit for bit. It is CI's other target: its
# core runs the portable paths arm64's does. arm64 under qemu-user and Windows under wine
# are checked by scripts/cross.sh (docs/portability.md): beside the page tests, arm64's
# quick check took the run past 40 minutes.
bash scripts/web_test.sh  # installs what it needs and builds the site first (scripts/web.sh)
lap "browser edition"
