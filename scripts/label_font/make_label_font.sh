#!/usr/bin/env bash
# Regenerates renderer/steps/label_font_glyphs.inc, the label font the step pictures are
# labelled in, from DejaVu Sans drawn by OpenImageIO (Debian's libopenimageio-dev and
# fonts-dejavu-core, which scripts/setup.sh installs). Run it only to change the font:
# the table is checked in, so that every target draws the same labels without a font
# library.
set -euo pipefail
cd "$(dirname "$0")/../.."
program=$(mktemp)
trap 'rm -f "$program"' EXIT
g++ -std=c++20 -O1 -o "$program" scripts/label_font/make_label_font.cpp $(pkg-config --cflags --libs OpenImageIO)
"$program" >renderer/steps/label_font_glyphs.inc.new
mv renderer/steps/label_font_glyphs.inc.new renderer/steps/label_font_glyphs.inc
echo "renderer/steps/label_font_glyphs.inc: $(grep -c '^    {' renderer/steps/label_font_glyphs.inc) glyphs"
