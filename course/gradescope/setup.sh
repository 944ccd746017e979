#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image: hsr's
# packages from the distribution (scripts/setup.sh), Python for submissions written in
# it, then hsr itself from the checkout make_autograder.sh packed into the zip.
# HSR_CHECKOUT: where that checkout is (default: /autograder/source/hsr).
set -euo pipefail
checkout=${HSR_CHECKOUT:-/autograder/source/hsr}
apt-get update
bash "$checkout/scripts/setup.sh"
apt-get install -y --no-install-recommends python3 make
cmake -S "$checkout" -B "$checkout/build" -DCMAKE_BUILD_TYPE=Release -DHSR_BUILD_TESTS=OFF -DHSR_BUILD_BENCH=OFF
cmake --build "$checkout/build" --target hsr -j "$(nproc)"
"$checkout/build/hsr" --version
