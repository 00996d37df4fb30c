#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build and test run. Any sanitizer report fails
# the run: ASan and UBSan halt on the first error (the build also passes -fno-sanitize-recover=undefined),
# LeakSanitizer is on. Tests labelled `long` (minutes of physics) or `nosan` (physics regressions that
# run no code path the rest of the suite does not, e.g. the main job's full DEM table) are skipped: the
# plain suite runs them. The build is the one sanitizer build (tools/ci/sanitizer_config.sh), which also
# holds the libFuzzer harnesses that tools/run-fuzz.sh runs.
#
# Usage: tools/run-sanitizers.sh [extra ctest arguments, e.g. -L stability]
#        tools/run-sanitizers.sh --build-only          configure and build, no tests
#        tools/run-sanitizers.sh --test-only [ctest arguments]   the tests of an existing build
# Environment:
#   SPREAD_ASAN_BUILD  build directory (default: build-asan)
#   SPREAD_JOBS        parallel build/test jobs (default: number of cores)
#   CC / CXX           compiler (default: clang / clang++; libFuzzer needs clang)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SPREAD_ASAN_BUILD:-$root/build-asan}
jobs=${SPREAD_JOBS:-$(nproc)}
. "$root/tools/ci/sanitizer_config.sh"

if [ "${1:-}" != --test-only ]; then
  sanitizer_configure "$build"
  cmake --build "$build" -j "$jobs"
  [ "${1:-}" != --build-only ] || exit 0
else
  shift
fi
sanitizer_environment
ctest --test-dir "$build" --output-on-failure -j "$jobs" -LE "long|nosan" "$@"
