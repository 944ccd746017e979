#!/usr/bin/env bash
# Rebuilds the seed corpus (tests/fuzz/corpus/) from the shipped scenes and the hard
# cases. The fuzz targets read a scene as if it were scenes/fuzz.toml, so a hard case's
# models get their folder: file = "torus.obj" becomes file = "hard/torus.obj". Scenes of
# the 100,000-triangle models (bunny, dragon) are left out: each input would take a
# second to load, and the fuzzer learns nothing from their size.
set -euo pipefail
cd "$(dirname "$0")/../.."
corpus=tests/fuzz/corpus
rm -rf "$corpus"
mkdir -p "$corpus/scene" "$corpus/obj"
for scene in scenes/*.toml scenes/study/*.toml scenes/hard/*.toml; do
  grep -q 'bunny.obj\|dragon_100k.obj' "$scene" && continue
  name=$(echo "${scene#scenes/}" | tr / -)
  case "$scene" in
    scenes/hard/*) sed -E 's|^(file *= *")([^"/]+\.obj")|\1hard/\2|' "$scene" >"$corpus/scene/$name" ;;
    *) cp "$scene" "$corpus/scene/$name" ;;
  esac
done
cp scenes/hard/*.obj models/tree.obj models/counter.obj "$corpus/obj/"
echo "corpus: $(ls "$corpus/scene" | wc -l) scenes, $(ls "$corpus/obj" | wc -l) OBJ files"
