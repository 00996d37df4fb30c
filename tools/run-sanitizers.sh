#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build and test run. Any sanitizer report fails
# the run: ASan and UBSan halt on the first error (the build also passes -fno-sanitize-recover=undefined),
# LeakSanitizer is on. Tests labelled `long` are skipped.
#
# Usage: tools/run-sanitizers.sh [extra ctest arguments, e.g. -L stability]
# Environment:
#   SPREAD_ASAN_BUILD  build directory (default: build-asan)
#   SPREAD_JOBS        parallel build/test jobs (default: number of cores)
#   CC / CXX           compiler (default: the system's cc/c++, i.e. gcc on Debian 12; clang works too)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SPREAD_ASAN_BUILD:-$root/build-asan}
jobs=${SPREAD_JOBS:-$(nproc)}

generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
# The generator of an existing build directory cannot change; keep whatever it was configured with.
[ -f "$build/CMakeCache.txt" ] && generator=()

cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSPREAD_SANITIZE=ON \
  -DSPREAD_BUILD_TESTS=ON -DSPREAD_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j "$jobs"

# halt_on_error: the first report ends the process with a non-zero status, so ctest records a failure.
# detect_leaks: LeakSanitizer works here (also as root). abort_on_error=0 keeps the exit code path (no
# core dumps). detect_stack_use_after_return catches returned pointers to locals.
export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:abort_on_error=0:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:detect_odr_violation=2}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1:report_error_type=1}
# Leaks inside third-party libraries we cannot fix (Open MPI's MPI_Init keeps global state alive).
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/tests/stability/lsan.supp:print_suppressions=0}

ctest --test-dir "$build" --output-on-failure -j "$jobs" -LE long "$@"
