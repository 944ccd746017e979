#!/usr/bin/env bash
# Regenerates the figures the READMEs show (images/figures/), from the current code.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
# The command outputs README quotes.
python3 scripts/readme_outputs.py
# The architecture: the layers and the pipeline's passes (README "Architecture").
dot -Tpng -Gdpi=96 images/figures/architecture.dot -o images/figures/architecture.png
mkdir -p images/figures/zbuffer
./build/hsr render scenes/dragons.toml --size 960x540 -o images/figures/dragons.png
for format in float32 reversed-float32 unorm24 unorm16; do
  ./build/hsr render scenes/hard/coplanar.toml --depth-format "$format" -o "images/figures/zbuffer/coplanar-$format.png"
done
# hsr compare's contact sheet on two scenes, and hsr sweep's depth-precision plot.
study=$(mktemp -d)
./build/hsr compare scenes/bunny.toml scenes/hard/coplanar.toml --out "$study" > /dev/null
cp "$study/contact_sheet.png" images/figures/compare.png
# Each algorithm's own steps (hsr render --steps), as the README's animations; and the
# occlusion stage's steps side by side: what it removed, its depth map, a pyramid level.
mkdir -p images/figures/steps
steps() {
  local name=$1
  shift
  ./build/hsr render "$@" -o "$study/$name.png" --steps "$study/steps-$name"
  cp "$study/steps-$name/steps.gif" "images/figures/steps/$name.gif"
}
steps zbuffer scenes/counters.toml --size 320x180 --every 100
steps newell scenes/hard/cyclic_overlap.toml --algo painter --variant newell --size 320x240
steps bsp scenes/hard/cyclic_overlap.toml --algo painter --size 320x240
steps ray_casting scenes/counters.toml --algo ray_casting --size 320x180 --every 12
steps floating_horizon scenes/ripple.toml --algo floating_horizon --size 400x300
steps appel scenes/blocks.toml --algo appel --size 400x300 --every 4
# Warnock: the subdivision after level 7 on the blocks (one frame of its steps), and
# what stopping at 4 and 16 pixels gets wrong; its knob swept on counters.
mkdir -p images/figures/warnock
steps warnock scenes/blocks.toml --algo warnock --size 480x360
cp "$study/steps-warnock/$(grep -m1 "level 7," "$study/steps-warnock/captions.txt" | cut -c1-4 | sed 's/^/step-/').png" \
  images/figures/warnock/subdivision.png
./build/hsr compare scenes/blocks.toml --algos warnock,warnock:smallest-window=4,warnock:smallest-window=16 --size 480x360 \
  --out "$study" > /dev/null
cp "$study/contact_sheet.png" images/figures/warnock/stops-blocks.png
./build/hsr sweep scenes/counters.toml --algo warnock --knob smallest-window=1,2,4,8,16 --threads 1 --repeat 7 \
  --out "$study" > /dev/null
cp "$study/sweep.png" images/figures/warnock/sweep-counters.png
# Watkins: a row of the blocks cut into spans (one frame of its steps), and what the
# split buys on the interpenetrating pair.
mkdir -p images/figures/watkins
steps watkins scenes/blocks.toml --algo watkins --size 480x360
cp "$study/steps-watkins/$(grep -m1 "row 206:" "$study/steps-watkins/captions.txt" | cut -c1-4 | sed 's/^/step-/').png" \
  images/figures/watkins/row-blocks.png
./build/hsr compare scenes/hard/interpenetrating.toml --algos watkins,watkins:split=halves,watkins:split=none --size 320x240 \
  --out "$study" > /dev/null
cp "$study/contact_sheet.png" images/figures/watkins/split-interpenetrating.png
# Weiler-Atherton: the blocks as its SVG draws them (rsvg-convert, from librsvg2-bin), the
# third clip polygon of its steps, and the steps.
mkdir -p images/figures/weiler_atherton
./build/hsr render scenes/blocks.toml --algo weiler_atherton --size 480x360 -o "$study/blocks.svg"
rsvg-convert "$study/blocks.svg" -o images/figures/weiler_atherton/polygons-blocks.png
steps weiler_atherton scenes/blocks.toml --algo weiler_atherton --size 480x360
cp "$study/steps-weiler_atherton/step-0003.png" images/figures/weiler_atherton/clip-blocks.png
# The A-buffer: the blocks' edges up close (the z-buffer, the A-buffer at 4 x 4 and at
# 8 x 8, each enlarged 4 times without smoothing), its steps, and its coverage error
# against time beside the supersampled z-buffer's (bench/antialiasing_bench, plotted).
mkdir -p images/figures/abuffer
./build/hsr render scenes/blocks.toml --size 480x360 -o "$study/edges-zbuffer.png"
./build/hsr render scenes/blocks.toml --size 480x360 --algo abuffer -o "$study/edges-4x4.png"
./build/hsr render scenes/blocks.toml --size 480x360 --algo abuffer --knob mask=8x8 -o "$study/edges-8x8.png"
oiiotool "$study/edges-zbuffer.png" --cut 80x60+180+150 --resize:filter=box 320x240 \
  "$study/edges-4x4.png" --cut 80x60+180+150 --resize:filter=box 320x240 \
  "$study/edges-8x8.png" --cut 80x60+180+150 --resize:filter=box 320x240 \
  --mosaic:pad=8 3x1 -o images/figures/abuffer/edges-blocks.png
