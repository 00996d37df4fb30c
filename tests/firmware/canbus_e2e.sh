#!/usr/bin/env bash
# End to end over spread-canbus with the real executables as separate processes: the bus, the ECU
# (firmware_sim --can unix:PATH) and the tractor (spread-tractor can --iface unix:PATH). The tractor waits
# for the ECU's address claim, sets 700 r/min (DDI 389) with acknowledge and requests DDI 389 back; the
# ECU's PDACK and its answer must reach the tractor. Then a second ECU with a lower NAME claims the same
# address: the first must lose it (ISO 11783-5 contention) and say cannot-claim. Passes only on the final
# "canbus e2e: ok" line.
# Usage: canbus_e2e.sh SPREAD_CANBUS FIRMWARE_SIM SPREAD_TRACTOR
set -eu
canbus=$1
firmware_sim=$2
tractor=$3
. "$(dirname "$0")/canbus_fixture.sh"
start_canbus "$canbus" canbus-e2e 25
"$firmware_sim" --no-lcm --can "unix:$bus" --duration 20 >"$dir/ecu.log" 2>&1 &
ecu=$!
pids+=($ecu)
out=$("$tractor" can --iface "unix:$bus" --ack --set 389=7000000 --request 389 --duration 1.5)
printf '%s\n' "$out"
# The claim (the tractor waited for it), the PDACK of the set-value, the value answered to the request.
grep -q "rx 0x80->0xFF address claimed" <<<"$out" || { echo "FAIL: no address claim from the ECU"; exit 1; }
grep -q "rx 0x80->0x81 PD acknowledge of set value and acknowledge element 0 DDI 389 (set-point revolutions): ok" <<<"$out" || { echo "FAIL: no PDACK for DDI 389"; exit 1; }
grep -q "rx 0x80->0x81 PD value element 0 DDI 389 set-point revolutions = 700.0000 r/min" <<<"$out" ||
  { echo "FAIL: no answer with DDI 389 = 700 r/min"; exit 1; }
# Serial 1 (the NAME's identity number) < 0x1234: the newcomer's NAME is lower and wins 0x80.
"$firmware_sim" --no-lcm --can "unix:$bus" --serial 1 --duration 1 >"$dir/ecu2.log" 2>&1
kill -INT "$ecu"  # firmware_sim stops on SIGINT and prints its summary
wait "$ecu" || true
cat "$dir/ecu.log" "$dir/ecu2.log"
# Cannot-claim twice: on losing, and in answer to the newcomer's request for every claim once its own
# stood (ISO 11783-5 §4.4.4.3: a function without an address answers that request with cannot-claim).
grep -Eq "ISOBUS address none, last 0xFE, claims sent [0-9]+, contentions won 0 lost 1, cannot-claim sent 2" "$dir/ecu.log" ||
  { echo "FAIL: the first ECU did not give up 0x80 to the lower NAME"; exit 1; }
grep -q "NAME 0x200A800000000001 " "$dir/ecu2.log" || { echo "FAIL: --serial 1 is not the NAME's identity"; exit 1; }
grep -Eq "ISOBUS address 0x80, claims sent [0-9]+, contentions won 0 lost 0" "$dir/ecu2.log" ||
  { echo "FAIL: the second ECU does not hold 0x80"; exit 1; }
echo "canbus e2e: ok"
