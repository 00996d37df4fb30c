#!/bin/sh
# The `spread` CLI's one failure mapping (tools/spread/error_exit.hpp): each class of failure, thrown by
# any command, gives one stderr line "spread <command>: error: <what>" and its exit code — 2 for input the
# user gave (scene, table or tray file, option), 1 for a good input that could not be written.
# Usage: cli_failures.sh SPREAD SOURCE_DIR WORK_DIR. Prints "PASS" (exit 0) or "FAIL: case: why" (exit 1).
set -u
spread=$1 src=$2 work=$3
table=$src/fuzz/corpus/capi_open/default_small.sqlite
mkdir -p "$work"
# expect NAME CODE STDERR_TEXT ARGS...: exit CODE, and stderr is exactly one line that starts with the
# command's name and holds STDERR_TEXT.
expect() {
  name=$1 code=$2 text=$3; shift 3
  "$spread" "$@" > "$work/$name.stdout" 2> "$work/$name.stderr"; rc=$?
  [ "$rc" -eq "$code" ] || { echo "FAIL: $name: exit $rc, expected $code"; cat "$work/$name.stderr"; exit 1; }
  [ "$(wc -l < "$work/$name.stderr")" -eq 1 ] || { echo "FAIL: $name: not one stderr line"; cat "$work/$name.stderr"; exit 1; }
  grep -qF -- "$text" "$work/$name.stderr" || { echo "FAIL: $name: no '$text' in"; cat "$work/$name.stderr"; exit 1; }
}
# Table files (spread::tables::TableError, kind missing)
expect table_missing 2 "spread predict: error: --tables '$work/none.sqlite'" \
  predict --tables "$work/none.sqlite" --material Urea --rpm 600
# Tray files (calibration::TrayCsvError: content, then a file that cannot be opened)
expect tray_content 2 "spread calibrate tray: error: $src/scenes/field/tray_test_bad_negative.csv:7: pass2_g: negative mass" \
  calibrate tray "$src/scenes/field/tray_test_bad_negative.csv"
expect tray_missing 2 "spread calibrate tray: error: $work/none.csv: cannot open the file" calibrate tray "$work/none.csv"
# Scenes (scene::SceneError)
expect scene_value 2 "spread simulate: error: $src/scenes/default.toml: machine.disc_radius_m: must be > 0, got -1" \
  simulate "$src/scenes/default.toml" --set machine.disc_radius_m=-1
# Options (spread::Error kind argument, thrown by the commands themselves)
expect option_drum 2 "spread drum: error: --sweep-froude: 'abc' is not a number" \
  drum "$src/scenes/drum.toml" --sweep-froude 0.1,abc
expect option_drum_inf 2 "spread drum: error: --sweep-froude: 'inf' is not a number" \
  drum "$src/scenes/drum.toml" --sweep-froude 0.1,inf
expect option_verify 2 "spread verify: error: unknown case 'nonsense'" verify nonsense
expect option_wind 2 "spread predict: error: --wind" predict --tables "$table" --material Urea --rpm 600 --wind 3
expect option_size_classes 2 "spread predict: error: --size-class-mm: class boundaries in mm, > 0 and increasing" \
  predict --tables "$table" --material Urea --rpm 600 --size-class-mm 3,2
expect option_size_classes_wind 2 "spread predict: error: --size-classes: not with --compensate-wind" \
  predict --tables "$table" --material Urea --rpm 600 --width 20 --wind 2,0 --compensate-wind --size-classes
# A good input whose output cannot be written (kind io): exit 1, and the text report is still printed.
expect report_write 1 "spread predict: error: --report: cannot write PDF '/proc/none.pdf'" \
  predict --tables "$table" --material Urea --rpm 600 --report /proc/none.pdf
grep -q "working width" "$work/report_write.stdout" || { echo "FAIL: report_write: the text report was dropped"; exit 1; }
echo PASS
