#!/usr/bin/env bash
# How the speed follows the cores: every algorithm on counters, city and dragons at
# 1920x1080, on 1 thread up to this machine's core count, the least of five fresh
# `hsr render --stats` runs at each count. For each: the visibility pass's time (builds
# and preparation included), its speed-up and efficiency against one thread, its serial
# fraction (the time outside parallel loops, as --stats measures it at the most threads,
# divided by the one-thread time) and the speed-up Amdahl's law then gives on 16 cores
# (each loop spread over at most as many cores as it has items), the time of every
# phase, and whether the id image (a line drawing's SVG) is the same bits at every count.
#   bash bench/scaling.sh                         all of it (about 4 minutes on 2 cores)
#   bash bench/scaling.sh --scenes counters --algos zbuffer,reference --threads 1,2,4 --runs 3
# Writes out/scaling/: scaling.csv (a row per algorithm, scene and thread count),
# phases.csv (every phase of the fastest run at each count), scaling.md (the table
# README quotes) and speedup.png (speed-up against threads, a panel per scene, the
# ideal as a line). Exits 1 if any image (ids and colour, or the drawing) differs
# between thread counts or a render fails at some counts only, 2 on a bad argument or
# when nothing could be rendered.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/hsr ] || { echo "scaling.sh: build/hsr: not built (bash scripts/build.sh builds it)" >&2; exit 2; }
command -v gnuplot >/dev/null || { echo "scaling.sh: gnuplot: not installed (bash scripts/setup.sh installs it)" >&2; exit 2; }
exec python3 - "$@" <<'PY'
import argparse, csv, hashlib, os, re, subprocess, sys, tempfile

cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)  # the cores it may use
parser = argparse.ArgumentParser(prog="bench/scaling.sh")
parser.add_argument("--scenes", default="counters,city,dragons", help="scene names in scenes/, comma-separated")
parser.add_argument("--algos", default="", help="algorithms, comma-separated (default: every one `hsr list` names)")
parser.add_argument("--threads", default=",".join(str(t) for t in sorted({1, 2, 4, 8, 16, cores}) if t <= cores),
                    help="thread counts, comma-separated (default: powers of two up to the core count, and the count)")
parser.add_argument("--runs", type=int, default=5, help="fresh runs per count; the fastest is kept")
parser.add_argument("--size", default="1920x1080")
parser.add_argument("--out", default="out/scaling")
options = parser.parse_args()
def fail(message):
    print(f"scaling.sh: {message}", file=sys.stderr)
    sys.exit(2)
try:
    threads = sorted({int(t) for t in options.threads.split(",")})
except ValueError:
    fail(f"--threads {options.threads}: expected thread counts separated by commas, e.g. 1,2,4")
if not threads or min(threads) < 1 or 1 not in threads:
    fail(f"--threads {options.threads}: expected positive counts, 1 among them (speed-ups are against one thread)")
if options.runs < 1:
    fail(f"--runs {options.runs}: expected at least 1")

listed = subprocess.run(["build/hsr", "list"], capture_output=True, text=True, check=True).stdout
kinds = dict(re.findall(r"^  ([a-z_]+) +(reference|surface|line) ", listed, re.M))
algorithms = options.algos.split(",") if options.algos else list(kinds)
for name in algorithms:
    if name not in kinds:
        fail(f"--algos: {name}: not an algorithm; expected one of {', '.join(kinds)}")
scenes = options.scenes.split(",")
for scene in scenes:
    if not os.path.exists(f"scenes/{scene}.toml"):
        fail(f"--scenes: scenes/{scene}.toml: no such scene")
os.makedirs(options.out, exist_ok=True)
work = tempfile.mkdtemp()

time_line = re.compile(r"^(.+?) time +([0-9.]+) ms$", re.M)

def run(algorithm, scene, count):
    """One fresh render: its phase times in ms and the hash of its ids and colour (or drawing), or the refusal."""
    line = kinds[algorithm] == "line"
    output = f"{work}/out.{'svg' if line else 'png'}"
    command = ["build/hsr", "render", f"scenes/{scene}.toml", "--algo", algorithm, "--size", options.size,
               "--threads", str(count), "--stats", "-o", output] + ([] if line else ["--ids", f"{work}/ids.png"])
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        return None, result.stderr.strip().splitlines()[-1] if result.stderr.strip() else f"exit {result.returncode}"
    phases = {name: float(ms) for name, ms in time_line.findall(result.stdout)}
    digest = hashlib.sha256()
    for image in [output] + ([] if line else [f"{work}/ids.png"]):
        with open(image, "rb") as file:
            digest.update(file.read())
    return phases, digest.hexdigest()[:16]

