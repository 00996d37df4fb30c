#!/usr/bin/env bash
# Set up (packages, configure, build the two programs it runs), then the main job on the bundled default:
# build the DEM launch table of scenes/default.toml (9 runs on both cores), predict the spread pattern,
# print the widths, the CV at the stated bout and the bands with their 95 % intervals, write the plots.
# Outputs go to out/ (override with OUT=dir). Extra arguments go to `spread predict`.
#
# The table needs only lookup_builder: it is built first, and `spread` (about half of the build: the CLI, and
# the libraries only it links -- calibration, accuracy, field, plot, drum, the C API) compiles while the
# table's runs go on, so neither leaves a core idle while the other still has work (the build's last
# files, the table's last row). The build's output goes to build/main-job-spread.log, printed if it fails.
# At the end, the wall time of each part (SPREAD_TIMING=0: not printed).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${OUT:-$root/out}
bin=$root/build
started=$SECONDS
"$root/tools/setup.sh" --main-job "$bin" lookup_builder
setup_s=$((SECONDS - started))
mkdir -p "$out"
# A fresh table each time (an existing file would be extended, not rebuilt), swapped in when complete.
rm -f "$out/default.sqlite.new" "$out/default.sqlite.new-journal"
"$bin/lookup_builder/lookup_builder" "$root/scenes/default.toml" --output "$out/default.sqlite.new" --jobs 2 &
table_pid=$!
trap 'kill "$table_pid" 2>/dev/null || true' EXIT
spread_log=$bin/main-job-spread.log
echo "run-default: building spread beside the table (log: $spread_log)"
if ! cmake --build "$bin" -j2 --target spread >"$spread_log" 2>&1; then
  cat "$spread_log" >&2
  echo "run-default: building spread failed (above; log: $spread_log)" >&2
  exit 1
fi
spread_s=$((SECONDS - started - setup_s))
wait "$table_pid"
trap - EXIT
table_s=$((SECONDS - started - setup_s))
mv -f "$out/default.sqlite.new" "$out/default.sqlite"
"$bin/tools/spread/spread" inspect "$out/default.sqlite"
# The bundled machine's stated setting (scenes/default.toml, [inlet]): Urea at 600 rpm on an 11 m bout,
# judged against CV <= 10 % -- one band of bout widths from 1 m past 11 m (docs/building-tables.md
# "Choosing the drop point"). MATERIAL, RPM, WIDTH (m) and CV_TARGET (%) choose another.
material=${MATERIAL:-Urea}
rpm=${RPM:-600}
width=${WIDTH:-11}
cv_target=${CV_TARGET:-10}
"$bin/tools/spread/spread" predict --tables "$out/default.sqlite" --material "$material" --rpm "$rpm" \
  --width "$width" --cv-target "$cv_target" "$@"
"$bin/tools/spread/spread" plot --tables "$out/default.sqlite" --material "$material" --rpm "$rpm" --cv-target "$cv_target" \
  --out "$out/default"
if [ "${SPREAD_TIMING:-1}" != 0 ]; then
  echo "run-default: wall times: set-up (packages, configure, lookup_builder) ${setup_s} s; then the table" \
    "${table_s} s, spread built beside it in ${spread_s} s; prediction and plots" \
    "$((SECONDS - started - setup_s - table_s)) s; total $((SECONDS - started)) s" >&2
fi
