#!/usr/bin/env bash
# The build options tested off (docs/architecture.md, "Build options"). Each off-configuration is configured
# and built in its own build directory, only the targets its checks need, and runs what it can:
#   capi-only   SPREAD_CAPI_ONLY=ON: libspreadc.so and libspreadc.a alone; the package test
#               (tests/capi/package_test.sh: installed, only spread_* global in either library, consumed with
#               pkg-config, the static link line, cc -static, find_package and a C++ program linked with
#               -static-libstdc++); the C example of docs/c-api.md (tests/capi/c_api_example.c) compiled with cc
#               as C99 against the build tree, outside CMake. Each program runs on the committed small
#               table of the default scene (fuzz/corpus/capi_open/default_small.sqlite).
#   no-extras   SPREAD_WITH_LCM=OFF, SPREAD_WITH_MPI=OFF, SPREAD_WITH_PLOTS=OFF: spread, lookup_builder and the
#               C API tests (ctest label capi, less the DEM-built default table, the ABI and the package
#               tests, which the full build runs); checks that neither cairo, LCM nor MPI is looked for or
#               linked, that firmware_sim, bench_firmware and spread-tractor are not targets, and (ctest
#               capi.cli.plot_without_plots) that `spread plot` fails saying it was built without plots.
# The builds are unoptimised and without debug information: they check configuring, compiling, linking and
# behaviour, not speed, and -O0 compiles fastest. Prints the wall time of each configuration.
# Usage: tools/check-build-options.sh [work-dir]   (default: build-options/ in the source tree)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
work=${1:-$root/build-options}
. "$root/tools/ci/ccache.sh"
common=(-G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS_DEBUG=-O0 -DCMAKE_CXX_FLAGS_DEBUG=-O0 "${spread_launcher[@]}")
fail() { echo "build-options: FAIL: $*" >&2; exit 1; }

# Neither the cache nor the build rules may mention a dependency the configuration turned off.
check_absent() {  # build-dir, cache-variable prefix, build.ninja pattern, what
  if grep -q "^$2" "$1/CMakeCache.txt"; then fail "$(basename "$1"): configure looked for $4 ($(grep -m1 "^$2" "$1/CMakeCache.txt"))"; fi
  if grep -Eq "$3" "$1/build.ninja"; then fail "$(basename "$1"): build rules use $4 ($(grep -Eom1 "$3" "$1/build.ninja"))"; fi
}

start=$SECONDS
dir=$work/capi-only
cmake -S "$root" -B "$dir" "${common[@]}" -DSPREAD_CAPI_ONLY=ON >/dev/null
cmake --build "$dir" -j2
check_absent "$dir" "\(CAIRO\|LCM\|MPI\|tomlplusplus\|CLI11\|GTest\)_" "libcairo|-lcairo|liblcm|libmpi|toml|CLI11|gtest" \
  "a dependency the C API does not need"
# The package end to end: installed, then the C example of docs/c-api.md built outside the tree with
# pkg-config (shared), the documented static link line, cc -static and find_package(spreadc), and a C++
# program with -static-libstdc++, each run on the committed small table of the default scene.
"$root/tests/capi/package_test.sh" "$root" "$dir/package" "$root/fuzz/corpus/capi_open/default_small.sqlite" \
  "$root/tests/capi/c_api_example.c" "$dir" >"$dir/package.out" 2>&1 ||
  { cat "$dir/package.out"; fail "capi-only: the package test"; }
grep -q "^package: ok" "$dir/package.out" || { cat "$dir/package.out"; fail "capi-only: the package test did not finish"; }
cc -std=c99 -Wall -Wextra -pedantic -Werror -I"$root/capi/include" "$root/tests/capi/c_api_example.c" \
  -o "$dir/c_api_example" -L"$dir/capi" -lspreadc -Wl,-rpath,"$dir/capi"
"$dir/c_api_example" "$root/fuzz/corpus/capi_open/default_small.sqlite" >"$dir/c_api_example.out" ||
  { cat "$dir/c_api_example.out"; fail "capi-only: the C example exited $?"; }
grep -Eq "working width [0-9.]+ m" "$dir/c_api_example.out" ||
  { cat "$dir/c_api_example.out"; fail "capi-only: the C example printed no working width"; }
echo "build-options: capi-only ok ($(head -1 "$dir/c_api_example.out")); package ok ($(grep -c '^package: ' "$dir/package.out") checks) in $((SECONDS - start)) s"

start=$SECONDS
dir=$work/no-extras
cmake -S "$root" -B "$dir" "${common[@]}" -DSPREAD_WITH_LCM=OFF -DSPREAD_WITH_MPI=OFF -DSPREAD_WITH_PLOTS=OFF >/dev/null
check_absent "$dir" "CAIRO_" "libcairo|-lcairo|/cairo\b" "cairo"
check_absent "$dir" "LCM_" "liblcm|lcm_generated|lcm-gen" "LCM"
check_absent "$dir" "MPI_" "libmpi|openmpi|SPREAD_HAVE_MPI" "MPI"
for t in firmware_sim bench_firmware spread-tractor; do
  if ninja -C "$dir" -t targets all | grep -q "^$t:"; then fail "no-extras: $t is a target"; fi
done
cmake --build "$dir" -j2 --target spread lookup_builder test_capi test_capi_golden test_capi_no_alloc make_test_table \
  capi_c99 c_api_example
ctest --test-dir "$dir" --output-on-failure -j2 -L capi -E "default_scene|default_table|default_chart|default_grid|default_advice|capi\.abi" ||
  fail "no-extras: C API tests"
listed=$(ctest --test-dir "$dir" -N -R "capi\.cli\.plot_without_plots")
[[ $listed == *"Test #"*": capi.cli.plot_without_plots"* ]] || fail "no-extras: the test of \`spread plot\` without plots is not registered"
echo "build-options: no-extras ok in $((SECONDS - start)) s"
