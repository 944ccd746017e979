// Bad input through the hsr command: one line on stderr saying what, where and what
// was expected; exit status 2; no output file, not even a partial one.
#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>

#include "renderer/image/frame.hpp"
#include "renderer/image/pfm.hpp"
#include "test_support.hpp"

namespace hsr {
namespace {

struct Case {
  std::string name;
  std::string arguments;  // after "hsr COMMAND"; OUT stands for the output path (or folder)
  std::string message;    // must appear in the error line
  std::string command = "render";
};

void PrintTo(const Case& c, std::ostream* out) { *out << c.name; }

// Every test process writes these files when it starts (the cases are built then), while
// other processes of the same suite may be reading them: write a temporary file and
// rename it over the old one, so that a reader sees one whole file or the other.
std::string write(const std::string& name, const std::string& text) {
  const auto path = test::outputPath(name);
  const auto temporary = test::outputPath(name + "." + std::to_string(getpid()));
  std::ofstream(temporary) << text;
  std::filesystem::rename(temporary, path);
  return path.string();
}

const std::string kCamera = "[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\n";

std::string meshScene(const std::string& name, const std::string& obj) {
  write(name + ".obj", obj);
  return write(name + ".toml", kCamera + "[[objects]]\nshape = \"mesh\"\nfile = \"" + name + ".obj\"\n");
}

class BadInput : public testing::TestWithParam<Case> {};

TEST_P(BadInput, OneLineExitTwoNoFile) {
  const Case& c = GetParam();
  const auto output = test::outputPath("bad-" + c.name + ".png");
  std::filesystem::remove(output);
  std::string arguments = c.arguments;
  if (const auto at = arguments.find("OUT"); at != std::string::npos) arguments.replace(at, 3, output.string());
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " " + c.command + " " + arguments);
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_EQ(result.output.rfind("hsr: error: ", 0), 0u) << result.output;
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
  EXPECT_NE(result.output.find(c.message), std::string::npos) << "expected \"" << c.message << "\" in: " << result.output;
  EXPECT_FALSE(std::filesystem::exists(output));
  // Nor a temporary one (other tests running at the same time may have their own here).
  const std::string partial = partialFilePrefix(output);
  for (const auto& entry : std::filesystem::directory_iterator(output.parent_path()))
    EXPECT_NE(entry.path().filename().string().rfind(partial, 0), 0u) << entry.path();
}

const std::string kCube = std::string(HSR_SOURCE_DIR) + "/scenes/cube.toml";
const std::string kGoldenCube = std::string(HSR_SOURCE_DIR) + "/images/golden/zbuffer/cube.png";
const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
// One room as a cell, with a floor; kInsideCamera puts the eye in it.
const std::string kOneRoom = "[[objects]]\nshape = \"grid\"\n[[cells]]\nname = \"room\"\nfrom = [-1, 0, -1]\nto = [1, 1, 1]\n";
const std::string kInsideCamera = "[camera]\neye = [0, 0.5, 0]\ntarget = [0, 0.5, -1]\n";

INSTANTIATE_TEST_SUITE_P(
    Cli, BadInput,
    testing::Values(
        Case{"missing-scene", "/no/such/scene.toml -o OUT", "/no/such/scene.toml: cannot open the scene file"},
        Case{"malformed-obj", meshScene("malformed", kTriangle + "f 1 2 3\nv 1 2 x\n") + " -o OUT",
             "malformed.obj:5: vertex needs three numbers x y z"},
        Case{"nan-coordinate", meshScene("nan", kTriangle + "v nan 0 0\nf 1 2 4\n") + " -o OUT",
             "nan.obj:4: vertex coordinate is not finite (NaN or Inf)"},
        Case{"inf-coordinate", meshScene("inf", "v 0 -inf 0\n" + kTriangle + "f 1 2 3\n") + " -o OUT",
             "inf.obj:1: vertex coordinate is not finite"},
        // Found by the OBJ fuzz target when tinyobjloader still stored floats: this became Inf.
        Case{"coordinate-too-large", meshScene("large", kTriangle + "v 1e105 0 0\nf 1 2 4\n") + " -o OUT",
             "large.obj:4: vertex coordinate 1e105 is out of range; expected at most 1e12 in size"},
        // Found by the OBJ fuzz target: a lone carriage return ends a line for tinyobjloader.
        Case{"lone-carriage-return", meshScene("cr", kTriangle + "f 1 2\r3\n") + " -o OUT",
             "cr.obj:4: face needs at least 3 corners, got 2"},
        // Found by the OBJ fuzz target: tinyobjloader reads 0e669798 as 0 x Inf = NaN.
        Case{"exponent-tinyobjloader-reads-as-nan", meshScene("nanread", kTriangle + "v 0e669798 0 0\nf 1 2 4\n") + " -o OUT",
             "nanread.obj:4: vertex reads as"},
        Case{"face-out-of-range", meshScene("range", kTriangle + "f 1 2 7\n") + " -o OUT",
             "range.obj:4: face index 7 is out of range: 3 vertices are defined before this line"},
        Case{"missing-obj", write("missing-obj.toml", kCamera + "[[objects]]\nshape = \"mesh\"\nfile = \"gone.obj\"\n") + " -o OUT",
             "objects[0].file: " + test::outputPath("gone.obj").string() + ": cannot open the OBJ file"},
        // A device would be read forever: only a regular file is opened.
        Case{"obj-is-a-device", write("device-obj.toml", kCamera + "[[objects]]\nshape = \"mesh\"\nfile = \"/dev/zero\"\n") + " -o OUT",
             "objects[0].file: /dev/zero: cannot open the OBJ file (missing, or not a regular file)"},
        // Found by the scene fuzz target: toml++ converted the float to an integer with undefined behaviour.
        Case{"integer-given-a-huge-float", write("float-height.toml", "[image]\nheight = 4e80\n" + kCamera + "[[objects]]\nshape = \"box\"\n") + " -o OUT",
             "float-height.toml:2:10: image.height: expected an integer in [1, 16384], got 4e+80"},
        // Found by the scene fuzz target: toml++ 3.3 tested the character for whitespace with undefined behaviour.
        Case{"non-ascii-outside-quotes", write("accent.toml", kCamera + "d = 1979-$5-27 07\"\xC2\xA7\"\n") + " -o OUT",
             "accent.toml:4:5: not valid TOML: Error while parsing value: could not determine value type"},
        Case{"steps-folder-in-a-missing-folder", kCube + " -o OUT --steps /no/such/folder/steps",
             "--steps /no/such/folder/steps: the folder it would go in (/no/such/folder) does not exist"},
        Case{"steps-folder-is-a-file", kCube + " -o OUT --steps " + kCube, "exists and is not a folder"},
        Case{"every-without-steps", kCube + " -o OUT --every 3", "--every 3: applies only with --steps DIR"},
        Case{"size-zero", kCube + " --size 0x100 -o OUT", "--size 0x100: image size 0x100 is out of range"},
        Case{"size-absurd", kCube + " --size 100000x100 -o OUT", "image size 100000x100 is out of range; expected 1 to 16384"},
        Case{"size-too-many-pixels", kCube + " --size 16384x16385 -o OUT", "at most 256 Mpixel"},
        Case{"size-malformed", kCube + " --size big -o OUT", "--size big: expected WIDTHxHEIGHT"},
        Case{"unknown-algorithm", kCube + " --algo zbufer -o OUT", "--algo zbufer: unknown algorithm; expected one of reference, zbuffer, ray_casting"},
        Case{"unknown-knob", kCube + " --knob precision=high -o OUT", "zbuffer has no knob 'precision'; expected one of variant, depth-format"},
        Case{"bad-knob-value", kCube + " --depth-format float16 -o OUT", "zbuffer depth-format must be one of float32, reversed-float32"},
        Case{"knob-without-value", kCube + " --knob variant -o OUT", "--knob variant: expected NAME=VALUE"},
        Case{"numeric-knob-not-a-number", kCube + " --algo ray_casting --variant march --knob step=fine -o OUT",
             "--knob step=fine: ray_casting step must be a number in [1e-06, 1e+06], or a percentage P% with P in that range"},
        Case{"numeric-knob-out-of-range", kCube + " --algo ray_casting --variant march --knob grid=100000 -o OUT",
             "ray_casting grid must be an integer in [1, 256]"},
        Case{"integer-knob-fraction", kCube + " --algo ray_casting --variant march --knob refine=1.5 -o OUT",
             "ray_casting refine must be an integer in [0, 52]"},
        Case{"knob-of-another-variant", kCube + " --algo ray_casting --knob step=1% -o OUT",
             "--knob step=1%: ray_casting step applies only to variant march, not to variant bvh"},
        Case{"naive-over-budget", std::string(HSR_SOURCE_DIR) + "/scenes/bunny.toml --algo ray_casting --variant naive -o OUT",
             "ray_casting cannot render it: naive ray casting would run 640 x 480 pixels x 3674 triangles = 1.13e+09 "
             "ray-triangle tests, over its budget of 1e+09 (raise it with --knob budget=N"},
        Case{"march-over-budget", kCube + " --algo ray_casting --variant march --knob step=1e-5% -o OUT",
             "march ray casting would run 640 x 480 pixels x"},
        Case{"svg-for-surface-algorithm", kCube + " -o OUT.svg", "SVG is for line drawings and visible polygons, and zbuffer draws pixels; expected a .png file"},
        Case{"line-style-for-surface-algorithm", kCube + " --line-style hidden -o OUT",
             "--line-style hidden: applies only to line algorithms (roberts, appel, floating_horizon)"},
        Case{"line-style-unknown", kCube + " --algo appel --line-style dotted -o OUT", "--line-style dotted: expected visible, hidden or qi"},
        Case{"cull-unknown-stage", kCube + " --cull backface,occlusionn -o OUT",
             "--cull: unknown culling stage 'occlusionn' in 'backface,occlusionn'; expected a comma-separated list of "
             "backface, frustum, occlusion, portals or pvs, each optionally :VARIANT and :KNOB=VALUE"},
        Case{"cull-unknown-variant", kCube + " --cull frustum:cone -o OUT",
             "--cull: culling stage frustum has no variant 'cone'; expected sphere, aabb, bvh, triangle or any-vertex"},
        Case{"cull-empty-stage", kCube + " --cull backface, -o OUT", "--cull: unknown culling stage '' in 'backface,'"},
        Case{"cull-knob-out-of-range", kCube + " --cull frustum,occlusion:map-width=5000 -o OUT",
             "--cull map-width=5000: culling stage occlusion map-width must be an integer in [1, 4096]"},
        Case{"cull-knob-of-another-variant", kCube + " --cull occlusion:previous-frame:occluders=volume -o OUT",
             "--cull occluders=volume: culling stage occlusion occluders applies only to variant depth-map, not to variant "
             "previous-frame"},
        Case{"cull-for-ray-casting", kCube + " --algo ray_casting --cull frustum -o OUT",
             "--cull: ray_casting does not draw from a culled set of triangles; expected --algo zbuffer or painter"},
        Case{"cull-for-a-line-algorithm", kCube + " --algo appel --cull backface -o OUT",
             "--cull: appel does not draw from a culled set of triangles"},
        Case{"depth-image-of-a-drawing", kCube + " --algo roberts --depth OUT.exr -o OUT",
             "--depth: roberts draws lines, which have no depth or id image"},
        Case{"segments-of-a-surface-algorithm", kCube + " --algo zbuffer -o OUT --segments lines.txt",
             "--segments lines.txt: zbuffer draws pixels; segments come from a line algorithm"},
        Case{"roberts-non-convex", std::string(HSR_SOURCE_DIR) + "/scenes/bunny.toml --algo roberts -o OUT",
             "roberts cannot render it: object 'bunny' is not convex: a vertex lies"},
        Case{"roberts-body-too-large",
             write("fine-sphere.toml", kCamera + "[[objects]]\nname = \"ball\"\nshape = \"sphere\"\nsegments = 128\nrings = 64\n") +
                 " --algo roberts -o OUT",
             "object 'ball' has 16128 triangles, more than the 8192 a Roberts body may have"},
        Case{"floating-horizon-not-a-height-field", kCube + " --algo floating_horizon -o OUT",
             "floating_horizon cannot render it: the floating horizon draws one height-field object"},
        Case{"floating-horizon-eye-above-the-footprint",
             write("plot-from-above.toml", "[camera]\neye = [0, 10, 0.5]\ntarget = [0, 0, 0]\n"
                                           "[[objects]]\nshape = \"heightfield\"\nfunction = \"gauss\"\n") +
                 " --algo floating_horizon -o OUT",
             "under perspective the floating horizon needs the eye outside the height field's footprint"},
        Case{"appel-open-surface", std::string(HSR_SOURCE_DIR) + "/scenes/hard/coplanar.toml --algo appel -o OUT",
             "bounds one triangle (the surface is open); quantitative invisibility by front faces needs closed"},
        Case{"lines-across-the-near-plane", std::string(HSR_SOURCE_DIR) + "/scenes/counters.toml --algo appel --knob surfaces=any -o OUT",
             "not beyond the near plane (0.1): line drawings do not clip"},
        Case{"appel-unknown-surfaces", kCube + " --algo appel --knob surfaces=some -o OUT", "appel surfaces must be one of closed, any"},
        Case{"opacity-without-transparency",
             write("opacity.toml", kCamera + "[[objects]]\nshape = \"box\"\nopacity = 0.5\n") + " --algo painter -o OUT",
             "opacity.toml:6:11: objects[0].opacity: an opacity below 1 needs \"transparency\" in the scene's effects"},
        Case{"opacity-out-of-range",
             write("opacity-range.toml", "effects = [\"transparency\"]\n" + kCamera + "[[objects]]\nshape = \"box\"\nopacity = 1.5\n") +
                 " --algo painter -o OUT",
             "opacity-range.toml:7:11: objects[0].opacity: expected a finite number in [0, 1], got 1.5"},
        Case{"ray-casting-on-transparency",
             write("glass.toml", "effects = [\"transparency\"]\n" + kCamera + "[[objects]]\nshape = \"box\"\nopacity = 0.5\n") +
                 " --algo ray_casting -o OUT",
             "ray_casting cannot render it: the scene declares transparency, which needs the surfaces behind a pixel blended back "
             "to front; ray casting keeps only the nearest (use --algo zbuffer or painter or warnock or watkins or weiler_atherton or abuffer)"},
        Case{"painter-knob-of-another-variant", kCube + " --algo painter --knob key=nearest -o OUT",
             "--knob key=nearest: painter key applies only to variant sort, not to variant bsp"},
        Case{"painter-split-cap-negative", kCube + " --algo painter --variant newell --knob split-cap=-1 -o OUT",
             "painter split-cap must be an integer in [0, 1e+09]"},
        Case{"warnock-smallest-window-zero", kCube + " --algo warnock --knob smallest-window=0 -o OUT",
             "warnock smallest-window must be an integer in [1, 4096]"},
        Case{"watkins-unknown-split", kCube + " --algo watkins --knob split=diagonal -o OUT",
             "watkins split must be one of crossing, halves, none"},
        Case{"abuffer-unknown-mask", kCube + " --algo abuffer --knob mask=3x3 -o OUT", "abuffer mask must be one of 4x4, 8x8, 2x2"},
        Case{"abuffer-unknown-depth", kCube + " --algo abuffer --knob depth=pixel -o OUT", "abuffer depth must be one of subsample, center"},
        Case{"weiler-atherton-budget-zero", kCube + " --algo weiler_atherton --knob budget=0 -o OUT",
             "weiler_atherton budget must be an integer in [1, 1e+09]"},
        Case{"weiler-atherton-over-budget", std::string(HSR_SOURCE_DIR) + "/scenes/dragons.toml --algo weiler_atherton -o OUT",
             "weiler_atherton cannot render it: weiler_atherton clips 399136 triangles against each other, more than --knob "
             "budget=250000; raise it"},
        Case{"bsp-over-split-limit", std::string(HSR_SOURCE_DIR) + "/scenes/hard/cyclic_overlap.toml --algo painter --knob split-limit=0 -o OUT",
             "painter bsp: the tree needs more than 0 splits (--knob split-limit=0); raise the limit"},
        Case{"newell-over-budget", std::string(HSR_SOURCE_DIR) + "/scenes/trees.toml --algo painter --variant newell -o OUT",
             "painter cannot render it: newell may test 1.64e+09 triangle pairs (57242 triangles), more than --knob "
             "budget=1e+09"},
        Case{"bsp-over-build-budget", std::string(HSR_SOURCE_DIR) + "/scenes/dragons.toml --algo painter -o OUT",
             "painter cannot render it: building the bsp tree of 399136 triangles takes about 1.38e+08 plane-side tests, "
             "more than --knob build-budget=1e+08"},
        Case{"unknown-scene-key", write("key.toml", kCamera + "[[objects]]\nshape = \"box\"\nsise = 2\n") + " -o OUT",
             "key.toml:6:1: objects[0].sise: unknown key"},
        Case{"output-folder-missing", kCube + " -o /no/such/folder/out.png", "the folder /no/such/folder does not exist"},
        Case{"output-not-png", kCube + " -o " + test::outputPath("bad-output-not-png.jpg").string(), "expected a file name ending in .png"},
        Case{"depth-not-exr", kCube + " -o OUT --depth " + test::outputPath("depth.png").string(), "expected a file name ending in .exr (OpenEXR) or .pfm"},
        Case{"threads-negative", kCube + " --threads -3 -o OUT", "--threads"},
        // hsr compare: everything is checked before the first render, so no folder appears.
        Case{"why-pixel-outside-the-image", kCube + " --size 64x48 --pixel 64,10",
             "--pixel 64,10: outside the 64x48 image; expected X in [0, 63] and Y in [0, 47]", "why"},
        Case{"why-pixel-not-a-pair", kCube + " --pixel 3x4", "--pixel 3x4: expected X,Y", "why"},
        Case{"why-pixel-twice", kCube + " --pixel 3,4 --pixel 3,4", "--pixel 3,4: given twice; expected each pixel once", "why"},
        Case{"why-line-algorithm", kCube + " --pixel 3,4 --algo appel",
             "--algo appel: a line algorithm answers along an edge; expected --edge N or --edge X,Y", "why"},
        Case{"why-edge-on-a-surface-algorithm", kCube + " --edge 3", "--edge: zbuffer draws no edges; expected --pixel X,Y, or --edge with --algo roberts, appel, floating_horizon",
             "why"},
        Case{"why-edge-not-in-the-drawing", kCube + " --edge 12 --algo appel",
             "--edge 12: the drawing has 12 edges; expected an edge number in [0, 11] or a pixel X,Y near one", "why"},
        Case{"why-edge-near-no-pixel", kCube + " --edge 0,0 --algo appel",
             "--edge 0,0: no edge of the drawing passes within 3 pixels of that pixel's center (the nearest is 288 pixels away)", "why"},
        Case{"why-edge-not-a-number", kCube + " --edge first --algo appel",
             "--edge first: expected an edge number, or X,Y for the edge passing nearest that pixel", "why"},
        Case{"why-pixel-and-edge", kCube + " --pixel 3,4 --edge 3 --algo appel", "--pixel excludes --edge", "why"},
        Case{"why-reference", kCube + " --pixel 3,4 --algo reference",
             "--algo reference: hsr why follows the loops of zbuffer, ray_casting, painter, warnock, watkins, weiler_atherton, abuffer so far", "why"},
        Case{"why-no-pixel", kCube, "hsr why: --pixel X,Y or --edge E is required", "why"},
        Case{"why-step-zero", kCube + " --size 64x48 --pixel 3,4 --step 0",
             "--step 0: zbuffer records 14 steps here (as hsr render --steps numbers them, with the same size, knobs and --every); expected 1 to 14",
             "why"},
        Case{"why-step-beyond-the-last", kCube + " --size 64x48 --pixel 3,4 --step 15", "--step 15: zbuffer records 14 steps here", "why"},
        Case{"why-every-without-step", kCube + " --pixel 3,4 --every 4", "--every 4: applies only with --step N", "why"},
        Case{"why-step-along-an-edge", kCube + " --edge 3 --algo appel --step 2", "--edge excludes --step", "why"},
        Case{"compare-unknown-algorithm", kCube + " --algos zbufer --out OUT", "--algos zbufer: unknown algorithm", "compare"},
        Case{"compare-bad-knob", kCube + " --algos zbuffer:depth-format=float16 --out OUT",
             "--algos zbuffer: depth-format=float16: zbuffer depth-format must be one of", "compare"},
        Case{"compare-knob-without-value", kCube + " --algos zbuffer:variant --out OUT", "variant: expected NAME=VALUE", "compare"},
        Case{"compare-reference-named", kCube + " --algos reference --out OUT", "the reference is always run", "compare"},
        Case{"compare-empty-list-item", kCube + " --algos zbuffer,,zbuffer --out OUT", "empty item", "compare"},
        Case{"compare-repeat-zero", kCube + " --repeat 0 --out OUT", "--repeat 0: expected at least 1", "compare"},
        Case{"compare-missing-scene", "/no/such/scene.toml --out OUT", "/no/such/scene.toml: cannot open the scene file", "compare"},
        Case{"compare-out-under-a-file", kCube + " --out " + kCube + "/folder", "cannot create the folder", "compare"},
        // hsr sweep
        Case{"sweep-no-knob", kCube + " --out OUT", "give at least one --knob", "sweep"},
        Case{"sweep-unknown-knob", kCube + " --knob precision=1,2 --out OUT", "zbuffer has no knob 'precision'", "sweep"},
        Case{"study-unknown", "culling-combo --out OUT", "study culling-combo: unknown study; expected culling-combos, occlusion-walkthrough, occlusion-queries, hzb-resolution, occluder-fraction, "
             "indoor, effects or shadow-map",
             "study"},
        Case{"study-scenes-of-an-occlusion-study", "hzb-resolution --scenes cube --out OUT",
             "--scenes: study hzb-resolution has its own scenes; --scenes is for culling-combos", "study"},
        Case{"study-unknown-scene", "culling-combos --scenes cube,teapot --out OUT",
             "--scenes cube,teapot: 'teapot' is not one of the study's scenes; expected some of cube, counters, trees, dragons", "study"},
        Case{"study-error-frames", "culling-combos --frames 4 --error-frames 5 --out OUT",
             "--error-frames 5: more than the 4 frames; expected at most --frames", "study"},
        Case{"study-bad-size", "culling-combos --size 0x10 --out OUT", "--size 0x10: image size 0x10 is out of range", "study"},
        Case{"study-shard-zero", "occlusion-queries --shard 0/2 --out OUT",
             "--shard 0/2: expected K/N, this run's share K of N shards, 1 <= K <= N <= 10000", "study"},
        Case{"study-shard-past-the-last", "occlusion-queries --shard 3/2 --out OUT", "--shard 3/2: expected K/N", "study"},
        Case{"study-shard-not-a-fraction", "occlusion-queries --shard half --out OUT", "--shard half: expected K/N", "study"},
        Case{"study-shard-unsharded-study", "hzb-resolution --shard 1/2 --out OUT",
             "--shard: study hzb-resolution is not sharded; expected study occlusion-queries", "study"},
        Case{"study-merge-missing", "occlusion-queries --merge /no/such/shard --out OUT",
             "--merge /no/such/shard: no occlusion_queries_frames.csv in it; expected a folder a --shard run wrote", "study"},
        Case{"study-merge-and-shard", "occlusion-queries --merge /tmp --shard 1/2 --out OUT",
             "--merge: a merge walks nothing; --shard is for the runs it joins", "study"},
        Case{"render-query-latency", kCube + " --cull occlusion:queries:latency=1001 -o OUT",
             "--cull latency=1001: culling stage occlusion latency must be an integer in [0, 1000]"},
        Case{"render-query-threshold", kCube + " --cull occlusion:queries:threshold=-1 -o OUT",
             "--cull threshold=-1: culling stage occlusion threshold must be an integer in [0, 100000]"},
        Case{"render-query-strategy", kCube + " --cull occlusion:queries:fastest -o OUT",
             "--cull: occlusion:queries has no strategy 'fastest'; expected stop-and-wait, delayed, chc or chcpp"},
        Case{"sweep-bad-value", kCube + " --knob depth-format=float32,float16 --out OUT", "depth-format must be one of", "sweep"},
        Case{"sweep-bad-size", kCube + " --knob size=64x48,big --out OUT", "--knob size: big: expected WIDTHxHEIGHT", "sweep"},
        Case{"sweep-variant-twice", kCube + " --algo ray_casting --variant march --knob variant=bvh,naive --out OUT",
             "the variant is already fixed by --variant march", "sweep"},
        Case{"sweep-knob-of-another-variant", kCube + " --algo ray_casting --knob refine=0,4 --out OUT",
             "ray_casting refine applies only to variant march", "sweep"},
        Case{"sweep-over-budget", kCube + " --algo ray_casting --variant naive --knob size=64x48,10000x10000 --out OUT",
             "(size=10000x10000): ray_casting cannot render it: naive ray casting would run 10000 x 10000 pixels", "sweep"},
        Case{"sweep-knob-twice", kCube + " --knob variant=full --knob variant=scanline --out OUT", "variant is swept twice", "sweep"},
        Case{"sweep-knob-without-values", kCube + " --knob variant --out OUT", "--knob variant: expected NAME=VALUE", "sweep"},
        Case{"sweep-bad-scale", kCube + " --scale triangle --out OUT", "--scale triangle: expected triangles or pixels", "sweep"},
        Case{"sweep-scale-with-a-list", kCube + " --scale pixels --knob variant=full,scanline --out OUT", "each --knob fixes one", "sweep"},
        Case{"sweep-reference", kCube + " --algo reference --knob size=8x8 --out OUT", "the reference is what a sweep measures against; sweep a surface or line algorithm", "sweep"},
        Case{"sweep-scale-too-many-triangles", std::string(HSR_SOURCE_DIR) + "/scenes/dragons.toml --scale triangles --out OUT",
             "--scale triangles grows a scene of at most 275,000", "sweep"},
        // hsr diff
        Case{"diff-missing-image", "/no/such/a.png " + kGoldenCube, "/no/such/a.png: cannot read the image", "diff"},
        Case{"diff-size-mismatch", kGoldenCube + " " + std::string(HSR_SOURCE_DIR) + "/images/golden/zbuffer/dragons.png",
             "expected 320x240", "diff"},
        Case{"diff-tolerance-out-of-range", kGoldenCube + " " + kGoldenCube + " --tolerance 2", "--tolerance 2", "diff"},
        Case{"diff-heatmap-not-png", kGoldenCube + " " + kGoldenCube + " --heatmap " + test::outputPath("bad-heat.jpg").string(),
             "expected a file name ending in .png", "diff"},
        // Levels divided into cells (the stages portals and pvs).
        Case{"portals-without-cells", kCube + " --cull portals -o OUT",
             "--cull portals: " + kCube + " has no cells; expected [[cells]] and [[portals]] tables dividing the level"},
        Case{"portals-eye-in-no-cell", write("eye-outside.toml", kCamera + kOneRoom) + " --cull frustum,portals -o OUT",
             "--cull portals: the eye (0, 0, 5) is in no cell of " + test::outputPath("eye-outside.toml").string() +
                 "; expected it inside one of its 1 cells"},
        Case{"portals-cell-without-objects",
             write("empty-cell.toml", kInsideCamera + kOneRoom + "[[cells]]\nname = \"attic\"\nfrom = [-1, 1, -1]\nto = [1, 2, 1]\n") +
                 " --cull portals -o OUT",
             "empty-cell.toml:11:8: cells[1] \"attic\": no object meets this cell; expected every cell to hold at least one object"},
        Case{"portals-orthographic", write("ortho-cells.toml", "[camera]\ntype = \"orthographic\"\neye = [0, 0.5, 0]\ntarget = [0, 0.5, -1]\nheight = 2\n" + kOneRoom) +
                                         " --cull portals -o OUT",
             "is orthographic; expected a perspective camera"},
        Case{"pvs-eye-in-no-cell", test::outputPath("eye-outside.toml").string() + " --cull pvs -o OUT", "--cull pvs: the eye (0, 0, 5) is in no cell"},
        Case{"pvs-samples-without-sampled", kCube + " --cull pvs:samples=4 -o OUT",
             "--cull: pvs:samples=4: samples and resolution set how build=sampled samples; expected build=sampled with them"},
        Case{"pvs-max-chains-with-sampled", kCube + " --cull pvs:build=sampled:max-chains=5 -o OUT",
             "--cull: pvs:build=sampled:max-chains=5: max-chains bounds the conservative build's search; expected build=conservative with it"},
        Case{"portals-max-passes-zero", kCube + " --cull portals:max-passes=0 -o OUT",
             "culling stage portals max-passes must be an integer in [1, 1e+09]"},
        Case{"pvs-build-without-cells", kCube + " --out OUT", "hsr pvs build: " + kCube + " has no cells", "pvs build"},
        Case{"pvs-build-zero-samples", std::string(HSR_SOURCE_DIR) + "/scenes/hard/portal_row.toml --build sampled --samples 0 --out OUT",
             "hsr pvs build samples=0: culling stage pvs samples must be an integer in [1, 100000]", "pvs build"},
        Case{"pvs-build-unknown-build", std::string(HSR_SOURCE_DIR) + "/scenes/hard/portal_row.toml --build exact --out OUT",
             "culling stage pvs build must be one of conservative, sampled", "pvs build"},
        // A class shares one checkout, which may be read-only: the file is always named.
        Case{"pvs-build-without-out", std::string(HSR_SOURCE_DIR) + "/scenes/hard/portal_row.toml",
             "--out is required", "pvs build"},
        Case{"pvs-cache-missing", std::string(HSR_SOURCE_DIR) + "/scenes/hard/portal_row.toml --cull pvs:cache=/no/such.pvs -o OUT",
             "/no/such.pvs: cannot open the visible-set cache; expected a file hsr pvs build --out wrote"},
        Case{"pvs-cache-of-another-level", std::string(HSR_SOURCE_DIR) + "/scenes/hard/portal_row.toml --cull pvs:cache=" +
                                               write("other-level.pvs", "hsr pvs 1\nfingerprint 0123456789abcdef\n") + " -o OUT",
             "other-level.pvs:2: built for another level"},
        Case{"pvs-cache-empty-name", std::string(HSR_SOURCE_DIR) + "/scenes/hard/portal_row.toml --cull pvs:cache= -o OUT",
             "culling stage pvs cache must be a file name"},
        Case{"mistyped-table", write("mistyped-table.toml", kCamera + "[[object]]\nshape = \"box\"\n") + " -o OUT",
             "mistyped-table.toml:4:3: object: unknown table; expected one of image, camera"}),
    [](const testing::TestParamInfo<Case>& param) {
      std::string name = param.param.name;
      std::replace(name.begin(), name.end(), '-', '_');
      return name;
    });

// The other side of the contract: good input writes every file asked for.
TEST(Cli, RenderWritesColorDepthAndIds) {
  const auto color = test::outputPath("cli-cube.png"), depth = test::outputPath("cli-cube.exr"), ids = test::outputPath("cli-cube-ids.png");
  for (const auto& path : {color, depth, ids}) std::filesystem::remove(path);
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " render " + kCube + " --size 64x48 -o " +
                                                      color.string() + " --depth " + depth.string() + " --ids " + ids.string() + " --stats");
  ASSERT_EQ(result.exitCode, 0) << result.output;
  const Image idImage = readImage(ids);
  ASSERT_EQ(idImage.width, 64);
  ASSERT_EQ(idImage.channels, 3);
  // The cube has 12 triangles: every decoded id is 0 (background) or 1..12.
  std::set<std::uint32_t> seen;
  std::int64_t covered = 0;
  for (std::size_t p = 0; p < 64 * 48; ++p) {
    seen.insert(idFromRgb(&idImage.pixels[3 * p]));
    covered += idFromRgb(&idImage.pixels[3 * p]) != 0;
  }
  // --stats counts the pixels a surface shows (what depth complexity is measured over).
  char line[64];
  std::snprintf(line, sizeof line, "%-32s %lld\n", "covered pixels", static_cast<long long>(covered));
  EXPECT_GT(covered, 0);
  EXPECT_NE(result.output.find(line), std::string::npos) << line << " in:\n" << result.output;
  EXPECT_TRUE(seen.count(0));
  EXPECT_LE(*seen.rbegin(), 12u);
  EXPECT_GE(seen.size(), 5u);  // background and at least two faces of two triangles each
  EXPECT_EQ(readImage(color).width, 64);
  EXPECT_TRUE(std::filesystem::exists(depth));
  // The same depth as a portable float map: +infinity exactly where the ids show the
  // background, and the cube's distances (its eye is 5.4 from the target) elsewhere.
  const auto pfm = test::outputPath("cli-cube-depth.pfm");
  ASSERT_EQ(test::runCommand(std::string(HSR_BINARY) + " render " + kCube + " --size 64x48 -o " + color.string() + " --depth " + pfm.string())
                .exitCode,
            0);
  std::vector<float> distances;
  ASSERT_EQ(readPfm(pfm, 64, 48, distances), "");
  for (std::size_t p = 0; p < 64 * 48; ++p) {
    if (idFromRgb(&idImage.pixels[3 * p]) == 0) {
      EXPECT_EQ(distances[p], std::numeric_limits<float>::infinity()) << p;
    } else {
      EXPECT_GT(distances[p], 3.0f) << p;
      EXPECT_LT(distances[p], 7.0f) << p;
    }
  }
}

