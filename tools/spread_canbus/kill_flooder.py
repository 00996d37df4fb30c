#!/usr/bin/env python3
"""A node that dies on spread-canbus: does the bus still send the frames it had queued?

Usage: kill_flooder.py SPREAD_CANBUS RUNS [spread-canbus options, e.g. --paced]

Per run: a bus; a listener; a flooder process that sends priority-6 frames as fast as its socket takes
them; after 1 s the flooder is SIGKILLed. The listener first drains what reached it by then, then counts the
flooder's frames that still arrive, and over what span after the kill. A real bus loses a dead node's
transmit queue at once: the count should be 0 (docs/can-integration.md).
"""
import os
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time


def connect(path):
    s = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    s.connect(path)
    return s


def run_once(exe, extra):
    d = tempfile.mkdtemp(prefix="kill-")
    path = d + "/bus"
    bus = subprocess.Popen([exe, path, "--duration", "6"] + extra, stderr=subprocess.PIPE)
    while not os.path.exists(path):
        time.sleep(0.01)
    listener = connect(path)
    pid = os.fork()
    if pid == 0:  # the flooder
        s = connect(path)
        i = 0
        while True:
            s.send(struct.pack("=IB3x8s", 0x18FF0090 | 0x80000000, 8, i.to_bytes(8, "little")))
            i += 1
    time.sleep(1.0)
    t_kill = time.monotonic()
    os.kill(pid, signal.SIGKILL)
    os.waitpid(pid, 0)
    listener.setblocking(False)
    try:  # relayed before the kill
        while True:
            listener.recv(16)
    except BlockingIOError:
        pass
    listener.settimeout(0.5)
    after = []
    try:
        while True:
            listener.recv(16)
            after.append(time.monotonic() - t_kill)
    except socket.timeout:
        pass
    bus.send_signal(signal.SIGTERM)
    summary = bus.communicate()[1].decode().strip().splitlines()[-1]
    try:
        os.rmdir(d)  # the bus removed its socket file
    except OSError:
        pass
    return len(after), (max(after) if after else 0.0) * 1000.0, summary


def main():
    exe, runs, extra = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
    results = []
    for r in range(runs):
        n, ms, summary = run_once(exe, extra)
        results.append((n, ms))
        print(f"run {r + 1}: {n} flood frames after the kill, over {ms:.0f} ms; bus: {summary}")
    print("summary:", ", ".join(f"{n} in {ms:.0f} ms" for n, ms in results))


if __name__ == "__main__":
    main()
