#!/usr/bin/env bash
# The one sanitizer build (default build-asan), shared by tools/run-sanitizers.sh, tools/run-fuzz.sh and
# tools/run-tests.sh: clang with AddressSanitizer + UndefinedBehaviorSanitizer and libFuzzer's coverage
# instrumentation (-fsanitize=fuzzer-no-link) on every object, so the same objects serve the test suite
# under the sanitizers and the libFuzzer harnesses (fuzz/, linked with -fsanitize=fuzzer). Compiled once.
# -O2 with line tables only: the sanitizers' reports need file:line, not variables, and line tables
# compile markedly faster than -g. Not -O1: clang 14 at -O1 leaves Eigen's fixed-size vector operations as
# calls, and the DEM tests ran 30 times slower than the plain build instead of a few.
#
# Sourced, not run:   . tools/ci/sanitizer_config.sh
#   sanitizer_configure BUILD_DIR   configure (idempotent: an existing directory keeps its generator)
#   sanitizer_environment           export the sanitizers' options for a test or fuzz run
sanitizer_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
. "$sanitizer_root/tools/ci/ccache.sh"

sanitizer_configure() {
  local build=$1 generator=()
  command -v ninja >/dev/null && generator=(-G Ninja)
  # The generator of an existing build directory cannot change; keep whatever it was configured with.
  [ -f "$build/CMakeCache.txt" ] && generator=()
  # libFuzzer needs clang; CC/CXX may name another clang.
  CC=${CC:-clang} CXX=${CXX:-clang++} cmake -S "$sanitizer_root" -B "$build" "${generator[@]}" "${spread_launcher[@]}" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
    -DCMAKE_C_FLAGS=-fsanitize=fuzzer-no-link -DCMAKE_CXX_FLAGS=-fsanitize=fuzzer-no-link \
    -DSPREAD_SANITIZE=ON -DSPREAD_BUILD_TESTS=ON -DSPREAD_BUILD_BENCH=OFF -DSPREAD_BUILD_FUZZ=ON >/dev/null
}

sanitizer_environment() {
  # halt_on_error: the first report ends the process with a non-zero status, so ctest records a failure.
  # detect_leaks: LeakSanitizer works here (also as root). abort_on_error=0 keeps the exit code path (no
  # core dumps). detect_stack_use_after_return catches returned pointers to locals.
  export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:abort_on_error=0:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:detect_odr_violation=2}
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1:report_error_type=1}
  # Leaks inside third-party libraries we cannot fix (Open MPI's MPI_Init keeps global state alive).
  export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$sanitizer_root/tests/stability/lsan.supp:print_suppressions=0}
}
