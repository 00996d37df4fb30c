#!/usr/bin/env bash
# Measurement helper (docs/can-integration.md, "Network management"): not a test; BIN_DIR holds spread-canbus,
# spread-tractor and firmware_sim.
# Usage: session.sh BIN_DIR nack|ownname|move
# spread-canbus, spread-tractor tc (first), firmware_sim 1 s later with --print-status; at 9 s after the TC a
# python injector plays the event. Prints the ECU's metered flow before/after and the TC's activations.
bin=$1; what=$2
dir=$(mktemp -d /tmp/sess-XXXXXX); bus=$dir/bus
"$bin/spread-canbus" "$bus" --duration 40 2>/dev/null & cb=$!
for _ in $(seq 100); do [ -S "$bus" ] && break; sleep 0.05; done
"$bin/spread-tractor" tc --iface "unix:$bus" --speed 3 --rate 250 --width 24 --rpm 700 --sections 11111111 \
  --work-state on --duration 30 --request-interval 5 --quiet-values >"$dir/tc.out" 2>&1 & tc=$!
sleep 1
extra=""; [ "$what" = move ] && extra=--isobus-self-configurable
"$bin/firmware_sim" --no-lcm --can "unix:$bus" --duration 28 --print-status --record "$dir/ecu.candump" $extra >"$dir/ecu.log" 2>&1 & ecu=$!
sleep 8
python3 - "$bus" "$what" <<'PY'
import socket, struct, sys, time
s = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET); s.connect(sys.argv[1])
def send(id29, data): s.send(struct.pack("=IB3x8s", id29 | 0x80000000, len(data), data.ljust(8, b"\0")))
what = sys.argv[2]
if what == "nack":
    for i in range(30):
        send(0x18E880F7, bytes([1, 0xFF, 0xFF, 0xFF, 0x80, 0x00, 0xCB, 0x00])); time.sleep(0.1)
elif what == "ownname":
    name = (0x200A800000001234).to_bytes(8, "little")
    send(0x18EEFF95, name); time.sleep(0.5); send(0x18EEFF95, name)
elif what == "move":
    send(0x18EEFF80, (1).to_bytes(8, "little"))
PY
wait $ecu; wait $tc; kill $cb 2>/dev/null; wait $cb 2>/dev/null
echo "== $what: ECU status lines (t, Q)"
grep -oE "t= *[0-9.]+ s|Q= *[0-9.]+" "$dir/ecu.log" | paste - - | awk 'NR%2==1' | tr '\n' ';' | head -c 2000; echo
grep -E "ISOBUS address|task controller" "$dir/ecu.log"
grep -cE "tc: client 0x8. active at" "$dir/tc.out" | sed 's/^/TC activations: /'
grep -E "active at|disconnected|connects again" "$dir/tc.out"
rm -rf "$dir"
