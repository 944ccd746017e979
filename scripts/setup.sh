#!/usr/bin/env bash
# Installs hsr's build dependencies from Debian's repositories when any is missing.
# Idempotent: a machine that already has every package runs no apt-get at all.
# Runs as root (as on a fresh Debian 12 machine); otherwise through sudo when there is one.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libglm-dev                   # vectors and matrices
  libopenimageio-dev           # EXR depth, image comparison, contact sheets, goldens (loaded on use)
  libpng-dev                   # the PNGs every render writes, without OpenImageIO's start-up cost
  libtinyobjloader-dev         # OBJ meshes
  libtomlplusplus-dev          # TOML scenes
  libcli11-dev                 # the hsr command line
  libgmp-dev                   # exact rational arithmetic in the reference
  gnuplot-nox                  # hsr sweep's plots; the floating horizon's peer (bench/gnuplot_peer)
  openimageio-tools            # oiiotool: scripts/figures.sh lays figures side by side
  graphviz                     # dot: the BSP tree in the painter's steps; scripts/figures.sh draws the architecture
  librsvg2-bin                 # rsvg-convert: scripts/figures.sh draws Weiler-Atherton's SVG as a PNG
  python3                      # scripts/readme_outputs.py: README's quoted outputs, checked by a test
  fonts-dejavu-core            # labels on hsr compare's contact sheet and on the steps' pictures
  chromium                     # tests: report.html loaded in a real browser, headless
  libgtest-dev libgmock-dev    # tests
  clang libclang-rt-14-dev     # the sanitizer build (scripts/sanitize.sh)
  libbenchmark-dev             # bench/
  hyperfine                    # bench/startup.sh: how long a command takes, start to finish
  libosmesa6-dev               # the Mesa peer benchmark (bench/ only)
  libembree-dev                # the Embree peer benchmark (bench/ only)
  libocct-modeling-algorithms-dev  # the Open CASCADE hidden-line peer (bench/occt_peer only);
  libocct-visualization-dev        # Debian ships OCCT 7.6's NCollection_AliasedArray.hxx
                                   # (which Poly_Triangulation.hxx includes) in this package
)

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