steps abuffer scenes/counters.toml --algo abuffer --size 480x270
./build/bench/antialiasing_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
  --benchmark_format=csv > "$study/antialiasing.csv"
python3 - "$study" <<'PYTHON'
import csv, sys
study = sys.argv[1]
rows = [r for r in csv.DictReader(l for l in open(f"{study}/antialiasing.csv") if l.count(",") > 5) if r["name"].endswith("_median")]
for family in ("zbuffer", "abuffer"):
    with open(f"{study}/{family}.dat", "w") as out:
        for scene in ("counters", "trees", "dragons"):
            for r in rows:
                label = r["label"]
                if label.startswith(scene + " " + family) and "center" not in label:
                    out.write(f'{r["real_time"]} {r["error_mixed"]} "{label.split(" ", 1)[1]}"\n')
            out.write("\n\n")
PYTHON
gnuplot <<GNUPLOT
set terminal pngcairo size 900,520 font "DejaVu Sans,11"
set output "images/figures/abuffer/error-time.png"
set logscale xy
set xlabel "whole render, ms (320 x 180, one thread)"
set ylabel "coverage error on mixed pixels"
set key top right
set title "The A-buffer and the supersampled z-buffer: the same samples, the same error (counters, trees, dragons)"
plot "$study/zbuffer.dat" index 0 using 1:2 with linespoints lc rgb "#1f5fbf" pt 7 title "zbuffer 1, 2x2, 4x4, 8x8: counters", \
     "" index 1 using 1:2 with linespoints lc rgb "#1f5fbf" pt 5 title "trees", \
     "" index 2 using 1:2 with linespoints lc rgb "#1f5fbf" pt 9 title "dragons", \
     "$study/abuffer.dat" index 0 using 1:2 with linespoints lc rgb "#d04010" pt 7 title "abuffer 2x2, 4x4, 8x8: counters", \
     "" index 1 using 1:2 with linespoints lc rgb "#d04010" pt 5 title "trees", \
     "" index 2 using 1:2 with linespoints lc rgb "#d04010" pt 9 title "dragons"
GNUPLOT
./build/hsr render scenes/city.toml --cull frustum,occlusion:pyramid=on --size 480x270 --every 100000 -o "$study/occlusion.png" \
  --steps "$study/steps-occlusion"
frame() { echo "$study/steps-occlusion/step-$(grep -m1 "$1" "$study/steps-occlusion/captions.txt" | cut -c1-4).png"; }
oiiotool "$(frame "culling stage occlusion")" "$(frame "occluders' depth")" --resize 480x240 \
  "$(frame "pyramid level 3")" --resize 480x240 --mosaic:pad=8 3x1 -o images/figures/steps/occlusion.png
./build/hsr sweep scenes/hard/coplanar.toml --algo zbuffer \
  --knob depth-format=unorm16,unorm24,float32,reversed-float32 --repeat 5 --out "$study" > /dev/null
cp "$study/sweep.png" images/figures/sweep-coplanar-depth.png
# The A-buffer swept by what it buys: coverage error against time, per mask and depth rule.
./build/hsr sweep scenes/counters.toml --algo abuffer --knob mask=2x2,4x4,8x8 --knob depth=center,subsample \
  --size 480x270 --repeat 3 --out "$study" > /dev/null
cp "$study/sweep.png" images/figures/sweep-abuffer-masks.png
# Ray casting: the march's accuracy against time beside bvh, on trees and on the thin
# sheet; naive's and bvh's time against the triangle count.
mkdir -p images/figures/ray_casting
./build/hsr sweep scenes/trees.toml --algo ray_casting --size 640x360 --knob variant=bvh,march \
  --knob step=4%,1%,0.25% --knob refine=0,6 --repeat 3 --out "$study" > /dev/null
cp "$study/sweep.png" images/figures/ray_casting/sweep-trees.png
./build/hsr sweep scenes/hard/thin_sheet.toml --algo ray_casting --knob variant=bvh,march \
  --knob step=5%,1%,0.1%,0.001 --knob refine=0,6 --repeat 3 --out "$study" > /dev/null
