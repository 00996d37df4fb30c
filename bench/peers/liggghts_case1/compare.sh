#!/usr/bin/env bash
# The disc side by side with LIGGGHTS on the anchor STL scene (docs/dem.md "Side by side with LIGGGHTS"):
# seed Case 1 (scenes/case1.toml) with the disc given as an STL file -- libspread's own ξ 5 mm mesh of it,
# 23,083 triangles, written by export_disc_stl.cpp and read by both codes --, 500 rpm, granules 3.2 mm
# (sd 0.6 mm) at 0.11 kg/s, fixed step 5 µs, 0.2 s simulated. One core each (taskset -c 1), alternated run by
# run in one sitting, timed on CPU (user + sys of the whole process, /usr/bin/time), so other work on the
# machine moves the wall times, not the figures compared.
#
# Ours is `spread simulate scenes/case1.toml --set machine.disc_model=stl --set machine.stl_path=… …` (the
# processor's widest registers), and the same scene through peer_ours_case1_cpu with the registers limited
# by SPREAD_BENCH_REGISTERS (bench/bench_registers.hpp): `avx` is the path of a processor without AVX-512,
# `baseline` the portable one. Printed per round: the CPU seconds, the particle-steps of each code, and
# LIGGGHTS' CPU time over ours (same simulated time; the particle-steps say how alike the two runs were).
#
# Usage: bench/peers/liggghts_case1/compare.sh [build-dir] [rounds] [duration-s]
#   build-dir   a build configured with the benchmarks (default: build, as tools/setup.sh makes it); the
#               script builds spread, peer_export_disc_stl and peer_ours_case1_cpu there
#   rounds      alternations (default 2); duration-s: simulated time (default 0.2)
#   SPREAD_PEER_REGISTERS  the limited paths to run besides the widest (default "avx baseline"; "" for none)
#   SPREAD_PEER_LOGS       a directory to keep the logs in (LIGGGHTS' log and screen, our JSON) per round
# Needs /usr/bin/liggghts (Debian: apt-get install -y --no-install-recommends liggghts) and /usr/bin/time.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
rounds=${2:-2}
duration_s=${3:-0.2}
registers=${SPREAD_PEER_REGISTERS-avx baseline}
dt_s=5e-6
command -v liggghts >/dev/null || { echo "compare.sh: liggghts not found (apt-get install -y --no-install-recommends liggghts)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "compare.sh: /usr/bin/time not found (apt-get install -y time)" >&2; exit 2; }
cmake --build "$build" -j2 --target spread peer_export_disc_stl peer_ours_case1_cpu >/dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
logs=${SPREAD_PEER_LOGS:-}
[ -z "$logs" ] || mkdir -p "$logs"

# The inputs, generated: the STL (both codes read this one file), LIGGGHTS' size classes, its input with
# `run` = duration / Δt.
(cd "$work" && "$build/bench/peer_export_disc_stl" >/dev/null)
python3 "$here/make_psd.py" | grep -v '^#' >"$work/psd.in"
steps=$(python3 -c "print(round($duration_s / $dt_s))")
sed "s/^run             40000\$/run             $steps/" "$here/in.case1_stl" >"$work/in.case1_stl"
grep -q "^run             $steps\$" "$work/in.case1_stl" || { echo "compare.sh: in.case1_stl has no 'run 40000' line" >&2; exit 2; }
scene=(machine.disc_model=stl "machine.stl_path=$work/disc_case1.stl" "numerics.dt_contact_s=$dt_s"
  "numerics.duration_s=$duration_s" numerics.threads=1 outputs.launch_csv=false outputs.pattern_png=false)
set_args=()
for s in "${scene[@]}"; do set_args+=(--set "$s"); done

# user + sys seconds of a command run on core 1; its standard output goes to $2.
cpu_of() {  # time-file, stdout-file, command...
  local tf=$1 of=$2
  shift 2
  /usr/bin/time -f '%U %S' -o "$tf" taskset -c 1 "$@" >"$of" 2>&1
  awk '{printf "%.2f", $1 + $2}' "$tf"
}
keep() {  # file, name
  [ -z "$logs" ] || cp "$1" "$logs/$2"
}

echo "processor: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'); $(nproc) cores;" \
  "AVX-512: $(grep -qw avx512f /proc/cpuinfo && echo yes || echo no)"
echo "scene: scenes/case1.toml, disc from STL ($(grep -c facet\ normal "$work/disc_case1.stl") triangles)," \
  "dt $dt_s s, $duration_s s simulated ($steps steps), one core; CPU = user + sys of the whole process"
header="round  load(1min)  LIGGGHTS CPU s  particle-steps | ours: registers   CPU s  particle-steps  LIGGGHTS/ours"
echo "$header"
for ((r = 1; r <= rounds; ++r)); do
  load=$(cut -d' ' -f1 /proc/loadavg)
  l_cpu=$( (cd "$work" && cpu_of "$work/time.l" "$work/screen.l" liggghts -in in.case1_stl -log "$work/log.l"))
  l_ps=$(python3 "$here/particle_steps.py" "$work/log.l" | sed 's/.*particle_steps \([0-9]*\).*/\1/')
  keep "$work/log.l" "log.case1_stl_$r"
  printf '%-6s %-11s %-15s %-15s|\n' "$r" "$load" "$l_cpu" "$l_ps"
  o_cpu=$(cpu_of "$work/time.o" "$work/ours.json" "$build/tools/spread/spread" simulate "$root/scenes/case1.toml" \
    "${set_args[@]}" --json)
  o_ps=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["particle_steps"])' "$work/ours.json")
  keep "$work/ours.json" "ours_simulate_$r.json"
  printf '%-6s %-11s %-15s %-15s| %-17s %-6s %-15s %s\n' "" "" "" "" "widest, simulate" "$o_cpu" "$o_ps" \
    "$(python3 -c "print(f'{$l_cpu / $o_cpu:.1f}x')")"
  for reg in $registers; do
    o_cpu=$(SPREAD_BENCH_REGISTERS=$reg cpu_of "$work/time.o" "$work/ours.txt" "$build/bench/peer_ours_case1_cpu" \
      "$root/scenes/case1.toml" "${scene[@]}")
    o_ps=$(awk '$1 == "particle_steps" {print $2}' "$work/ours.txt")
    keep "$work/ours.txt" "ours_${reg}_$r.txt"
    printf '%-6s %-11s %-15s %-15s| %-17s %-6s %-15s %s\n' "" "" "" "" "$reg" "$o_cpu" "$o_ps" \
      "$(python3 -c "print(f'{$l_cpu / $o_cpu:.1f}x')")"
  done
done
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
