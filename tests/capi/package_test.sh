#!/usr/bin/env bash
# The C API as a package, end to end: configures the C API alone (SPREAD_CAPI_ONLY) with plain cmake as
# a fresh machine would, builds and installs it into a temporary prefix, checks what the libraries
# export, then builds the documented example (tests/capi/c_api_example.c) outside the tree against the
# installed package — with pkg-config (shared), with the documented static link line, fully static
# (cc -static with pkg-config --static), with find_package(spreadc) (both targets) — and a C++ program
# (package_consumer/cxx_consumer.cpp) with the archive and -static-libstdc++, and runs each on a
# launch-table file.
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
# Every global symbol either library defines, in its full symbol table (not only the dynamic one): only
# spread_*. Weak template instantiations and GNU unique symbols count: either would bind to, or be taken
# by, a consumer's own copy. Type A is the shared library's version node (SPREADC_0), not a symbol.
for lib in "$so" "$libdir/libspreadc.a"; do
  globals=$work/globals_$(basename "$lib").txt
  nm -g --defined-only "$lib" | awk 'NF == 3 && $2 != "A" {print $3}' >"$globals"
  others=$(grep -v '^spread_' "$globals" || true)
  [ -z "$others" ] || fail "$(basename "$lib") has $(echo "$others" | wc -l) globals besides spread_*:" \
    "$(echo "$others" | head -5 | c++filt | tr '\n' ' ')"
  grep -qx spread_predict "$globals" || fail "spread_predict not global in $(basename "$lib")"
done
for lib in "$so" "$libdir/libspreadc.a"; do
  if nm -C "$lib" 2>/dev/null | grep -q arm_internal_fault_for_test; then fail "test fault seam in $lib"; fi
done
echo "package: libspreadc.so.0 exports $(wc -l <"$work/exports.txt") symbols, libspreadc.a $(wc -l <"$work/globals_libspreadc.a.txt"), all spread_*"

check_run() {  # program, how it links: shared | static (the archive) | static-all (-static) | static-cxx
  local needed
  needed=$(readelf -d "$1" | grep -c "NEEDED.*libspreadc" || true)
  if [ "$2" = shared ] && [ "$needed" -eq 0 ]; then fail "$1 does not use libspreadc.so.0"; fi
  if [ "$2" != shared ] && [ "$needed" -ne 0 ]; then fail "$1 needs libspreadc.so.0 though linked statically"; fi
  if [ "$2" = static-all ] && readelf -d "$1" | grep -q NEEDED; then fail "$1 is not linked statically"; fi
  if [ "$2" = static-cxx ] && readelf -d "$1" | grep -q "NEEDED.*libstdc++"; then
    fail "$1 needs libstdc++.so though linked with -static-libstdc++"
  fi
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
# Fully static, as a controller image links: the archive's private copies of the C++ runtime's inline
# and template code must not stand in for libstdc++.a's own (undefined references otherwise).
# shellcheck disable=SC2046
cc "${cflags[@]}" -static "$example" $(pkg-config --static --cflags --libs spreadc) -o "$work/example_all_static" \
  >"$work/all_static.log" 2>&1 || { cat "$work/all_static.log"; fail "cc -static with pkg-config --static"; }
check_run "$work/example_all_static" static-all
# A C++ program with its own std::string and exceptions, the archive, and libstdc++ linked statically.
# shellcheck disable=SC2046
c++ -std=c++17 -Wall -Wextra -pedantic -Werror "$(dirname "$0")/package_consumer/cxx_consumer.cpp" \
  $(pkg-config --cflags spreadc) -static-libstdc++ -L"$libdir" -Wl,-Bstatic -lspreadc -Wl,-Bdynamic \
  -lsqlite3 -lm -pthread -o "$work/cxx_consumer" >"$work/cxx_consumer.log" 2>&1 ||
  { cat "$work/cxx_consumer.log"; fail "C++ program with -static-libstdc++"; }
check_run "$work/cxx_consumer" static-cxx

cmake -S "$(dirname "$0")/package_consumer" -B "$work/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
  -DSPREAD_EXAMPLE_C="$example" >"$work/consumer.log" || { cat "$work/consumer.log"; fail "find_package(spreadc)"; }
cmake --build "$work/consumer" >>"$work/consumer.log" || { cat "$work/consumer.log"; fail "build with find_package"; }
check_run "$work/consumer/example_spreadc" shared
check_run "$work/consumer/example_spreadc_static" static
echo "package: ok"
