#!/usr/bin/env bash
# The C API as a package, end to end: configures the C API alone (SPREAD_CAPI_ONLY) with plain cmake as
# a fresh machine would, builds and installs it into a temporary prefix, checks what the libraries
# export, then builds the documented example (tests/capi/c_api_example.c) outside the tree against the
# installed package — with pkg-config (shared), with the documented static link line, with
# find_package(spreadc) (both targets) — and runs each on a launch-table file.
# Usage: package_test.sh SOURCE_DIR WORK_DIR TABLE.sqlite EXAMPLE.c [BUILD_DIR]
# With BUILD_DIR, an existing SPREAD_CAPI_ONLY build is checked, built and installed instead of configuring
# one in WORK_DIR (tools/check-build-options.sh's capi-only configuration: the C API compiled once).
set -euo pipefail
src=$1 work=$2 table=$3 example=$4 build=${5:-}
fail() { echo "package: FAIL: $*"; exit 1; }
rm -rf "$work"
mkdir -p "$work"

if [ -z "$build" ]; then
  build=$work/build
  cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSPREAD_CAPI_ONLY=ON >"$work/configure.log" ||
    { cat "$work/configure.log"; fail "configure with SPREAD_CAPI_ONLY=ON"; }
fi
grep -q "^SPREAD_CAPI_ONLY:BOOL=ON" "$build/CMakeCache.txt" || fail "$build is not configured with SPREAD_CAPI_ONLY=ON"
# Only the C API's dependencies were looked for.
for dep in tomlplusplus CLI11 nlohmann_json GTest benchmark CAIRO MPI LCM; do
  if grep -q "^${dep}_\(DIR\|FOUND\|LIBRARY\|INCLUDE\)" "$build/CMakeCache.txt"; then
    fail "SPREAD_CAPI_ONLY configure looked for $dep"
  fi
done
cmake --build "$build" -j2 >"$work/build.log" || { tail -50 "$work/build.log"; fail "build"; }
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log" || { cat "$work/install.log"; fail "install"; }

prefix=$work/prefix
so=$(find "$prefix" -name libspreadc.so.0)
[ -n "$so" ] || fail "no libspreadc.so.0 installed"
libdir=$(dirname "$so")
for f in "$prefix/include/spread/spread.h" "$libdir/libspreadc.a" "$libdir/libspreadc.so" "$libdir/pkgconfig/spreadc.pc" \
         "$libdir/cmake/spreadc/spreadcConfig.cmake"; do
  [ -e "$f" ] || fail "not installed: $f"
done

# The shared library: its SONAME, and only the C API exported (no C++ internals, no test hook).
readelf -d "$so" | grep -q "SONAME.*\[libspreadc.so.0\]" || fail "SONAME is not libspreadc.so.0"
nm -D --defined-only "$so" | awk '$2 != "A" {print $3}' | sed 's/@.*//' | sort >"$work/exports.txt"
others=$(grep -v '^spread_' "$work/exports.txt" || true)
[ -z "$others" ] || fail "exported besides spread_*: $(echo "$others" | head -5 | tr '\n' ' ')"
for f in spread_open spread_close spread_predict spread_trajectory spread_status_str spread_version; do
  grep -qx "$f" "$work/exports.txt" || fail "$f not exported"
done
# The archive too: pre-linked, its only globals are spread_* (and the C++ library's own "unique"
# symbols from its headers, which bind to one copy per program whatever the archive does).
nm --defined-only --extern-only "$libdir/libspreadc.a" | awk 'NF == 3 && $2 != "u" {print $3}' >"$work/archive_globals.txt"
others=$(grep -v '^spread_' "$work/archive_globals.txt" || true)
[ -z "$others" ] || fail "libspreadc.a has globals besides spread_*: $(echo "$others" | head -5 | tr '\n' ' ')"
grep -qx spread_predict "$work/archive_globals.txt" || fail "spread_predict not in libspreadc.a"
for lib in "$so" "$libdir/libspreadc.a"; do
  if nm -C "$lib" 2>/dev/null | grep -q arm_internal_fault_for_test; then fail "test fault seam in $lib"; fi
done
echo "package: libspreadc.so.0 exports $(wc -l <"$work/exports.txt") symbols, libspreadc.a $(wc -l <"$work/archive_globals.txt"), all spread_*"

check_run() {  # program, whether it must link libspreadc.so.0 dynamically
  local needed
  needed=$(readelf -d "$1" | grep -c "NEEDED.*libspreadc" || true)
  if [ "$2" = shared ] && [ "$needed" -eq 0 ]; then fail "$1 does not use libspreadc.so.0"; fi
  if [ "$2" = static ] && [ "$needed" -ne 0 ]; then fail "$1 needs libspreadc.so.0 though linked statically"; fi
  "$1" "$table" >"$1.out" || { cat "$1.out"; fail "$1 exited $?"; }
  grep -Eq "working width [0-9.]+ m" "$1.out" || { cat "$1.out"; fail "$1 printed no working width"; }
  # A missing file is a C++ exception thrown and caught inside the library: it must still come out as
  # its status (exception tables and type information survive the pre-link and the hiding).
  if "$1" "$(dirname "$table")/no-such-table.sqlite" >"$1.missing" 2>&1; then fail "$1 opened a missing file"; fi
  grep -q "SPREAD_ERROR_FILE_MISSING" "$1.missing" || { cat "$1.missing"; fail "$1: no FILE_MISSING for a missing file"; }
  echo "package: $(basename "$1") ($2): $(head -1 "$1.out")"
}
cflags=(-std=c99 -Wall -Wextra -pedantic -Werror)

export PKG_CONFIG_PATH=$libdir/pkgconfig
# shellcheck disable=SC2046  # pkg-config's output is meant to be split
cc "${cflags[@]}" "$example" $(pkg-config --cflags --libs spreadc) -Wl,-rpath,"$libdir" -o "$work/example_pkgconfig" ||
  fail "build with pkg-config"
check_run "$work/example_pkgconfig" shared
for l in -lsqlite3 -lstdc++ -lm; do
  pkg-config --static --libs spreadc | grep -q -- "$l" || fail "pkg-config --static --libs spreadc lacks $l"
done
# The one archive and the documented dependencies are all a static link needs.
# shellcheck disable=SC2046
cc "${cflags[@]}" "$example" $(pkg-config --cflags spreadc) -L"$libdir" -Wl,-Bstatic -lspreadc -Wl,-Bdynamic \
  -lsqlite3 -lstdc++ -lm -pthread -o "$work/example_static" || fail "static link with -lspreadc -lsqlite3 -lstdc++ -lm -pthread"
check_run "$work/example_static" static

cmake -S "$(dirname "$0")/package_consumer" -B "$work/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
  -DSPREAD_EXAMPLE_C="$example" >"$work/consumer.log" || { cat "$work/consumer.log"; fail "find_package(spreadc)"; }
cmake --build "$work/consumer" >>"$work/consumer.log" || { cat "$work/consumer.log"; fail "build with find_package"; }
check_run "$work/consumer/example_spreadc" shared
check_run "$work/consumer/example_spreadc_static" static
echo "package: ok"