// A size within the limits that this machine's memory cannot hold (here, a memory
// limit of 1.5 GiB against the 3 GiB frame of 16384 x 16384): bad input, said as such,
// with what the frame needs; no file.
TEST(Cli, RunningOutOfMemorySaysWhatTheSizeNeedsAndWritesNothing) {
  const auto output = test::outputPath("cli-out-of-memory.png");
  std::filesystem::remove(output);
  const test::CommandResult result = test::runCommand("ulimit -v 1500000 && " + std::string(HSR_BINARY) + " render " + kCube +
                                                      " --size 16384x16384 --threads 1 -o " + output.string());
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
  EXPECT_EQ(result.output.rfind("hsr: error: out of memory rendering 16384x16384 with zbuffer: the frame alone needs 3.0 GiB", 0), 0u)
      << result.output;
  EXPECT_FALSE(std::filesystem::exists(output));
}

// A shipped scene by the name `hsr list` prints, with or without ".toml", from any folder.
TEST(Cli, ShippedScenesAreFoundByName) {
  const auto byName = test::outputPath("cli-by-name-ids.png"), byPath = test::outputPath("cli-by-path-ids.png");
  const std::string render = std::string(HSR_BINARY) + " render ";
  const std::string options = " --size 64x36 -o " + test::outputPath("cli-by-name.png").string() + " --ids ";
  ASSERT_EQ(test::runCommand("cd / && " + render + "counters" + options + byName.string()).exitCode, 0);
  ASSERT_EQ(test::runCommand(render + test::sourcePath("scenes/counters.toml").string() + options + byPath.string()).exitCode, 0);
  EXPECT_EQ(readImage(byName).pixels, readImage(byPath).pixels);
  EXPECT_EQ(test::runCommand("cd / && " + render + "hard/coplanar.toml" + options + byName.string()).exitCode, 0);
  // A name that is neither a file nor a shipped scene says both were tried.
  const test::CommandResult missing = test::runCommand(render + "countres -o " + test::outputPath("x.png").string());
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.output.find("countres: cannot open the scene file (no such file), and no shipped scene has that name"),
            std::string::npos) << missing.output;
}

