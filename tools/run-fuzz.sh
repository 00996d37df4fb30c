#!/usr/bin/env bash
# Builds the libFuzzer harnesses (fuzz/, clang, AddressSanitizer + UBSan) in the one sanitizer build
# (build-asan, tools/ci/sanitizer_config.sh: the test suite's sanitizer run uses the same objects, so after
# tools/run-sanitizers.sh nothing is compiled again) and runs each for a bounded time on its seed corpus
# (fuzz/corpus/<harness>/). Fails when any harness finds a crash,
# a broken invariant, a leak, a timeout or runs out of memory; the input is saved under
# build-asan/fuzz/artifacts/<harness>/ — add it to fuzz/regressions/<harness>/ once fixed, and the test
# suite replays it for ever after (tests/stability, ctest -L stability).
#
# Usage: tools/run-fuzz.sh [harness ...]        (default: every harness that was built)
# Environment:
#   SPREAD_FUZZ_SECONDS  run time per harness, seconds (default 30); with a budget, the cap
#   SPREAD_FUZZ_BUDGET   file of "harness runs" lines (fuzz/ci-runs.txt): each listed harness runs that
#                        many inputs from a fresh work corpus (CI mode: the same inputs on every machine)
#   SPREAD_FUZZ_SEED     libFuzzer -seed (default 1; use others for exploratory runs)
#   SPREAD_FUZZ_TIMEOUT  seconds one input may take before it counts as a hang (default 20)
#   SPREAD_FUZZ_BUILD    build directory (default: build-asan, shared with tools/run-sanitizers.sh)
#   SPREAD_JOBS          build jobs (default: number of cores)
#   CC / CXX             clang / clang++ (default); libFuzzer needs clang
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SPREAD_FUZZ_BUILD:-$root/build-asan}
seconds=${SPREAD_FUZZ_SECONDS:-30}
timeout_s=${SPREAD_FUZZ_TIMEOUT:-20}
budget_file=${SPREAD_FUZZ_BUDGET:-}
fuzz_seed=${SPREAD_FUZZ_SEED:-1}
[ -z "$budget_file" ] || [ -f "$budget_file" ] || { echo "run-fuzz: no budget file $budget_file" >&2; exit 1; }
jobs=${SPREAD_JOBS:-$(nproc)}
. "$root/tools/ci/sanitizer_config.sh"

sanitizer_configure "$build"
cmake --build "$build" -j "$jobs" --target spread_fuzzers

harnesses=("$@")
if [ ${#harnesses[@]} -eq 0 ]; then
  for exe in "$build"/fuzz/fuzz_*; do
    [ -x "$exe" ] && harnesses+=("$(basename "$exe" | sed 's/^fuzz_//')")
  done
fi
[ ${#harnesses[@]} -gt 0 ] || { echo "run-fuzz: no harness was built (is CXX clang?)" >&2; exit 1; }

export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}

failed=()
summary=()
for h in "${harnesses[@]}"; do
  exe=$build/fuzz/fuzz_$h
  seeds=$root/fuzz/corpus/$h
  work=$build/fuzz/corpus-work/$h        # new interesting inputs stay out of the source tree
  artifacts=$build/fuzz/artifacts/$h/
  log=$build/fuzz/logs/$h.log
  mkdir -p "$work" "$artifacts" "$(dirname "$log")"
  dirs=("$work")
  [ -d "$seeds" ] && dirs+=("$seeds")
  runs_limit=()
  budget=""
  [ -n "$budget_file" ] && budget=$(awk -v h="$h" '$1 == h { print $2 }' "$budget_file")
  if [ -n "$budget" ]; then
    rm -rf "$work" && mkdir -p "$work"   # the same start on every machine
    runs_limit=(-runs="$budget")
    echo "run-fuzz: $h for $budget runs (at most ${seconds}s)"
  else
    echo "run-fuzz: $h for ${seconds}s"
  fi
  status=0
  started=$SECONDS
  "$exe" -seed="$fuzz_seed" "${runs_limit[@]}" -max_total_time="$seconds" -timeout="$timeout_s" -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$artifacts" "${dirs[@]}" >"$log" 2>&1 || status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | sed 's/cov: //')
  if [ "$status" -ne 0 ]; then
    failed+=("$h")
    echo "run-fuzz: $h FAILED (exit $status), see $log and $artifacts" >&2
    grep -E "ERROR:|invariant broken|Test unit written|SUMMARY" "$log" | head -8 >&2 || true
  fi
  summary+=("$(printf '%-18s %6ss %10s runs %8s exec/s  cov %6s  %s' "$h" "$((SECONDS - started))" "${runs:-?}" "${rate:-?}" \
    "${cov:-?}" "$([ "$status" -eq 0 ] && echo ok || echo FAILED)")")
done
echo
echo "run-fuzz: summary (logs in $build/fuzz/logs)"
printf '  %s\n' "${summary[@]}"
if [ ${#failed[@]} -gt 0 ]; then
  echo "run-fuzz: findings in: ${failed[*]}" >&2
  exit 1
fi
