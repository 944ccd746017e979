#!/usr/bin/env bash
# Packs a Gradescope autograder for one exercise: the zip Gradescope's "Zip file upload"
# takes, with setup.sh and run_autograder at its root and this checkout inside.
#   bash course/gradescope/make_autograder.sh EXERCISE [SEED] > autograder.zip
# SEED: the hidden tests' seed (default: a random one, printed on stderr and kept in the
# zip's config.sh; keep it from students: the same seed makes the same hidden scenes).
# It packs the last commit: commit a change first.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
checkout=$(cd "$here/../.." && pwd)
exercise=${1:?usage: make_autograder.sh EXERCISE [SEED] > autograder.zip}
seed=${2:-$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')}
echo "make_autograder.sh: exercise $exercise, hidden tests from seed $seed (also in the zip's config.sh)" >&2
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/hsr"
git -C "$checkout" archive HEAD | tar -x -C "$stage/hsr"
cp "$here/setup.sh" "$here/run_autograder" "$stage/"
printf 'EXERCISE=%s\nSEED=%s\n' "$exercise" "$seed" > "$stage/config.sh"
chmod +x "$stage/setup.sh" "$stage/run_autograder"
(cd "$stage" && python3 -c '
import os, sys, zipfile
with zipfile.ZipFile(sys.stdout.buffer, "w", zipfile.ZIP_DEFLATED) as z:
    for folder, _, files in os.walk("."):
        for name in files:
            path = os.path.join(folder, name)
            info = zipfile.ZipInfo.from_file(path, os.path.relpath(path, "."))
            with open(path, "rb") as f:
                z.writestr(info, f.read())
')
