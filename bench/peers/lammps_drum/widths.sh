#!/usr/bin/env bash
# The drum at rest on one core (docs/drum.md "Without AVX-512"): LAMMPS, then ours with the registers limited
# to AVX-512, AVX2 and the baseline (SPREAD_REGISTERS, libspread/core/cpu_features.hpp), alternated round by
# round. Prints CPU seconds — LAMMPS' loop time times its "CPU use", ours bench_drum's CPU time — and LAMMPS'
# over ours, which on a machine shared with other work move less than wall times.
#
# Usage: bench/peers/lammps_drum/widths.sh [build-dir] [rounds]   (default: build, 3)
# Needs /usr/bin/lmp (Debian: apt-get install -y --no-install-recommends lammps).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
rounds=${2:-3}
steps=1000
command -v lmp >/dev/null || { echo "widths.sh: lmp not found (apt-get install -y --no-install-recommends lammps)" >&2; exit 2; }
[ -x "$build/bench/bench_drum" ] || { echo "widths.sh: $build/bench/bench_drum not built" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && python3 "$here/make_drum_data.py" >/dev/null)
sed "s/^run             200/run             $steps/" "$here/in.drum" > "$work/in.drum"
for ((r = 0; r < rounds; ++r)); do
  (cd "$work" && taskset -c 1 lmp -in in.drum -log "log.$r" -screen none)
  loop=$(grep '^Loop time' "$work/log.$r" | tail -1 | awk '{print $4}')
  cpu=$(grep '% CPU use' "$work/log.$r" | tail -1 | sed 's/%.*//' | awk '{print $NF}')
  l=$(python3 -c "print(f'{$loop * $cpu / 100:.3f}')")
  line="round $((r + 1)): LAMMPS $l"
  for registers in avx512 avx2 baseline; do
    SPREAD_REGISTERS=$registers SPREAD_BENCH_DRUM_STEPS=$steps SPREAD_BENCH_DRUM_THREADS=1 taskset -c 1 "$build/bench/bench_drum" \
      --benchmark_filter='^BM_DrumVerletStatic/' --benchmark_out="$work/ours.json" --benchmark_out_format=json >/dev/null 2>&1
    o=$(python3 -c 'import json,sys; b=json.load(open(sys.argv[1]))["benchmarks"][0]; print(b["cpu_time"] * {"s":1,"ms":1e-3,"us":1e-6,"ns":1e-9}[b["time_unit"]])' "$work/ours.json")
    line="$line | $registers $(printf '%.3f' "$o") ($(python3 -c "print(f'{$l / $o:.2f}')")x)"
  done
  echo "$line"
done
