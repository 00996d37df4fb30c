#!/usr/bin/env bash
# Set up (packages, configure, build the two programs it runs), then the main job on the bundled default:
# build the DEM launch table of scenes/default.toml (9 runs on both cores), predict the spread pattern,
# print the widths with their 95 % intervals, write the plots.
# Outputs go to out/ (override with OUT=dir). Extra arguments go to `spread predict`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${OUT:-$root/out}
"$root/tools/setup.sh" "$root/build" lookup_builder spread
mkdir -p "$out"
bin=$root/build
# A fresh table each time (an existing file would be extended, not rebuilt), swapped in when complete.
rm -f "$out/default.sqlite.new" "$out/default.sqlite.new-journal"
"$bin/lookup_builder/lookup_builder" "$root/scenes/default.toml" --output "$out/default.sqlite.new" --jobs 2
mv -f "$out/default.sqlite.new" "$out/default.sqlite"
"$bin/tools/spread/spread" inspect "$out/default.sqlite"
material=${MATERIAL:-Urea}
rpm=${RPM:-600}
"$bin/tools/spread/spread" predict --tables "$out/default.sqlite" --material "$material" --rpm "$rpm" "$@"
# The same machine with the drop point turned +45 degrees, the setting of docs/building-tables.md
# "Choosing the drop point": one band of bout widths at CV <= 10 % for every material and row.
echo "with the drop point turned +45 degrees (docs/building-tables.md \"Choosing the drop point\"):"
"$bin/tools/spread/spread" predict --tables "$out/default.sqlite" --material "$material" --rpm "$rpm" \
  --drop-point-turn 45 --cv-target 10
"$bin/tools/spread/spread" plot --tables "$out/default.sqlite" --material "$material" --rpm "$rpm" \
  --out "$out/default"
