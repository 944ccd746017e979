#!/usr/bin/env bash
# Compares two builds of one Google Benchmark program on a noisy machine: A and B run at
# the same time, one on each of the first two cores (swapped every round), so that
# whatever else loads the machine loads both alike, and each round gives the ratio
# B / A of their times. Prints every round and the geometric mean of the ratios.
#
#   bash scripts/paired_bench.sh A B FILTER [ROUNDS]
#   e.g. git worktree add /tmp/before HEAD~1, build its bench/ there, then
#   bash scripts/paired_bench.sh /tmp/before/build/bench/occlusion_bench \
#        build/bench/occlusion_bench 'occluders/center/1920x1080' 6
#
# The two share the memory bus and the last-level cache, so both run slower than alone:
# read the ratio, not the times. Needs taskset (util-linux) and two cores.
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: paired_bench.sh A B FILTER [ROUNDS]" >&2
  exit 2
fi
a=$1 b=$2 filter=$3 rounds=${4:-6}
for program in "$a" "$b"; do
  [ -x "$program" ] || { echo "paired_bench.sh: $program: not an executable program" >&2; exit 2; }
done
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# The time of the first benchmark FILTER names, in the program's own unit (the header
# lines of Google Benchmark's report start with a capital or a space).
time_of() { awk '$1 ~ /^[a-z]/ && NF >= 3 { print $2; exit }' "$1"; }

for round in $(seq "$rounds"); do
  core_a=$((round % 2)) core_b=$(((round + 1) % 2))
  taskset -c "$core_a" "$a" --benchmark_filter="$filter" --benchmark_min_time=1 > "$scratch/a" 2> /dev/null &
  taskset -c "$core_b" "$b" --benchmark_filter="$filter" --benchmark_min_time=1 > "$scratch/b" 2> /dev/null &
  wait
  echo "$(time_of "$scratch/a") $(time_of "$scratch/b")"
done | awk -v filter="$filter" '
  NF < 2 { failed = 1; exit 1 }
  { ratio = $2 / $1; printf "round %d: A %s  B %s  B/A %.3f\n", NR, $1, $2, ratio; sum += log(ratio) }
  END {
    if (failed) { print "paired_bench.sh: no benchmark of both programs matched the filter " filter > "/dev/stderr"; exit 1 }
    printf "geometric mean of B/A over %d rounds: %.3f\n", NR, exp(sum / NR)
  }'
