#!/usr/bin/env bash
# Runs the fuzz targets (tests/fuzz: obj, scene, render) side by side under libFuzzer with
# AddressSanitizer and UndefinedBehaviorSanitizer for SECONDS seconds (default 20),
# starting from the seed corpus and every crash found before (tests/fuzz/regressions/).
# New inputs the fuzzer finds go to build-sanitize/fuzz/TARGET/, not to the checked-in
# corpus; a crash, a hang (one input over 10 s) or a leak stops that target's run and keeps
# the input in out/fuzz/TARGET/, the others run to their end, and the script fails. Each
# target's last line of statistics (executions, coverage) is printed.
#   scripts/fuzz.sh            20 s per target (CI: scripts/test.sh)
#   scripts/fuzz.sh 600        the long run before a release: 10 minutes per target
#   scripts/fuzz.sh 60 render  one target
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
targets=(obj scene render)
[ $# -gt 1 ] && targets=("${@:2}")

bash scripts/setup.sh tests >/dev/null
cmake --preset sanitize >/dev/null
cmake --build build-sanitize -j"$(nproc)" --target $(printf '%s_fuzz ' "${targets[@]}")
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The targets run side by side, each for SECONDS of wall time (on fewer cores than
# targets, each gets a share of them: fewer executions, the same time), then each
# reports in turn.
fuzz() {
  local target=$1 seeds=tests/fuzz/corpus/$1
  [ "$target" = render ] && seeds=tests/fuzz/corpus/scene
  local work=build-sanitize/fuzz/$target artifacts=out/fuzz/$target
  mkdir -p "$work" "$artifacts"
  local regressions=()
  [ -d "tests/fuzz/regressions/$target" ] && regressions=("tests/fuzz/regressions/$target")
  build-sanitize/tests/fuzz/${target}_fuzz -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
    -print_final_stats=1 -artifact_prefix="$artifacts/" "$work" "$seeds" "${regressions[@]}" >"$work.log" 2>&1
}
pids=()
for target in "${targets[@]}"; do
  echo "fuzz: $target for ${seconds} s"
  fuzz "$target" &
  pids+=($!)
done
failed=0
for i in "${!targets[@]}"; do
  target=${targets[$i]}
  log=build-sanitize/fuzz/$target.log
  if ! wait "${pids[$i]}"; then
    tail -n 60 "$log" || true
    echo "fuzz: $target FAILED; the input is in out/fuzz/$target/ (add it to tests/fuzz/regressions/$target/ once fixed)" >&2
    failed=1
    continue
  fi
  echo "fuzz: $target"
  { grep -E '^#[0-9]+.*(DONE|pulse)' "$log" | tail -n 1; grep -E 'stat::number_of_executed_units|stat::peak_rss_mb' "$log" | tr '\n' ' '; } || true
  echo
done
exit "$failed"
