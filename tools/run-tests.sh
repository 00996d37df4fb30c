#!/usr/bin/env bash
# The README's test command (also CI's, via .ci/run): set up (packages, configure, build) and run
#   1. the whole test suite (ctest, all labels but `long`),
#   2. the same suite under AddressSanitizer + UndefinedBehaviorSanitizer (tools/run-sanitizers.sh),
#   3. every libFuzzer harness for a fixed, seeded number of inputs (fuzz/ci-runs.txt, tools/run-fuzz.sh).
#   4. the build options turned off, each in its own build directory (tools/check-build-options.sh).
# With arguments, only step 1 runs and the arguments go to ctest, e.g. tools/run-tests.sh -L flight
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/setup.sh" "$root/build"
if [ $# -gt 0 ]; then
  exec ctest --test-dir "$root/build" --output-on-failure -j2 "$@"
fi
ctest --test-dir "$root/build" --output-on-failure -j2 -LE long
"$root/tools/run-sanitizers.sh"
SPREAD_FUZZ_BUDGET=${SPREAD_FUZZ_BUDGET:-$root/fuzz/ci-runs.txt} SPREAD_FUZZ_SECONDS=${SPREAD_FUZZ_SECONDS:-60} \
  "$root/tools/run-fuzz.sh"
"$root/tools/check-build-options.sh"
