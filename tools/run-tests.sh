#!/usr/bin/env bash
# Set up (packages, configure, build) and run the whole test suite. Extra arguments go to ctest,
# e.g. tools/run-tests.sh -L flight
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/setup.sh" "$root/build"
ctest --test-dir "$root/build" --output-on-failure -j2 "$@"
