#!/usr/bin/env bash
# Writes the student edition of an exercise: a copy of the suite (the last commit) in
# which every region of the exercise's algorithm folder marked
#     // BEGIN SOLUTION
#     ...the solution...
#     // SKELETON
#     // ...the skeleton, commented out...
#     // END SOLUTION
# holds its skeleton instead. The edition builds and runs, and fails the exercise's
# tests (its ctest label, and hsr grade) until the student writes the code; the exact
# reference, the other algorithms and the grader are as shipped; the answer key and the
# bug catalogue are left out. It is made from the last commit: commit a change first.
#   bash scripts/student_edition.sh EXERCISE OUT
# Then: cd OUT && bash scripts/build.sh && ./build/hsr grade algorithms/FOLDER --exercise EXERCISE
set -euo pipefail
checkout=$(cd "$(dirname "$0")/.." && pwd)
exercise=${1:?usage: student_edition.sh EXERCISE OUT}
out=${2:?usage: student_edition.sh EXERCISE OUT}
case "$exercise" in
  1) folder=zbuffer ;;
  *) echo "student_edition.sh: error: exercise $exercise has no regions marked BEGIN SOLUTION yet; expected 1" >&2; exit 2 ;;
esac
if [ -e "$out" ]; then
  echo "student_edition.sh: error: $out exists; expected a new folder" >&2
  exit 2
fi
mkdir -p "$out"
git -C "$checkout" archive HEAD | tar -x -C "$out"
# Not for students: the answer key, and the bug catalogue (its mutations quote the
# solution's lines). The grader needs neither.
rm -r "$out/docs/instructors" "$out/course/bugs"
python3 - "$out/algorithms/$folder" <<'PYTHON'
import pathlib, re, sys
regions = 0
for path in sorted(pathlib.Path(sys.argv[1]).glob('*.[ch]pp')):
    lines, out, state = path.read_text().split('\n'), [], 'code'
    for number, line in enumerate(lines, 1):
        marker = line.strip()
        if marker == '// BEGIN SOLUTION':
            state = 'solution'
        elif marker == '// SKELETON' and state == 'solution':
            state = 'skeleton'
        elif marker == '// END SOLUTION' and state == 'skeleton':
            state, regions = 'code', regions + 1
        elif state == 'skeleton':
            if not re.match(r'\s*// ?', line):
                sys.exit(f'{path}:{number}: a skeleton line that is not commented out')
            out.append(re.sub(r'^(\s*)// ?', r'\1', line, count=1))
        elif state == 'code':
            out.append(line)
    if state != 'code':
        sys.exit(f'{path}: a BEGIN SOLUTION region without its SKELETON and END SOLUTION')
    path.write_text('\n'.join(out))
print(f'{regions} regions replaced by their skeletons in {sys.argv[1]}')
PYTHON
echo "the student edition of exercise $exercise is in $out: build it with bash scripts/build.sh there, then"
echo "  ./build/hsr grade algorithms/$folder --exercise $exercise"
