#!/usr/bin/env bash
# The drum side by side with LAMMPS (docs/drum.md "Side by side with LAMMPS"): the same 20,250-bead drum at
# rest (in.drum / BM_DrumVerletStatic) and turning at Fr 0.1 (in.drum_rotating / BM_DrumVerlet), alternated
# run by run, on one core; then both on two cores (LAMMPS with 2 MPI ranks, ours with 2 OpenMP threads).
# Prints each run's loop time and our throughput over LAMMPS' (LAMMPS' loop time / ours).
#
# Usage: bench/peers/lammps_drum/compare.sh [build-dir] [rounds] [steps]
#   build-dir  a build with bench_drum (default: build, as tools/setup.sh makes it)
#   rounds     alternations per case (default 3); steps: timed steps per run (default 1000)
# SPREAD_REGISTERS=avx2 (or baseline) in the environment limits our side's registers (libspread/core/
# cpu_features.hpp): the figures of a processor without AVX-512 on one with it.
# Needs /usr/bin/lmp (Debian: apt-get install -y --no-install-recommends lammps) and mpirun (openmpi-bin).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
rounds=${2:-3}
steps=${3:-1000}
command -v lmp >/dev/null || { echo "compare.sh: lmp not found (apt-get install -y --no-install-recommends lammps)" >&2; exit 2; }
[ -x "$build/bench/bench_drum" ] || { echo "compare.sh: $build/bench/bench_drum not built" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && python3 "$here/make_drum_data.py" >/dev/null)
for input in in.drum in.drum_rotating; do
  sed "s/^run             200/run             $steps/" "$here/$input" > "$work/$input"
done

# LAMMPS' "Loop time of T on P procs" (s) of the timed run (the last of the input's two runs).
lammps_s() {  # input, cores
  local log="$work/log.$1.$2"
  if [ "$2" = 1 ]; then
    (cd "$work" && taskset -c 1 lmp -in "$1" -log "$log" -screen none)
  else
    (cd "$work" && mpirun --allow-run-as-root --oversubscribe -np 2 --bind-to core lmp -in "$1" -log "$log" -screen none >/dev/null)
  fi
  grep '^Loop time' "$log" | tail -1 | awk '{print $4}'
}
# bench_drum's wall time (s) of one benchmark.
ours_s() {  # benchmark name, threads
  local out="$work/ours.json" cores=1
  [ "$2" = 1 ] || cores=0,1
  SPREAD_BENCH_DRUM_STEPS=$steps SPREAD_BENCH_DRUM_THREADS=$2 taskset -c $cores "$build/bench/bench_drum" \
    --benchmark_filter="^$1/" --benchmark_out="$out" --benchmark_out_format=json >/dev/null 2>&1
  python3 -c 'import json,sys; b=json.load(open(sys.argv[1]))["benchmarks"][0]; print(b["real_time"] * {"s":1,"ms":1e-3,"us":1e-6,"ns":1e-9}[b["time_unit"]])' "$out"
}

printf '%-22s %5s %-6s %-26s %-26s %s\n' drum steps cores "LAMMPS loop (s)" "ours (s)" "throughput ours/LAMMPS"
for cores in 1 2; do
  for case in "at rest:in.drum:BM_DrumVerletStatic" "turning, Fr 0.1:in.drum_rotating:BM_DrumVerlet"; do
    IFS=: read -r label input bench <<< "$case"
    l_times=() o_times=() ratios=()
    for ((r = 0; r < rounds; ++r)); do
      l=$(lammps_s "$input" "$cores")
      o=$(ours_s "$bench" "$cores")
      l_times+=("$l") o_times+=("$(printf '%.3f' "$o")")
      ratios+=("$(python3 -c "print(f'{$l / $o:.2f}')")")
    done
    printf '%-22s %5s %-6s %-26s %-26s %s\n' "$label" "$steps" "$cores" "${l_times[*]}" "${o_times[*]}" "${ratios[*]}"
  done
done
