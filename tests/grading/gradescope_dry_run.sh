#!/usr/bin/env bash
# A dry run of the Gradescope autograder (course/gradescope/run_autograder) on a fake
# /autograder: the shipped z-buffer as the submission must score full marks with the
# hidden tests, and a submission that does not build must score 0 with its reason.
#   gradescope_dry_run.sh HSR CHECKOUT WORK
set -euo pipefail
hsr=$1 checkout=$2 work=$3
rm -rf "$work" && mkdir -p "$work/source" "$work/submission"
printf 'EXERCISE=1\nSEED=20261129\n' > "$work/source/config.sh"
cp "$checkout/course/shipped/Makefile" "$checkout/course/shipped/implemented.txt" "$work/submission/"
AUTOGRADER_ROOT=$work HSR=$hsr bash "$checkout/course/gradescope/run_autograder"
listed=$("$hsr" grade --list --exercise 1 --hidden)
python3 - "$work/results/results.json" "$(echo "$listed" | wc -l)" "$(echo "$listed" | grep -c '^hidden/')" <<'PYTHON'
import json, sys
results = json.load(open(sys.argv[1]))
tests = [t for t in results['tests'] if t['name'] != 'make build']
assert len(tests) == int(sys.argv[2]), (len(tests), sys.argv[2])
assert results['score'] == len(tests) == sum(t['max_score'] for t in tests), results['score']
assert sum(t['visibility'] == 'after_published' for t in tests) == int(sys.argv[3]), 'the hidden tests show once published'
print(f"full marks: {results['score']:g} of {len(tests)} tests")
PYTHON
printf 'build:\n\texit 1\nrun:\n\ttrue\n' > "$work/submission/Makefile"
AUTOGRADER_ROOT=$work HSR=$hsr bash "$checkout/course/gradescope/run_autograder"
python3 - "$work/results/results.json" <<'PYTHON'
import json, sys
results = json.load(open(sys.argv[1]))
assert results['score'] == 0 and 'the submission did not build' in results['output'], results
print('a submission that does not build: 0, with its reason')
PYTHON
