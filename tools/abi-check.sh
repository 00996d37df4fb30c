#!/usr/bin/env bash
# The ABI of libspreadc.so against the committed baseline capi/abi/spreadc.abi (abigail-tools).
#   tools/abi-check.sh build/capi/libspreadc.so            check (test capi.abi)
#   tools/abi-check.sh --update build/capi/libspreadc.so   rewrite the baseline: a deliberate change,
#                                                          reviewed in the diff of capi/abi/spreadc.abi
# (or: cmake --build build --target spreadc_abi_baseline). Only the public types of spread.h are kept.
# The check passes when the library equals the baseline or only adds to it: new functions, new enum
# values, fields appended to the struct_size-versioned structs (capi/abi/spreadc.abignore). It fails on
# anything else: a function removed or its signature changed, a field inserted, removed, retyped or
# moved, an enum value renumbered, a struct's size changed other than by appending.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
update=0
if [ "${1:-}" = --update ]; then update=1; shift; fi
lib=${1:?usage: tools/abi-check.sh [--update] path/to/libspreadc.so}
baseline=$root/capi/abi/spreadc.abi
suppressions=$root/capi/abi/spreadc.abignore

dump() {
  # No paths of this checkout in the XML: the baseline is compared in other trees (CI's clone).
  abidw --headers-dir "$root/capi/include/spread" --drop-private-types --exported-interfaces-only --no-corpus-path --no-comp-dir-path \
        --short-locs --out-file "$1" "$lib"
}

if [ $update -eq 1 ]; then
  dump "$baseline"
  echo "abi: baseline written to capi/abi/spreadc.abi from $lib"
  exit 0
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
dump "$tmp/current.abi"
# A baseline without the public API's functions would make every check pass: refuse it.
grep -q "name='spread_predict'" "$baseline" || { echo "abi: $baseline has no spread_predict"; exit 1; }
status=0
abidiff --no-added-syms --suppressions "$suppressions" "$baseline" "$tmp/current.abi" >"$tmp/report" || status=$?
if [ $status -ne 0 ]; then
  cat "$tmp/report"
  echo "abi: INCOMPATIBLE with capi/abi/spreadc.abi (abidiff exit $status). Existing programs would break."
  echo "abi: if this is deliberate (a new major version): tools/abi-check.sh --update $lib"
  exit 1
fi
# Additions pass; they are listed so that a reviewer sees them before the baseline is regenerated.
if ! abidiff --suppressions "$suppressions" "$baseline" "$tmp/current.abi" >"$tmp/additions"; then
  echo "abi: compatible additions not yet in the baseline:"
  cat "$tmp/additions"
fi
echo "abi: compatible with capi/abi/spreadc.abi"
