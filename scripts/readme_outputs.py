#!/usr/bin/env python3
"""The command outputs and run times README.md and docs/*.md quote, kept true to the program.

A fenced block right after a line `<!-- output of: COMMAND -->` holds what COMMAND prints
(stdout; run from the repository's root). A time written right after
`<!-- time of: COMMAND -->` ("0.50 s") is how long COMMAND takes, start to finish: the
median of three runs (one run when it takes over 20 s). The markdown files read are
README.md and every docs/*.md; each message names the file and line.

Without arguments this rewrites every block and time from fresh runs (scripts/figures.sh
calls it). With --check it only compares the blocks, times masked (any "N ms" matches any
other: they change from run to run), prints the difference and exits 1 when a block has
drifted (the test Readme.QuotedOutputsAreCurrent); times are not run then, since some
commands are studies of minutes.
"""
import argparse
import difflib
import pathlib
import re
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
MARKER = re.compile(r"^<!-- output of: (.+) -->$")
TIME = re.compile(r" *\d+(\.\d+)? ms")
TIMED = re.compile(r"<!-- time of: (.+?) -->\d+(\.\d+)? s")


def documents():
    """The markdown files whose quoted outputs and times are kept: README.md, then docs/*.md."""
    return [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))


def blocks(lines, name):
    """(command, first line of the block's body, line after its closing fence) per marker."""
    for i, line in enumerate(lines):
        match = MARKER.match(line)
        if not match:
            continue
        if i + 1 >= len(lines) or not lines[i + 1].startswith("```"):
            sys.exit(f"{name}:{i + 1}: an output marker must be followed by a fenced block")
        end = next((j for j in range(i + 2, len(lines)) if lines[j].startswith("```")), None)
        if end is None:
            sys.exit(f"{name}:{i + 2}: the fenced block after the output marker is not closed")
        yield match.group(1), i + 2, end


def run(command, hsr):
    command = command.replace("./build/hsr", hsr)
    result = subprocess.run(command, shell=True, cwd=ROOT, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"`{command}` failed ({result.returncode}): {result.stderr.strip()}")
    return result.stdout.rstrip("\n").split("\n")


def seconds(command, hsr):
    """How long COMMAND takes, formatted: the median of three runs, or one when slow."""
    command = command.replace("./build/hsr", hsr)
    times = []
    while len(times) < 3 and (not times or times[0] <= 20):
        start = time.monotonic()
        result = subprocess.run(command, shell=True, cwd=ROOT, capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit(f"`{command}` failed ({result.returncode}): {result.stderr.strip()}")
        times.append(time.monotonic() - start)
    median = sorted(times)[len(times) // 2]
    return f"{median:.2f} s" if median < 10 else f"{median:.0f} s"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--check", action="store_true", help="compare only; exit 1 on a drifted block")
    parser.add_argument("--hsr", default="./build/hsr", help="the hsr program to run")
    arguments = parser.parse_args()
    drifted = 0
    for document in documents():
        name = document.relative_to(ROOT).as_posix()
        lines = document.read_text().split("\n")
        # From the last block up, so that rewriting one leaves the earlier ones' positions.
        for command, begin, end in reversed(list(blocks(lines, name))):
            output = run(command, arguments.hsr)
            if not arguments.check:
                lines[begin:end] = output
                continue
            quoted = [TIME.sub(" # ms", line) for line in lines[begin:end]]
            fresh = [TIME.sub(" # ms", line) for line in output]
            if quoted != fresh:
                drifted += 1
                print(f"{name}:{begin}: the output of `{command}` has drifted:")
                print("\n".join(difflib.unified_diff(quoted, fresh, name, "now", lineterm="")))
        if arguments.check:
            continue
        text = "\n".join(lines)
        text = TIMED.sub(lambda match: f"<!-- time of: {match.group(1)} -->{seconds(match.group(1), arguments.hsr)}", text)
        if text != document.read_text():
            document.write_text(text)
    if arguments.check:
        sys.exit(1 if drifted else 0)


if __name__ == "__main__":
    main()
