# Sourced by the end-to-end scripts on spread-canbus (canbus_e2e.sh, tc_e2e.sh): a temporary folder `dir`,
# the bus socket `bus` served by spread-canbus for BUS_DURATION_S seconds, and `pids`, every background
# process, killed (and the folder removed) when the script exits however it exits.
# Usage: start_canbus SPREAD_CANBUS NAME BUS_DURATION_S
start_canbus() {
  dir=$(mktemp -d "/tmp/$2-XXXXXX")
  bus=$dir/bus
  pids=()
  trap canbus_cleanup EXIT
  "$1" "$bus" --duration "$3" &
  pids+=($!)
  for _ in $(seq 100); do [ -S "$bus" ] && break; sleep 0.05; done
  [ -S "$bus" ] || { echo "FAIL: spread-canbus did not create $bus"; exit 1; }
}

canbus_cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$dir"
}
