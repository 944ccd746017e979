#!/usr/bin/env bash
# Writes GitHub Classroom's .github/classroom/autograding.json for one exercise: a
# command-grader test per hsr grade test, passing on exit 0 (hsr grade --test NAME exits
# 0 when that test passes, 1 when it fails), a point each. The students' repository is
# the student edition (scripts/student_edition.sh); the first test's setup installs the
# packages and builds hsr there, and each test grades SUBMISSION (default: the
# exercise's algorithm folder; "." for a program with its own Makefile). The visible
# tests only: a hidden test's seed would sit in the students' repository. Run it from a
# built checkout. The grader is built from the students' own repository, where they can
# change it: for marks that count, use Gradescope (course/gradescope/).
#   bash course/github-classroom/make_autograding.sh EXERCISE [SUBMISSION] > .github/classroom/autograding.json
set -euo pipefail
checkout=$(cd "$(dirname "$0")/../.." && pwd)
exercise=${1:?usage: make_autograding.sh EXERCISE [SUBMISSION] > autograding.json}
case "$exercise" in  # the exercise's algorithm folder, in a student edition
  1|7|8) folder=algorithms/zbuffer ;;
  3) folder=algorithms/ray_casting ;;
  4) folder=algorithms/painter ;;
  5) folder=algorithms/appel ;;
  14) folder=algorithms/warnock ;;
  15) folder=algorithms/watkins ;;
  16) folder=algorithms/weiler_atherton ;;
  *) echo "make_autograding.sh: error: exercise $exercise is not graded; expected 1, 3, 4, 5, 7, 8, 14, 15 or 16" >&2; exit 2 ;;
esac
submission=${2:-$folder}
setup='sudo bash scripts/setup.sh && cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DHSR_BUILD_TESTS=OFF -DHSR_BUILD_BENCH=OFF && cmake --build build --target hsr -j 2'
"$checkout/build/hsr" grade --list --exercise "$exercise" | python3 -c '
import json, sys
exercise, submission, setup = sys.argv[1:4]
tests = []
for k, name in enumerate(sys.stdin.read().split()):
    tests.append({"name": name, "setup": setup if k == 0 else "",
                  "run": f"./build/hsr grade {submission} --exercise {exercise} --test {name} --out /tmp/grade",
                  "input": "", "output": "", "comparison": "included", "timeout": 10, "points": 1})
print(json.dumps({"tests": tests}, indent=2))
' "$exercise" "$submission" "$setup"
