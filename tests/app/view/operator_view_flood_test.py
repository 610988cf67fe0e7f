#!/usr/bin/python3
"""The flood: `rovctl sim --serve` held for 20 s, once without viewers and once with N
stream connections (camera and events alternately, read by one client thread); ABORT is posted
10 times in each run and must be answered 200 within 100 ms, and the tick's overruns (the run's
own telemetry, skipped_total) with streams may exceed those without by at most 1 % of ticks.

usage: operator_view_flood_test.py ROVCTL [--streams 300]   (about 50 s)
"""
import argparse
import csv
import os
import re
import socket
import subprocess
import sys
import tempfile
import threading
import time


def run(rovctl, streams):
    out = tempfile.mkdtemp(prefix="rovctl-view-flood-")
    p = subprocess.Popen([rovctl, "sim", "--serve", "127.0.0.1:0", "--token", "t", "--hold",
                          "--realtime", "--max-time", "20", "--out", out, "--serve-linger", "0"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    port = None
    for line in p.stderr:
        m = re.search(r"operator view at http://[\d.]+:(\d+)/", line)
        if m:
            port = int(m.group(1))
            break
    if port is None:
        sys.exit("rovctl did not start the view")
    threading.Thread(target=lambda: [None for _ in p.stderr], daemon=True).start()
    time.sleep(3)
    socks = []
    for i in range(streams):
        s = socket.create_connection(("127.0.0.1", port))
        path = b"/stream.mjpg" if i % 2 == 0 else b"/events"
        s.sendall(b"GET " + path + b" HTTP/1.1\r\nHost: x\r\n\r\n")
        s.setblocking(False)
        socks.append(s)
    stop = threading.Event()

    def drain():
        while not stop.is_set():
            for s in socks:
                try:
                    s.recv(65536)
                except OSError:
                    pass
            time.sleep(0.01)
    threading.Thread(target=drain, daemon=True).start()
    time.sleep(3)
    latencies = []
    for _ in range(10):
        t = time.monotonic()
        c = socket.create_connection(("127.0.0.1", port))
        c.sendall(b"POST /abort HTTP/1.1\r\nHost: x\r\nX-Rovctl-Token: t\r\n"
                  b"Content-Length: 0\r\nConnection: close\r\n\r\n")
        c.settimeout(5)
        answer = c.recv(4096)
        latencies.append((time.monotonic() - t) * 1000.0)
        c.close()
        if not answer.startswith(b"HTTP/1.1 200"):
            sys.exit(f"ABORT with {streams} streams: {answer[:80]!r}")
        time.sleep(0.5)
    p.wait()
    stop.set()
    rows = list(csv.DictReader(open(os.path.join(out, "trial_000.csv"))))
    return {"streams": streams, "abort_ms_max": round(max(latencies), 1),
            "ticks": len(rows), "overruns": int(rows[-1]["skipped_total"])}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rovctl")
    ap.add_argument("--streams", type=int, default=300)
    a = ap.parse_args()
    quiet = run(a.rovctl, 0)
    flood = run(a.rovctl, a.streams)
    print(quiet)
    print(flood)
    ok = flood["abort_ms_max"] <= 100.0 and quiet["abort_ms_max"] <= 100.0
    extra = (flood["overruns"] / flood["ticks"]) - (quiet["overruns"] / quiet["ticks"])
    print(f"overruns with streams minus without: {100 * extra:.2f} % of ticks (limit 1 %)")
    sys.exit(0 if ok and extra <= 0.01 else 1)


main()
