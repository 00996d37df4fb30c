#!/usr/bin/env bash
# Set up (packages, configure, build), then the main job on the bundled default: build a small launch
# table from scenes/default.toml, predict the spread pattern, print the widths, write the plots.
# Outputs go to out/ (override with OUT=dir). Extra arguments go to `spread predict`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${OUT:-$root/out}
"$root/tools/setup.sh" "$root/build"
mkdir -p "$out"
bin=$root/build
"$bin/lookup_builder/lookup_builder" "$root/scenes/default.toml" --output "$out/default.sqlite"
"$bin/tools/spread/spread" inspect "$out/default.sqlite"
material=${MATERIAL:-Urea}
rpm=${RPM:-600}
"$bin/tools/spread/spread" predict --tables "$out/default.sqlite" --material "$material" --rpm "$rpm" "$@"
"$bin/tools/spread/spread" plot --tables "$out/default.sqlite" --material "$material" --rpm "$rpm" \
  --out "$out/default"
