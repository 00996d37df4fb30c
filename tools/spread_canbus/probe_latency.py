#!/usr/bin/env python3
"""Delivery latency of high-priority frames on a spread-canbus, with or without a flooding node.

Usage: probe_latency.py BUS_PATH quiet|flood

Three clients join the bus at BUS_PATH: a listener; a prober sending 400 frames with identifier
0x0CFF0010 (priority 3) 5 ms apart, each carrying its send time; and with `flood` a separate process
sending 8-byte frames with identifier 0x18FF0020 (priority 6) as fast as its socket takes them, for
2.8 s. The listener prints how many probes arrived and their latency (p50, p99, max). Run it once
against `spread-canbus PATH` and once against `spread-canbus PATH --paced` (docs/can-integration.md).
"""
import socket
import struct
import subprocess
import sys
import threading
import time

PROBE_ID = 0x0CFF0010
FLOOD_ID = 0x18FF0020
PROBES = 400

FLOODER = """
import socket, struct, sys, time
s = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
s.connect(sys.argv[1])
f = struct.pack("=IB3x8s", %d | 0x80000000, 8, bytes([0x55] * 8))
n = 0
end = time.monotonic() + float(sys.argv[2])
while time.monotonic() < end:
    s.send(f)
    n += 1
print(n)
""" % FLOOD_ID


def connect(path):
    s = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    s.connect(path)
    return s


def now_us48():
    return (time.monotonic_ns() // 1000) & 0xFFFFFFFFFFFF


def main():
    path, mode = sys.argv[1], sys.argv[2]
    listener, prober = connect(path), connect(path)
    latency_ms = {}

    def listen():
        listener.settimeout(0.5)
        while True:
            try:
                record = listener.recv(16)
            except socket.timeout:
                return
            can_id, _, data = struct.unpack("=IB3x8s", record)
            if can_id & 0x1FFFFFFF == PROBE_ID:
                seq = struct.unpack("=H", data[:2])[0]
                sent = struct.unpack("=Q", data[2:8] + b"\0\0")[0]
                latency_ms[seq] = ((now_us48() - sent) & 0xFFFFFFFFFFFF) / 1000.0

    time.sleep(0.3)
    thread = threading.Thread(target=listen)
    thread.start()
    flooder = None
    if mode == "flood":
        flooder = subprocess.Popen([sys.executable, "-c", FLOODER, path, "2.8"], stdout=subprocess.PIPE, text=True)
        time.sleep(0.3)
    for i in range(PROBES):
        data = struct.pack("=H", i) + struct.pack("=Q", now_us48())[:6]
        prober.send(struct.pack("=IB3x8s", PROBE_ID | 0x80000000, 8, data))
        time.sleep(0.005)
    thread.join()
    flood_frames = int(flooder.communicate()[0]) if flooder else 0
    values = sorted(latency_ms.values())
    if not values:
        print(f"{mode}: no probe arrived")
        return 1

    def quantile(p):
        return values[min(len(values) - 1, int(p * len(values)))]

    print(f"{mode}: probes received {len(values)}/{PROBES}, latency p50 {quantile(0.5):.3f} ms "
          f"p99 {quantile(0.99):.3f} ms max {values[-1]:.3f} ms; flood frames sent {flood_frames}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