TEST(Cli, ListShowsAlgorithmsKnobsAndScenes) {
  const test::CommandResult result = test::runCommand(std::string(HSR_BINARY) + " list");
  ASSERT_EQ(result.exitCode, 0);
  for (const char* expected : {"zbuffer", "--knob variant=full | scanline", "reversed-float32-inf", "dragons.toml", "hard/coplanar.toml"})
    EXPECT_NE(result.output.find(expected), std::string::npos) << expected;
}

TEST(Cli, VersionNamesTheCommitItWasBuiltFrom) {
  const test::CommandResult version = test::runCommand(std::string(HSR_BINARY) + " --version");
  ASSERT_EQ(version.exitCode, 0) << version.output;
  EXPECT_EQ(version.output.rfind("hsr " HSR_VERSION " (", 0), 0u) << version.output;
  // The build's commit is the checkout's (a build from a tarball says it has none).
  const test::CommandResult head = test::runCommand("git -C " + test::sourcePath("").string() + " rev-parse --short=12 HEAD");
  if (head.exitCode == 0)
    EXPECT_NE(version.output.find(head.output.substr(0, 12)), std::string::npos) << version.output << " against " << head.output;
  else
    EXPECT_NE(version.output.find("unknown commit"), std::string::npos) << version.output;
}

}  // namespace
}  // namespace hsr
