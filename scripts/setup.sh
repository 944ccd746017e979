#!/usr/bin/env bash
# Installs what hsr needs from Debian's repositories when any of it is missing, in sets:
#   scripts/setup.sh                what building and running the hsr program needs (the demo)
#   scripts/setup.sh tests          that, and what the tests, the benchmarks and the figures need
#   scripts/setup.sh tests arm64    that, and the arm64 cross-compiler and qemu-user (scripts/cross.sh)
#   scripts/setup.sh tests windows  that, and MinGW-w64 and wine (scripts/cross.sh windows)
#   scripts/setup.sh web            that, and emscripten and Node.js (scripts/web.sh)
#   scripts/setup.sh npm            npm, for the browser test (scripts/web_test.sh asks for it
#                                   only where Node.js came without it)
# Idempotent: a machine that already has every package runs no apt-get at all.
# Runs as root (as on a fresh Debian 12 machine); otherwise through sudo when there is one.
set -euo pipefail

program=(
  build-essential cmake pkg-config
  libglm-dev                   # vectors and matrices
  libopenimageio-dev           # EXR depth, GIF steps, contact sheets, hsr diff (loaded on use)
  libpng-dev                   # the PNGs every render writes, without OpenImageIO's start-up cost
  libtinyobjloader-dev         # OBJ meshes
  libtomlplusplus-dev          # TOML scenes
  libcli11-dev                 # the hsr command line
  gnuplot-nox                  # hsr sweep's and the studies' plots
  graphviz                     # dot: the BSP tree in the painter's steps
  fonts-dejavu-core            # labels on hsr compare's contact sheet and on the steps' pictures
)
tests=(
  libgtest-dev libgmock-dev    # the tests
  libgmp-dev                   # the tests: GMP's rationals, the oracle the exact arithmetic is checked against
  python3                      # scripts/readme_outputs.py: the documents' quoted outputs, checked by a test
  chromium                     # tests: report.html loaded in a real browser, headless
  clang libclang-rt-14-dev     # the sanitizer build (scripts/sanitize.sh)
  libbenchmark-dev             # bench/
  hyperfine                    # bench/startup.sh: how long a command takes, start to finish
  libosmesa6-dev               # the Mesa peer benchmark (bench/ only)
  libembree-dev                # the Embree peer benchmark (bench/ only)
  libocct-modeling-algorithms-dev  # the Open CASCADE hidden-line peer (bench/occt_peer only);
  libocct-visualization-dev        # Debian ships OCCT 7.6's NCollection_AliasedArray.hxx
                                   # (which Poly_Triangulation.hxx includes) in this package
  openimageio-tools            # oiiotool: scripts/figures.sh lays figures side by side
  librsvg2-bin                 # rsvg-convert: scripts/figures.sh draws Weiler-Atherton's SVG as a PNG
)

arm64=(g++-aarch64-linux-gnu qemu-user)
windows=(g++-mingw-w64-x86-64-posix wine64)
web=(emscripten binaryen nodejs node-acorn)
npm=(npm)  # the browser test's playwright-core, where Node.js came without npm (Debian's does)

packages=("${program[@]}")
for set in "$@"; do
  case "$set" in
    program) ;;
    tests) packages+=("${tests[@]}") ;;
    arm64) packages+=("${arm64[@]}") ;;
    windows) packages+=("${windows[@]}") ;;
    web) packages+=("${web[@]}") ;;
    npm) packages+=("${npm[@]}") ;;
    *) echo "setup: unknown set '$set'; expected program, tests, arm64, windows, web or npm" >&2; exit 2 ;;
  esac
done

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
