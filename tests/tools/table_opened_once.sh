#!/bin/sh
# Every `spread` command that works from a launch table reads the file once (tools/spread/table_session.hpp):
# each command below runs under strace, and the opens of the table file are counted — the kernel's record,
# not the program's own. `predict` runs with its guidance (the CV at 24 m is above the target), --stability
# and --size-classes, which once read the file again each.
# Usage: table_opened_once.sh SPREAD SOURCE_DIR WORK_DIR. Prints "PASS" (exit 0) or "FAIL: …" (exit 1).
set -u
spread=$1 src=$2 work=$3
command -v strace >/dev/null || { echo "FAIL: strace is not installed (tools/setup.sh installs it)"; exit 1; }
rm -rf "$work" && mkdir -p "$work"
# Under the sanitizers: LeakSanitizer cannot run under ptrace (strace); the other checks still do.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
table=$work/urea.sqlite
cp "$src/fuzz/corpus/capi_open/default_small.sqlite" "$table"
# opened_once NAME EXPECTED_STDOUT_TEXT ARGS...: the command succeeds, prints the text, and reads the table
# file once: one read is two opens of its path — the reader's check of the file's kind and header
# (libspread/io/tables/table_file.cpp, O_NONBLOCK) and SQLite's connection — so exactly one of each.
opened_once() {
  name=$1 text=$2; shift 2
  strace -f -qq -e trace=open,openat -o "$work/$name.trace" "$spread" "$@" > "$work/$name.stdout" 2> "$work/$name.stderr" ||
    { echo "FAIL: $name: exit $?"; cat "$work/$name.stderr"; exit 1; }
  grep -qF -- "$text" "$work/$name.stdout" || { echo "FAIL: $name: no '$text' in its output"; exit 1; }
  grep -F "\"$table\"" "$work/$name.trace" > "$work/$name.opens"
  checks=$(grep -c "O_NONBLOCK" "$work/$name.opens")
  connections=$(grep -vc "O_NONBLOCK" "$work/$name.opens")
  [ "$checks" -eq 1 ] && [ "$connections" -eq 1 ] ||
    { echo "FAIL: $name read $table $connections times ($checks header checks):"; cat "$work/$name.opens"; exit 1; }
}
opened_once predict "one setting at a time" predict --tables "$table" --material Urea --rpm 520 --width 24 --stability 3 --size-classes
opened_once plot "_transverse.png" plot --tables "$table" --material Urea --rpm 520 --what transverse --out "$work/plot"
opened_once chart "disc speed" chart --tables "$table" --material Urea --widths 12,18
opened_once border "border" border --tables "$table" --material Urea --rpm 520 --width 18
opened_once inspect "launch table" inspect "$table"
opened_once field "field CV" field --tables "$table" --material Urea --rpm 520 --bout 10 --rate 200 \
  --boundary "$src/scenes/field/field_am_bach.geojson"
opened_once synth "wrote" calibrate synth --tables "$table" --material Urea --rpm 520 --output "$work/synth.csv"
echo "PASS: predict, plot, chart, border, inspect, field and calibrate synth each opened the table once"
