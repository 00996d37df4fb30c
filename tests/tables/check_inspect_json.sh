#!/bin/sh
# check_inspect_json.sh SPREAD TABLE: `spread inspect TABLE --json` lists the default scene's materials
# with their rpm rows and sample counts (built with samples_per_run = 64).
set -eu
out=$("$1" inspect "$2" --json)
for needle in '"name": "Urea"' '"name": "DAP"' '"name": "AMS standard"' '"sample_counts"' '750.0' \
              '"scene_hash"' '"software_version"' '"speed_mean"' '"source": "analytic"'; do
  printf '%s' "$out" | grep -qF "$needle" || { echo "missing $needle"; exit 1; }
done
count=$(printf '%s' "$out" | grep -c '"sample_count": 64')
# 3 materials x the default scene's 3 rpm rows (450, 600, 750).
[ "$count" -eq 9 ] || { echo "expected 9 runs of 64 samples, got $count"; exit 1; }
echo ok
