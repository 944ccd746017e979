#!/usr/bin/env bash
# The student edition of Exercise 1 (scripts/student_edition.sh): its z-buffer folder,
# skeletons in place of the solution, builds into an hsr of its own and fails the
# exercise's tests, saying that nothing is drawn; the shipped folder passes the same test.
#   student_edition.sh HSR CHECKOUT WORK
set -euo pipefail
hsr=$1 checkout=$2 work=$3
rm -rf "$work"
bash "$checkout/scripts/student_edition.sh" 1 "$work/edition"
if grep -q 'BEGIN SOLUTION' "$work/edition/algorithms/zbuffer/"*; then echo "a solution region is left" >&2; exit 1; fi
for secret in docs/instructors course/bugs; do
  if [ -e "$work/edition/$secret" ]; then echo "the edition holds $secret" >&2; exit 1; fi
done
status=0
"$hsr" grade "$work/edition/algorithms/zbuffer" --exercise 1 --test visible/cube --out "$work/report" > "$work/output.txt" 2>&1 || status=$?
cat "$work/output.txt"
[ "$status" -eq 1 ] || { echo "expected the edition to fail its test (exit 1), got $status" >&2; exit 1; }
grep -q 'FAILED visible/cube' "$work/output.txt"
grep -q -- '- nothing drawn' "$work/report/results.json"
"$hsr" grade "$checkout/algorithms/zbuffer" --exercise 1 --test visible/cube --out "$work/shipped" > /dev/null
echo "the edition fails until the student writes the code; the shipped folder passes"
