#!/usr/bin/env bash
# The student editions (scripts/student_edition.sh): for every exercise with regions
# marked BEGIN SOLUTION, the edition's algorithm folder, skeletons in place of the
# solution, builds into an hsr of its own and fails the exercise's test, saying that
# nothing is drawn; the shipped folder passes the same test. An exercise without such
# regions gets one line naming those with them, and no folder.
#   student_edition.sh HSR CHECKOUT WORK [all]
# ctest builds three editions, one of each kind of algorithm (a rasterizer, a ray caster,
# a line drawing: about 30 s each, built and graded); `all` builds every one (docs/testing.md).
set -euo pipefail
hsr=$1 checkout=$2 work=$3
editions="1 3 4 5 14 15 16"
built="1 3 5"
[ "${4:-}" = all ] && built=$editions
rm -rf "$work"
mkdir -p "$work"
status=0
bash "$checkout/scripts/student_edition.sh" 2 "$work/none" 2> "$work/none.txt" || status=$?
[ "$status" -eq 2 ] && [ ! -e "$work/none" ] || { echo "exercise 2 has no edition: expected exit status 2 and no folder, got $status" >&2; exit 1; }
if ls -A "$work" | grep -q '^\.student-edition'; then echo "a scratch folder was left beside OUT" >&2; exit 1; fi
grep -qx "student_edition.sh: error: exercise 2 has no regions marked BEGIN SOLUTION; expected one of ${editions// /, }" "$work/none.txt" ||
  { cat "$work/none.txt"; echo "expected the exercises with editions to be exactly $editions" >&2; exit 1; }
for exercise in $built; do
  edition="$work/edition-$exercise"
  bash "$checkout/scripts/student_edition.sh" "$exercise" "$edition" > "$work/made-$exercise.txt"
  folder=$(sed -n 's/^  \.\/build\/hsr grade \(.*\) --exercise .*/\1/p' "$work/made-$exercise.txt")
  if grep -rq 'BEGIN SOLUTION' "$edition/algorithms"; then echo "exercise $exercise: a solution region is left" >&2; exit 1; fi
  grep -rq "Exercise $exercise:" "$edition/$folder" || { echo "exercise $exercise: no skeleton in $folder" >&2; exit 1; }
  [ "$(stat -c %a "$edition")" = 755 ] || { echo "exercise $exercise: the edition's folder is not readable by all" >&2; exit 1; }
  for secret in docs/instructors course/bugs; do
    if [ -e "$edition/$secret" ]; then echo "exercise $exercise: the edition holds $secret" >&2; exit 1; fi
  done
  test=visible/cube cause='- nothing drawn'
  [ "$exercise" = 5 ] && test=visible/blocks cause='- (drawn though hidden|hidden though visible)'
  status=0
  "$hsr" grade "$edition/$folder" --exercise "$exercise" --test "$test" --out "$work/report-$exercise" > "$work/output-$exercise.txt" 2>&1 || status=$?
  cat "$work/output-$exercise.txt"
  [ "$status" -eq 1 ] || { echo "exercise $exercise: expected the edition to fail its test (exit 1), got $status" >&2; exit 1; }
  grep -q "FAILED $test" "$work/output-$exercise.txt"
  grep -qE -- "$cause" "$work/report-$exercise/results.json"
  "$hsr" grade "$checkout/$folder" --exercise "$exercise" --test "$test" --out "$work/shipped-$exercise" > /dev/null
  echo "exercise $exercise: the edition of $folder fails until the student writes the code; the shipped folder passes"
done
