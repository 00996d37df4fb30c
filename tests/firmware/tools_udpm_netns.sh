#!/usr/bin/env bash
# End to end with the real executables over udpm://, inside a private network namespace this script
# creates (never on the machine's interfaces): firmware_sim runs, spread-tractor sends a command and must
# see it accepted, then sends an out-of-range one and must see it rejected (exit code 3).
# Usage: tools_udpm_netns.sh FIRMWARE_SIM SPREAD_TRACTOR.  Exit 77 = skipped (no namespaces here).
set -u
firmware_sim=$1
tractor=$2
if [ -z "${SPREAD_FIRMWARE_IN_NETNS:-}" ]; then
  if ! unshare -n true 2>/dev/null; then
    echo "skipped: unshare -n is not permitted here"
    exit 77
  fi
  exec env SPREAD_FIRMWARE_IN_NETNS=1 unshare -n "$0" "$@"
fi
set -e
ip link set lo up
ip link set lo multicast on
ip route add 224.0.0.0/4 dev lo
url='udpm://239.255.76.67:7712?ttl=0'  # port reserved for this test
"$firmware_sim" --lcm-url "$url" --channel-prefix TOOLS_ --duration 8 &
ecu=$!
trap 'kill $ecu 2>/dev/null || true' EXIT
"$tractor" lcm --lcm-url "$url" --channel-prefix TOOLS_ --once --rate 200 --width 24 --speed 3.333 \
  --rpm 700 --material urea --off 8 | tee /dev/stderr | grep -q "W=21.00/24.00 m"
set +e
"$tractor" lcm --lcm-url "$url" --channel-prefix TOOLS_ --once --rate 200 --width 24 --speed 3.333 \
  --rpm 9000 --material urea --timeout 1
rc=$?
set -e
if [ $rc -ne 3 ]; then
  echo "expected exit code 3 (rejected) for rpm 9000, got $rc"
  exit 1
fi
"$tractor" lcm --lcm-url "$url" --channel-prefix TOOLS_ --duration 1.1 --heartbeats | tee /dev/stderr |
  grep -q "heartbeat #"
echo "tools over udpm: ok"
