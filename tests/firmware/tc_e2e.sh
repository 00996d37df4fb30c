#!/usr/bin/env bash
# The ECU driven by a task controller, three processes on spread-canbus: the bus, the ECU
# (firmware_sim --can unix:PATH, its ISO 11783-10 TC client) and spread-tractor tc (the TC server, with
# the ground-based speed broadcast). The TC must receive the ECU's DDOP, accept and activate it, switch
# sections 1-4 on (condensed work state DDI 290 = 11110000) with the work state on, and then see the ECU
# report them: DDI 161 = sections 1-4 on, DDI 141 = on, DDI 7 = the rate. The ECU then stops (its run
# ends at 6 s): the TC must notice the missing client task message within its 6 s supervision.
# Passes only on the final "tc e2e: ok" line.
# Usage: tc_e2e.sh SPREAD_CANBUS FIRMWARE_SIM SPREAD_TRACTOR
set -eu
canbus=$1
firmware_sim=$2
tractor=$3
. "$(dirname "$0")/canbus_fixture.sh"
start_canbus "$canbus" tc-e2e 40
"$firmware_sim" --no-lcm --can "unix:$bus" --duration 6 --record "$dir/ecu.candump" >"$dir/ecu.log" 2>&1 &
pids+=($!)
status=0
"$tractor" tc --iface "unix:$bus" --speed 3 --rate 250 --width 24 --rpm 700 --sections 11110000 --work-state on \
  --duration 15 --connect-timeout 10 --print-ddop --log "$dir/as_applied.csv" >"$dir/tc.out" 2>&1 || status=$?
cat "$dir/tc.out"
echo "--- ECU"
cat "$dir/ecu.log"
echo "--- as-applied log (first lines)"
head -n 9 "$dir/as_applied.csv"
[ "$status" -eq 0 ] || { echo "FAIL: spread-tractor tc exited with $status"; exit 1; }
out=$(cat "$dir/tc.out")
grep -Eq "s  pool from 0x80 accepted: [0-9]+ bytes, [0-9]+ objects, 8 section\(s\)" <<<"$out" ||
  { echo "FAIL: the TC did not accept the ECU's pool"; exit 1; }
grep -q "tc: client 0x80 active at" <<<"$out" || { echo "FAIL: the pool was not activated"; exit 1; }
grep -q '└ DET 100 section "Section 1" element 4' <<<"$out" || { echo "FAIL: the DDOP tree lacks section 1"; exit 1; }
grep -q "tc: set DDI 290 set-point condensed work state 1-16 = sections 11110000-------- on element 1" <<<"$out" ||
  { echo "FAIL: the section set-point did not go to the boom element"; exit 1; }
grep -q "element 1 DDI 161 actual condensed work state 1-16 = sections 11110000--------" <<<"$out" ||
  { echo "FAIL: the ECU never reported sections 1-4 on (DDI 161)"; exit 1; }
grep -q "element 0 DDI 141 actual work state = on" <<<"$out" || { echo "FAIL: the ECU never reported work state on"; exit 1; }
grep -q "element 2 DDI 7 actual mass per area = 25000 mg/m2 (250.00 kg/ha)" <<<"$out" ||
  { echo "FAIL: the ECU never reported 250 kg/ha"; exit 1; }
grep -q "s  client 0x80 silent for 6 s (no client task message): disconnected" <<<"$out" ||
  { echo "FAIL: the TC did not notice the ECU going silent"; exit 1; }
grep -q '^[0-9.]*,0x80,1,161,"actual condensed work state 1-16",-65451,"sections 11110000--------"$' "$dir/as_applied.csv" ||
  { echo "FAIL: the as-applied log lacks the section states"; exit 1; }
# On the bus, as the ECU received them: the TC's end-of-message acknowledgement of the pool (TP.CM 19,
# 1CEC80F7#13...) before its object-pool transfer response (0CCB80F7#71...), ISO 11783-3 §5.10.3.3.
eoma=$(grep -n ' 1CEC80F7#13' "$dir/ecu.candump" | head -n 1 | cut -d: -f1)
answer=$(grep -n ' 0CCB80F7#71' "$dir/ecu.candump" | head -n 1 | cut -d: -f1)
[ -n "$eoma" ] && [ -n "$answer" ] ||
  { echo "FAIL: no EoMA ($eoma) or pool transfer response ($answer) on the bus"; exit 1; }
echo "pool transfer: EoMA at line $eoma of the ECU's candump, pool transfer response at line $answer"
[ "$eoma" -lt "$answer" ] || { echo "FAIL: the TC answered the pool before its EoMA"; exit 1; }
echo "tc e2e: ok"