cp "$study/sweep.png" images/figures/ray_casting/sweep-thin-sheet.png
./build/hsr sweep scenes/bunny.toml --algo ray_casting --variant naive --knob budget=1e11 --scale triangles \
  --size 64x48 --repeat 1 --out "$study" > /dev/null
cp "$study/scale_triangles.png" images/figures/ray_casting/scale-naive.png
./build/hsr sweep scenes/bunny.toml --algo ray_casting --scale triangles --size 64x48 --repeat 5 --out "$study" > /dev/null
cp "$study/scale_triangles.png" images/figures/ray_casting/scale-bvh.png
./build/hsr compare scenes/hard/thin_sheet.toml scenes/trees.toml --size 480x270 \
  --algos "ray_casting,ray_casting:variant=march,ray_casting:variant=march:refine=6" --out "$study" > /dev/null
cp "$study/contact_sheet.png" images/figures/ray_casting/compare.png
# The painter: the cyclic overlap and the interpenetrating pair for each variant, and
# each variant's time against the triangle count (up to its budget).
mkdir -p images/figures/painter
./build/hsr compare scenes/hard/cyclic_overlap.toml scenes/hard/interpenetrating.toml \
  --algos "painter:variant=sort,painter:variant=newell,painter:variant=bsp" --out "$study" > /dev/null
cp "$study/contact_sheet.png" images/figures/painter/hard-cases.png
./build/hsr sweep scenes/bunny.toml --algo painter --variant sort --scale triangles --repeat 1 --threads 1 --out "$study" > /dev/null
cp "$study/scale_triangles.png" images/figures/painter/scale-sort.png
./build/hsr sweep scenes/bunny.toml --algo painter --variant newell --knob budget=1e10 --scale triangles --repeat 1 \
  --threads 1 --out "$study" > /dev/null
cp "$study/scale_triangles.png" images/figures/painter/scale-newell.png
./build/hsr sweep scenes/bunny.toml --algo painter --variant bsp --scale triangles --repeat 1 --threads 1 --out "$study" > /dev/null
cp "$study/scale_triangles.png" images/figures/painter/scale-bsp.png
# Hidden lines: Roberts with hidden lines dashed, its junction lines, Appel's QI on the
# torus, Appel on the dragon.
mkdir -p images/figures/lines
./build/hsr render scenes/blocks.toml --algo roberts --line-style hidden -o images/figures/lines/blocks-roberts.png
./build/hsr render scenes/hard/box_junctions.toml --algo roberts --line-style hidden --size 480x360 \
  -o images/figures/lines/junctions-roberts.png
./build/hsr render scenes/hard/torus.toml --algo appel --line-style qi --size 480x360 -o images/figures/lines/torus-qi.png
./build/hsr render scenes/dragon.toml --algo appel --knob surfaces=any --size 960x540 -o images/figures/lines/dragon-appel.png
# Appel against Open CASCADE's HLRBRep_PolyAlgo (bench/occt_peer; about two minutes for the
# dragon): the two drawings overlaid, and Open CASCADE's misses against the exact line
# reference on the dragon and on the city merged into one mesh.
./build/bench/occt_peer --out "$study/occt-dragon" > /dev/null
./build/bench/occt_peer --size 560x530 --out "$study/occt-city" scenes/hard/merged_city.toml > /dev/null
oiiotool "$study/occt-dragon/overlay.png" --cut 560x530+325+145 "$study/occt-dragon/occt_errors.png" --cut 560x530+325+145 \
  "$study/occt-city/occt_errors.png" --mosaic:pad=8 3x1 -o images/figures/lines/occt-against-appel.png
# The floating horizon: the ripple as rows and as a mesh, its lessons as error maps, the
# sweep at 1280 wide, and gnuplot's hidden3d beside it (bench/gnuplot_peer keeps both).
mkdir -p images/figures/floating_horizon
./build/hsr render scenes/ripple.toml --algo floating_horizon -o "$study/rows.png"
./build/hsr render scenes/ripple.toml --algo floating_horizon --knob mesh=on -o "$study/mesh.png"
oiiotool "$study/rows.png" "$study/mesh.png" --mosaic 2x1 -o images/figures/floating_horizon/ripple.png
./build/hsr compare scenes/ripple.toml scenes/hard/fh_below_first.toml --size 480x360 --repeat 1 \
  --algos "floating_horizon,floating_horizon:samples=5%:interpolate=off,floating_horizon:lower=off" --out "$study" > /dev/null
cp "$study/contact_sheet.png" images/figures/floating_horizon/lessons.png
./build/hsr sweep scenes/ripple.toml --algo floating_horizon --size 1280x960 --knob columns=10%,25%,100%,200% \
  --knob samples=2%,5%,10%,25%,100% --knob interpolate=on,off --repeat 3 --threads 1 --out "$study" > /dev/null
