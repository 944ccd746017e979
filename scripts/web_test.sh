#!/usr/bin/env bash
# The browser edition's test: builds the site (scripts/web.sh), installs the test's one
# npm package (playwright-core, which drives Debian's chromium; tests/web/package-lock.json
# pins it) when missing, and runs tests/web/web_test.mjs: the site served as README says,
# the first render timed, the controls clicked through, bad input against the command
# line's messages (build/hsr must be built), and the same bits as native in the page; then
# tests/web/steps_page_test.mjs and report_page_test.mjs: the steps page hsr render --steps
# writes and the report.html hsr compare writes, clicked through.
#   bash scripts/web_test.sh           the hard cases and 10 random scenes (what CI runs)
#   bash scripts/web_test.sh --full    every shipped scene and 100 random scenes
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh tests web
bash scripts/web.sh
if [ ! -d tests/web/node_modules/playwright-core ]; then
  command -v npm >/dev/null || bash scripts/setup.sh npm
  npm ci --prefix tests/web --no-audit --no-fund
fi
node tests/web/web_test.mjs "$@"
node tests/web/steps_page_test.mjs
node tests/web/report_page_test.mjs
