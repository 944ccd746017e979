#!/usr/bin/env bash
# A snapshot of what hsr renders, to prove a refactoring changed no bit: every shipped
# scene and hard case, each algorithm and the variants the goldens cover, at one small
# size, with the ids, the depth's pixels (or the drawing) and the counters --stats prints
# (the times left out). Writes OUT/manifest.txt, one line per file with its SHA-256, and the
# files beside it; two snapshots are the same bits when their manifests are equal:
#   bash scripts/render_snapshot.sh out/before build-before/hsr
#   bash scripts/render_snapshot.sh out/after
#   diff out/before/manifest.txt out/after/manifest.txt && echo "the same bits"
# A configuration that refuses a scene (exit status 2: a budget, a line algorithm on an
# open mesh) records its one-line reason instead, which must not change either.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: render_snapshot.sh OUT [HSR]}
hsr=${2:-./build/hsr}
size=${SNAPSHOT_SIZE:-192x108}
mkdir -p "$out"
configurations=(
  "zbuffer" "zbuffer --knob path=scalar" "zbuffer --variant scanline" "zbuffer --depth-format unorm16"
  "ray_casting" "ray_casting --variant march" "painter" "painter --variant newell" "painter --variant sort"
  "warnock" "watkins" "weiler_atherton" "abuffer" "reference" "roberts" "appel" "floating_horizon")
for scene in scenes/*.toml scenes/hard/*.toml; do
  name=$(echo "${scene#scenes/}" | tr / _ | sed 's/\.toml$//')
  for configuration in "${configurations[@]}"; do
    read -r algorithm knobs <<<"$configuration"
    stem="$out/$name--$(echo "$configuration" | tr ' =' '__')"
    case $algorithm in
      roberts | appel | floating_horizon) outputs=(-o "$stem.svg") ;;
      *) outputs=(-o "$stem.png" --ids "$stem-ids.png" --depth "$stem-depth.exr") ;;
    esac
    status=0
    # shellcheck disable=SC2086  # the knobs are words
    "$hsr" render "$scene" --algo "$algorithm" $knobs --size "$size" --threads 2 "${outputs[@]}" --stats \
      >"$stem.stats" 2>"$stem.stderr" || status=$?
    grep -v ' ms$' "$stem.stats" >"$stem.counters" || true
    rm "$stem.stats"
    # An EXR holds the time it was written: its pixels' hash stands in for it.
    if [ -f "$stem-depth.exr" ]; then
      oiiotool --hash "$stem-depth.exr" | grep 'SHA-1' >"$stem-depth.pixels"
      rm "$stem-depth.exr"
    fi
    echo "exit $status" >>"$stem.stderr"
  done
done
(cd "$out" && find . -type f ! -name manifest.txt | sort | xargs sha256sum) >"$out/manifest.txt"
echo "$(wc -l <"$out/manifest.txt") files in $out/manifest.txt"