cp "$study/sweep.png" images/figures/floating_horizon/sweep-ripple-1280.png
./build/bench/gnuplot_peer --runs 5 --out "$study" > /dev/null
oiiotool "$study/ripple40_gnuplot.png" "$study/ripple40_hsr.png" --ch R,G,B "$study/ripple100_gnuplot.png" "$study/ripple100_hsr.png" --ch R,G,B \
  --mosaic 2x2 -o images/figures/floating_horizon/gnuplot-side-by-side.png
# Culling: the two wrong variants on the scenes built to show them, and the
# culling-combinations study's plot (about 90 s).
mkdir -p images/figures/culling
./build/hsr render scenes/hard/cull_off_center.toml -o "$study/right.png"
./build/hsr render scenes/hard/cull_off_center.toml --cull backface:view-direction -o "$study/wrong.png"
oiiotool "$study/right.png" "$study/wrong.png" --mosaic:pad=8 2x1 -o images/figures/culling/view-direction.png
./build/hsr render scenes/hard/cull_big_floor.toml --cull frustum:triangle -o "$study/right.png"
./build/hsr render scenes/hard/cull_big_floor.toml --cull frustum:any-vertex -o "$study/wrong.png"
oiiotool "$study/right.png" "$study/wrong.png" --mosaic:pad=8 2x1 -o images/figures/culling/any-vertex.png
./build/hsr study culling-combos --threads 1 --out "$study" > /dev/null
cp "$study/culling_combos.png" images/figures/culling/culling-combos.png
# Occlusion culling: the walkthrough (about 2 minutes), the hierarchical-Z resolution
# and the occluder fraction.
./build/hsr study occlusion-walkthrough --out "$study" > /dev/null
cp "$study/occlusion_walkthrough.png" images/figures/culling/occlusion_walkthrough.png
./build/hsr study hzb-resolution --threads 1 --out "$study" > /dev/null
cp "$study/hzb_resolution.png" images/figures/culling/hzb_resolution.png
./build/hsr study occluder-fraction --threads 1 --out "$study" > /dev/null
cp "$study/occluder_fraction.png" images/figures/culling/occluder_fraction.png
# Occlusion queries: the survey's walkthrough, 2,000 positions (about 3 minutes).
./build/hsr study occlusion-queries --out "$study" > /dev/null
cp "$study/occlusion_queries.png" images/figures/culling/occlusion_queries.png
cp "$study/occlusion_queries_frames.png" images/figures/culling/occlusion_queries_frames.png
# Cells, portals and visible sets: the indoor study's table, its walk, and the map.
./build/hsr study indoor --out "$study" > /dev/null
for plot in indoor indoor_frames indoor_map; do cp "$study/$plot.png" "images/figures/culling/$plot.png"; done
# The indoor level from its own camera, down the hall, drawn after portal culling.
./build/hsr render scenes/study/indoor.toml --cull frustum,portals:narrowing=polygon --size 640x360 -o images/figures/culling/indoor_view.png
# Effects: the showcase with each effect added in turn and the time of each pass, and
# the shadow map's resolution x bias against exact shadow rays.
mkdir -p images/figures/effects
./build/hsr study effects --threads 1 --out "$study" > /dev/null
cp "$study/effects_steps.png" images/figures/effects/steps.png
cp "$study/effects.png" images/figures/effects/passes.png
./build/hsr study shadow-map --out "$study" > /dev/null
cp "$study/shadow_map.png" images/figures/effects/shadow_map.png
rm -r "$study"
# The browser edition's page after its first render, as its test leaves it (README "In the
# browser"): the site built, served and clicked through in headless chromium; and the
# steps page and hsr compare's report.html as their tests leave them.
bash scripts/web_test.sh > /dev/null
cp out/web/page.png images/figures/web.png
cp out/web/why.png images/figures/web-why.png  # a pixel asked why about (README "Asking why")
cp out/web/quiz.png images/figures/web-quiz.png  # quiz me: predict, then reveal (README "Asking why")
cp out/web/steps.png images/figures/steps-page.png  # the steps page (README "Watching an algorithm work")
cp out/web/web-steps.png images/figures/web-steps.png  # the steps in the browser edition (README "In the browser")
cp out/web/report.png images/figures/report.png     # hsr compare's report.html (README "report.html")
# hsr grade's feedback page, as its test leaves it (README "Grading"): a submission
# without a depth test, graded and opened in headless chromium.
build/tests/grading_tests --gtest_filter=FeedbackPage.* > /dev/null
cp build/tests/output/grading/overdrawn-report/screenshot.png images/figures/grade-feedback.png
# The speed-up of every algorithm's visibility pass against threads (README "On more
# cores"): a machine's own figure, so it changes with the machine that runs this.
bash bench/scaling.sh > /dev/null  # its progress, and any image differing between counts, on stderr
cp out/scaling/speedup.png images/figures/scaling.png
echo "figures are in images/figures/"
