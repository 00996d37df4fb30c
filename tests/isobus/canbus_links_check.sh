#!/bin/sh
# spread-canbus carries frames and links no ECU code: no symbol of the ECU's namespace (spread::firmware, all of
# firmware_sim/) in the binary, while the relay's own symbols are there (so the search reads the binary at all).
# The same search must find the ECU in the ECU's own library, or it could not fail.
# Usage: canbus_links_check.sh NM SPREAD_CANBUS ECU_LIBRARY
nm=$1 canbus=$2 ecu=$3
ecu_symbols() { "$nm" -C "$1" 2>/dev/null | grep -c 'spread::firmware::'; }
relay=$("$nm" -C "$canbus" | grep -c 'spread::isobus::can::CanBusRelay::')
[ "$relay" -gt 0 ] || { echo "FAIL: no spread::isobus::can::CanBusRelay symbol in $canbus: nm read nothing"; exit 1; }
control=$(ecu_symbols "$ecu")
[ "$control" -gt 0 ] || { echo "FAIL: the search finds no ECU symbol in $ecu either"; exit 1; }
found=$(ecu_symbols "$canbus")
if [ "$found" -ne 0 ]; then
  echo "FAIL: $canbus has $found symbols of the ECU (spread::firmware::), e.g.:"
  "$nm" -C "$canbus" | grep 'spread::firmware::' | head -5
  exit 1
fi
echo "PASS: spread-canbus: $relay relay symbols, 0 of the ECU (its library has $control)"