rows, phase_rows, refused, differing = [], [], [], []
for scene in scenes:
    for algorithm in algorithms:
        least = {}  # thread count -> the phases of its fastest run (totals and serial times from one run)
        hashes = {}  # thread count -> the images' hashes
        for count in threads:
            best, seen = None, set()
            for _ in range(options.runs):
                phases, answer = run(algorithm, scene, count)
                if phases is None:
                    break
                seen.add(answer)
                if best is None or phases["pass: visibility"] < best["pass: visibility"]:
                    best = phases
            if phases is None:
                if least:  # it rendered at fewer threads: failing at this count is a difference too
                    differing.append((algorithm, scene, count))
                    print(f"{algorithm} on {scene}: failed at {count} threads only: {answer}", file=sys.stderr)
                else:
                    refused.append((algorithm, scene, answer))
                    print(f"{algorithm} on {scene}: refused: {answer}", file=sys.stderr)
                break
            least[count], hashes[count] = best, seen
            print(f"{algorithm} on {scene}, {count} thread(s): {best['pass: visibility']:.1f} ms", file=sys.stderr)
            phase_rows += [{"algorithm": algorithm, "scene": scene, "threads": count, "phase": name, "ms": f"{ms:.3f}"}
                           for name, ms in sorted(best.items())]
        if len(least) < len(threads):
            continue
        # The serial time is measured where the parallel code runs as it does on many
        # cores: at the most threads run (with one thread, some builds take a serial path).
        one = least[1]["pass: visibility"]
        most = least[max(threads)]
        serial_fraction = most["pass: visibility serial"] / one
        amdahl = one / most["pass: visibility on 16 cores (Amdahl)"]
        for count in threads:
            ms = least[count]["pass: visibility"]
            same = len(hashes[count]) == 1 and hashes[count] == hashes[1]
            if not same:
                differing.append((algorithm, scene, count))
            rows.append({"algorithm": algorithm, "scene": scene, "threads": count, "visibility ms": f"{ms:.2f}",
                         "speed-up": f"{one / ms:.2f}", "efficiency": f"{one / ms / count:.2f}",
                         "serial ms": f"{least[count]['pass: visibility serial']:.2f}",
                         "serial fraction": f"{serial_fraction:.3f}", "Amdahl speed-up on 16": f"{amdahl:.1f}",
                         "same bits as 1 thread": "yes" if same else "NO"})

if not rows:
    fail("nothing was rendered: " + "; ".join(f"{a} on {s}: {reason}" for a, s, reason in refused))

def write_csv(name, table):
    with open(f"{options.out}/{name}", "w", newline="") as file:
        if table:
            writer = csv.DictWriter(file, fieldnames=list(table[0]))
            writer.writeheader()
            writer.writerows(table)
write_csv("scaling.csv", rows)
write_csv("phases.csv", phase_rows)

# The table: a row per algorithm and scene, a column per thread count.
processor = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")), "unknown CPU") \
    if os.path.exists("/proc/cpuinfo") else "unknown CPU"
lines = [f"{processor}, {cores} cores; {options.size}; the least of {options.runs} fresh runs of `hsr render --stats`, "
         "\"pass: visibility time\" (ms); serial fraction: the serial time at the most threads over the one-thread time; "
         "Amdahl's speed-up on 16 cores from it, each parallel loop spread over at most its items", "",
         "| algorithm | scene | " + " | ".join(f"{t} thread{'s' if t > 1 else ''} ms (speed-up)" for t in threads) +
         " | serial fraction | Amdahl on 16 | same bits |",
         "| --- | --- | " + " | ".join("---" for _ in threads) + " | --- | --- | --- |"]
for scene in scenes:
    for algorithm in algorithms:
        mine = [row for row in rows if row["algorithm"] == algorithm and row["scene"] == scene]
        if not mine:
            continue
        cells = [next((f"{row['visibility ms']} ({row['speed-up']})" for row in mine if row["threads"] == t), "") for t in threads]
        lines.append(f"| {algorithm} | {scene} | " + " | ".join(cells) + f" | {mine[0]['serial fraction']} | "
                     f"{mine[0]['Amdahl speed-up on 16']} | {'yes' if all(r['same bits as 1 thread'] == 'yes' for r in mine) else 'NO'} |")
if refused:
    lines += ["", "Refused (the algorithm's own limits, as `hsr render` says them):"]
    prefix = "hsr: error: "
    lines += [f"- {algorithm} on {scene}: {reason[len(prefix):] if reason.startswith(prefix) else reason}"
              for algorithm, scene, reason in refused]
open(f"{options.out}/scaling.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))

# The plot: speed-up against threads, an algorithm a line, a panel a scene.
plot = [f"set terminal pngcairo size {420 * len(scenes)},420 font ',9'", f"set output '{options.out}/speedup.png'",
        f"set multiplot layout 1,{len(scenes)}", "set datafile separator ','", "set key top left font ',8'",
        f"set xrange [1:{max(threads)}]", f"set yrange [0:{max(threads) * 1.1}]", "set xlabel 'threads'",
        "set ylabel 'speed-up of the visibility pass'", "set grid", "set termoption noenhanced"]
for scene in scenes:
    plot.append(f"set title '{scene}, {options.size}'")
    curves = ["x title 'ideal' dashtype 2 linecolor 'grey'"]
    for number, algorithm in enumerate(algorithms):  # an algorithm keeps its colour and mark in every panel
        points = [row for row in rows if row["algorithm"] == algorithm and row["scene"] == scene]
        if points:
            data = f"{work}/{scene}-{algorithm}.csv"
            open(data, "w").write("".join(f"{row['threads']},{row['speed-up']}\n" for row in points))
            curves.append(f"'{data}' using 1:2 with linespoints linetype {number + 1} title '{algorithm}'")
    plot.append("plot " + ", ".join(curves))
subprocess.run(["gnuplot"], input="\n".join(plot) + "\n", text=True, check=True)
print(f"\nwrote {options.out}/scaling.csv, phases.csv, scaling.md and speedup.png", file=sys.stderr)
if differing:
    print("scaling.sh: images differ between thread counts: " +
          "; ".join(f"{a} on {s} at {t} threads" for a, s, t in differing), file=sys.stderr)
    sys.exit(1)
PY
