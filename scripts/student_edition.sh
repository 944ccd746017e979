#!/usr/bin/env bash
# Writes the student edition of an exercise: a copy of the suite (the last commit) in
# which every region of the algorithms marked
#     // BEGIN SOLUTION
#     ...the solution...
#     // SKELETON
#     // // Exercise N: ...what to write, commented out...
#     // END SOLUTION
# whose skeleton names the exercise holds its skeleton instead; the other exercises'
# regions keep their solutions (the markers and skeletons dropped). The edition builds
# and runs, and fails the exercise's tests (its ctest label, and hsr grade) until the
# student writes the code; the exact reference, the other algorithms and the grader are
# as shipped; the answer key and the bug catalogue are left out. It is made from the
# last commit: commit a change first.
#   bash scripts/student_edition.sh EXERCISE OUT
# Then: cd OUT && bash scripts/build.sh && ./build/hsr grade algorithms/FOLDER --exercise EXERCISE
set -euo pipefail
checkout=$(cd "$(dirname "$0")/.." && pwd)
exercise=${1:?usage: student_edition.sh EXERCISE OUT}
out=${2:?usage: student_edition.sh EXERCISE OUT}
if ! [[ "$exercise" =~ ^[0-9]+$ ]]; then
  echo "student_edition.sh: error: exercise '$exercise': expected a number" >&2
  exit 2
fi
if [ -e "$out" ]; then
  echo "student_edition.sh: error: $out exists; expected a new folder" >&2
  exit 2
fi
# Made beside OUT and renamed to it when whole: an error leaves no OUT behind.
mkdir -p "$(dirname "$out")"
scratch=$(mktemp -d "$(dirname "$out")/.student-edition.XXXXXX")
chmod 755 "$scratch"
trap 'rm -rf "$scratch"' EXIT
git -C "$checkout" archive HEAD | tar -x -C "$scratch"
# Not for students: the answer key, and the bug catalogue (its mutations quote the
# solution's lines). The grader needs neither.
rm -r "$scratch/docs/instructors" "$scratch/course/bugs"
# The edition's skeletons written in; prints the algorithm folder that holds them.
folder=$(python3 - "$scratch" "$exercise" <<'PYTHON'
import pathlib, re, sys
root, exercise = pathlib.Path(sys.argv[1]), sys.argv[2]
named = re.compile(r'\s*// // Exercise (\d+):')
folders, numbers = set(), set()
for path in sorted((root / 'algorithms').rglob('*.[ch]pp')):
    lines, out, state, skeleton = path.read_text().split('\n'), [], 'code', []
    for number, line in enumerate(lines, 1):
        marker = line.strip()
        if marker == '// BEGIN SOLUTION' and state == 'code':
            state, solution, skeleton = 'solution', [], []
        elif marker == '// SKELETON' and state == 'solution':
            state = 'skeleton'
        elif marker == '// END SOLUTION' and state == 'skeleton':
            exercises = {m.group(1) for m in map(named.match, skeleton) if m}
            if len(exercises) != 1:
                sys.exit(f'{path}:{number}: a skeleton names no exercise or several; expected one "// // Exercise N:" line')
            numbers |= exercises
            if exercise in exercises:
                out += [re.sub(r'^(\s*)// ?', r'\1', kept, count=1) for kept in skeleton]
                folders.add(path.parent.relative_to(root).as_posix())
            else:
                out += solution
            state = 'code'
        elif state == 'solution':
            solution.append(line)
        elif state == 'skeleton':
            if not re.match(r'\s*// ?', line):
                sys.exit(f'{path}:{number}: a skeleton line that is not commented out')
            skeleton.append(line)
        else:
            out.append(line)
    if state != 'code':
        sys.exit(f'{path}: a BEGIN SOLUTION region without its SKELETON and END SOLUTION')
    path.write_text('\n'.join(out))
def fail(message):
    print(f'student_edition.sh: error: {message}', file=sys.stderr)
    sys.exit(2)
if not folders:
    fail(f'exercise {exercise} has no regions marked BEGIN SOLUTION; expected one of {", ".join(sorted(numbers, key=int))}')
if len(folders) > 1:
    fail(f'exercise {exercise} has regions in {" and ".join(sorted(folders))}; expected one algorithm folder')
print(*folders)
PYTHON
)
mv "$scratch" "$out"
trap - EXIT
echo "the student edition of exercise $exercise is in $out ($folder with skeletons): build it with bash scripts/build.sh there, then"
echo "  ./build/hsr grade $folder --exercise $exercise"
