#!/usr/bin/env bash
# The README's test command (also CI's, via .ci/run). Stages, each timed against its budget in
# tools/ci/stage-budgets.txt (tools/ci/stage_timing.sh: a stage over budget prints a loud warning naming it):
#   setup            packages, configure, build (tools/setup.sh: gcc, -O2 with line tables)
#   suite            the whole test suite (ctest, all labels but `long`)
#   sanitizer-build  the one sanitizer build: clang, ASan + UBSan, with the libFuzzer harnesses
#                    (tools/ci/sanitizer_config.sh)
#   sanitizer-suite  the suite under the sanitizers (all labels but `long` and `nosan`)
#   fuzz             every libFuzzer harness for a fixed, seeded number of inputs (fuzz/ci-runs.txt,
#                    tools/run-fuzz.sh), on the sanitizer build's objects: nothing compiled again
#   build-options    the build options turned off, each in its own build directory
#                    (tools/check-build-options.sh)
# With arguments, only the setup and the suite run and the arguments go to ctest, e.g. tools/run-tests.sh -L flight
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -gt 0 ]; then
  "$root/tools/setup.sh" "$root/build"
  exec ctest --test-dir "$root/build" --output-on-failure -j2 "$@"
fi
. "$root/tools/ci/stage_timing.sh"
trap 'stage_summary' EXIT
stage setup "$root/tools/setup.sh" "$root/build"
stage suite ctest --test-dir "$root/build" --output-on-failure -j2 -LE long
stage sanitizer-build "$root/tools/run-sanitizers.sh" --build-only
stage sanitizer-suite "$root/tools/run-sanitizers.sh" --test-only
stage fuzz env SPREAD_FUZZ_BUDGET="${SPREAD_FUZZ_BUDGET:-$root/fuzz/ci-runs.txt}" \
  SPREAD_FUZZ_SECONDS="${SPREAD_FUZZ_SECONDS:-60}" "$root/tools/run-fuzz.sh"
stage build-options "$root/tools/check-build-options.sh"
