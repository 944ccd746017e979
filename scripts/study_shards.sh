#!/usr/bin/env bash
# Runs hsr study occlusion-queries as N shards with GNU parallel (Debian package
# `parallel`), one per job slot, then merges them into one table and plot:
#
#   bash scripts/study_shards.sh N OUT [STUDY OPTIONS...]
#
# e.g. `bash scripts/study_shards.sh 8 out/queries --size 640x360`. Shard K writes
# OUT/shard-K; the merge writes OUT itself. Extra options go to every shard (not --out,
# --shard or --merge). Across machines, give parallel their names through
# PARALLEL_SSH_LOGINS (parallel's --sshlogin syntax, e.g. "2/alice@node1,2/alice@node2"):
# each must have the same checkout at the same path, built, and OUT on a shared disk.
set -euo pipefail
if [[ $# -lt 2 ]]; then
  echo "usage: bash scripts/study_shards.sh N OUT [STUDY OPTIONS...]" >&2
  exit 2
fi
shards=$1 out=$2
shift 2
cd "$(dirname "$0")/.."
hsr="$PWD/build/hsr"
remote=()
if [[ -n "${PARALLEL_SSH_LOGINS:-}" ]]; then
  remote=(--sshlogin "$PARALLEL_SSH_LOGINS" --workdir "$PWD")
fi
mkdir -p "$out"
seq 1 "$shards" | parallel --halt now,fail=1 "${remote[@]}" \
  "$hsr" study occlusion-queries --shard "{}/$shards" --out "$out/shard-{}" "$@" '>' "$out/shard-{}.log"
folders=()
for k in $(seq 1 "$shards"); do folders+=("$out/shard-$k"); done
"$hsr" study occlusion-queries --out "$out" --merge "${folders[@]}"
