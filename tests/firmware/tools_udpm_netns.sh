#!/usr/bin/env bash
# End to end with the real executables over udpm://, inside a private network namespace this script
# creates (never on the machine's interfaces): firmware_sim runs, spread-tractor sends a command and must
# see it accepted, then sends an out-of-range one and must see it rejected (exit code 3).
# Usage: tools_udpm_netns.sh FIRMWARE_SIM SPREAD_TRACTOR.  Exit 77 = skipped (no namespaces here and
# not root; as root `unshare -n` must work, so its failure fails the test). The outer run passes only
# when the inner one printed its final "ok" line: exit status 0 alone is not enough.
set -u
firmware_sim=$1
tractor=$2
if [ -z "${SPREAD_FIRMWARE_IN_NETNS:-}" ]; then
  if ! unshare -n true 2>/dev/null; then
    if [ "$(id -u)" -eq 0 ]; then
      echo "FAIL: running as root, yet unshare -n is not permitted"
      exit 1
    fi
    echo "skipped: unshare -n is not permitted here"
    exit 77
  fi
  inner=$(env SPREAD_FIRMWARE_IN_NETNS=1 unshare -n "$0" "$@" 2>&1)
  rc=$?
  printf '%s\n' "$inner"
  if [ $rc -ne 0 ]; then
    echo "FAIL: the run inside the namespace exited $rc"
    exit 1
  fi
  case "$inner" in
    *"tools over udpm: ok"*) exit 0 ;;
    *) echo "FAIL: the run inside the namespace did not report 'tools over udpm: ok'"; exit 1 ;;
  esac
fi
set -e
ip link set lo up
ip link set lo multicast on
ip route add 224.0.0.0/4 dev lo
url='udpm://239.255.76.67:7712?ttl=0'  # port reserved for this test
# Heartbeats on a channel named in full (--heartbeat-channel), the others from the prefix.
"$firmware_sim" --lcm-url "$url" --channel-prefix TOOLS_ --heartbeat-channel TOOLS_BEAT --duration 8 &
ecu=$!
trap 'kill $ecu 2>/dev/null || true' EXIT
"$tractor" lcm --lcm-url "$url" --channel-prefix TOOLS_ --once --rate 200 --width 24 --speed 3.333 \
  --rpm 700 --material urea --off 8 | tee /dev/stderr | grep -q "sections=11111110"
# The border mode over LCM: taken and reported (no tables here to set a disc apart with: not applied).
"$tractor" lcm --lcm-url "$url" --channel-prefix TOOLS_ --once --rate 200 --width 24 --speed 3.333 \
  --rpm 700 --material urea --border right --border-gap 1 | tee /dev/stderr | grep -q " border=right "
set +e
"$tractor" lcm --lcm-url "$url" --channel-prefix TOOLS_ --once --rate 200 --width 24 --speed 3.333 \
  --rpm 9000 --material urea --timeout 1
rc=$?
set -e
if [ $rc -ne 3 ]; then
  echo "expected exit code 3 (rejected) for rpm 9000, got $rc"
  exit 1
fi
# Full channel names override another prefix: the command must still be accepted.
"$tractor" lcm --lcm-url "$url" --channel-prefix ELSEWHERE_ --command-channel TOOLS_COMMAND \
  --status-channel TOOLS_STATUS --once --rate 200 --width 24 --speed 3.333 --rpm 650 --material urea |
  tee /dev/stderr | grep -q -- "->650.0 rate"
"$tractor" lcm --lcm-url "$url" --channel-prefix TOOLS_ --heartbeat-channel TOOLS_BEAT --duration 1.1 \
  --heartbeats | tee /dev/stderr | grep -q "heartbeat #"
echo "tools over udpm: ok"
