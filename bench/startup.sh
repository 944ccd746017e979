#!/usr/bin/env bash
# How long hsr takes as a command, start to finish: `hsr --help`, `hsr list`, a render of
# the cube, and the same render also writing its depth as OpenEXR (the one of the four
# that loads OpenImageIO), each 20 times after 3 warm-ups (hyperfine, no shell in
# between), median and range in ms.
#   bash bench/startup.sh                  # the build in build/
#   bash bench/startup.sh OTHER/hsr        # and another binary beside it, interleaved
# Pass another build's hsr to compare two builds in one run (ratios, not figures across runs).
set -euo pipefail
cd "$(dirname "$0")/.."
binaries=(build/hsr "$@")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
commands=()
for hsr in "${binaries[@]}"; do
  [ -x "$hsr" ] || { echo "startup.sh: $hsr: not an executable (bash scripts/build.sh builds build/hsr)" >&2; exit 2; }
  commands+=("$hsr --help" "$hsr list" "$hsr render scenes/cube.toml -o $out/cube.png"
             "$hsr render scenes/cube.toml -o $out/cube.png --depth $out/depth.exr")
done
hyperfine --shell=none --warmup 3 --runs 20 --style none --export-json "$out/times.json" "${commands[@]}" > /dev/null
python3 - "$out/times.json" "$out" <<'PY'
import json, sys
print("| command | median ms | min–max ms |")
print("| --- | --- | --- |")
for result in json.load(open(sys.argv[1]))["results"]:
    times = [1000 * t for t in result["times"]]
    command = result["command"].replace(sys.argv[2] + "/", "")
    print(f"| `{command}` | {result['median'] * 1000:.1f} | {min(times):.1f}–{max(times):.1f} |")
PY
