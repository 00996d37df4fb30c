#!/usr/bin/env bash
# Measurement helper (docs/can-integration.md, "Network management"): not a test; BIN_DIR holds spread-canbus,
# spread-tractor and firmware_sim.
# Usage: tc_first.sh BIN_DIR N  -- the TC (spread-tractor tc) on the bus 0.5-5 s before the ECU, N starts.
# Per start: did the ECU report the TC's rate set-point back (DDI 7 = 250 kg/ha), and did the ECU's claim
# follow its own global request for address claimed within 0.755 s (an independent stack's pruning window)?
bin=$1; n=$2
ok=0; claimed=0
for i in $(seq 1 "$n"); do
  d=$(python3 -c "print(0.5 + 4.5*($i-1)/max(1,$n-1))")
  dir=$(mktemp -d /tmp/tcfirst-XXXXXX); bus=$dir/bus
  "$bin/spread-canbus" "$bus" --duration 30 & cb=$!
  for _ in $(seq 100); do [ -S "$bus" ] && break; sleep 0.05; done
  "$bin/spread-tractor" tc --iface "unix:$bus" --speed 3 --rate 250 --width 24 --rpm 700 --sections 11110000 \
     --work-state on --duration "$(python3 -c "print($d+9)")" --connect-timeout 20 >"$dir/tc.out" 2>&1 & tc=$!
  sleep "$d"
  "$bin/firmware_sim" --no-lcm --can "unix:$bus" --duration 8.5 --record "$dir/ecu.candump" >"$dir/ecu.log" 2>&1
  wait $tc
  kill $cb 2>/dev/null; wait $cb 2>/dev/null
  sp=0; grep -q "DDI 7 actual mass per area = 25000" "$dir/tc.out" && sp=1
  cl=$(python3 - "$dir/ecu.candump" <<'PY'
import sys,re
req=None; ok=0
for line in open(sys.argv[1]):
    m=re.match(r"\((\d+\.\d+)\) \S+ ([0-9A-F]{8})#",line)
    if not m: continue
    t=float(m.group(1)); cid=m.group(2)
    if cid=="18EAFF80" and req is None: req=t
    elif cid=="18EEFF80" and req is not None and t-req<=0.755: ok=1; break
print(ok)
PY
)
  ok=$((ok+sp)); claimed=$((claimed+cl))
  echo "start $i: ECU $d s after the TC: set-point delivered $sp, own claim after own request $cl"
  rm -rf "$dir"
done
echo "summary: $ok of $n starts delivered the set-point; $claimed of $n answered their own global request"
