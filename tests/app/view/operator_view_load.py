#!/usr/bin/python3
"""A/B load test of the operator view: one real-time `rovctl sim --serve` run, its first half
without clients and its second half with N clients each streaming /stream.mjpg and /events.
Reads the run's own telemetry (tick jitter = wakeup - deadline, skipped releases) per half.

usage: operator_view_load.py ROVCTL [--clients 8] [--seconds 60] [--out DIR] [--no-sched-fifo]
On demand (about 2 x SECONDS + 10 s); the figures go in the issue note, not in CI.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request


def stream(url, stop, counts, i):
    try:
        with urllib.request.urlopen(url, timeout=10) as r:
            while not stop.is_set():
                chunk = r.read(65536)
                if not chunk:
                    break
                counts[i] += len(chunk)
    except Exception as e:  # a client error is reported, not hidden
        counts[i] = -1
        print(f"client {i}: {e}", file=sys.stderr)


def percentile(values, q):
    s = sorted(values)
    return s[min(len(s) - 1, int(q * (len(s) - 1) + 0.5))] if s else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("rovctl")
    ap.add_argument("--clients", type=int, default=8)
    ap.add_argument("--seconds", type=float, default=60.0)
    ap.add_argument("--out", default=None)
    ap.add_argument("--no-sched-fifo", dest="sched_fifo", action="store_false",
                    help="leave the tick at SCHED_OTHER (default: SCHED_FIFO 80 + mlockall)")
    a = ap.parse_args()
    out = a.out or tempfile.mkdtemp(prefix="rovctl-view-load-")
    # The shipped sim config with the vehicle's real-time settings, as `rovctl run` flies.
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))))
    conf_dir = os.path.join(repo, "deploy", "config")
    text = open(os.path.join(conf_dir, "sim.yaml")).read()
    text = re.sub(r"^calibration:\s*(\S+)",
                  lambda m: "calibration: " + os.path.join(conf_dir, m.group(1)), text, flags=re.M)
    text += ("\nscheduler:\n  realtime:\n    sched_fifo: %s\n    priority: 80\n"
             "    mlockall: %s\n" % (("true",) * 2 if a.sched_fifo else ("false",) * 2))
    os.makedirs(out, exist_ok=True)
    config = os.path.join(out, "sim-load.yaml")
    open(config, "w").write(text)
    total = 2 * a.seconds + 8
    # Held: the vehicle keeps estimating and publishing every tick but does not dock and end.
    p = subprocess.Popen([a.rovctl, "sim", "--config", config, "--serve", "127.0.0.1:0", "--hold",
                          "--realtime",
                          "--max-time", str(total), "--out", out, "--serve-linger", "0"],
                         stderr=subprocess.PIPE, text=True)
    url = None
    for line in p.stderr:
        m = re.search(r"operator view at (http://\S+)", line)
        if m:
            url = m.group(1)
            break
    if not url:
        sys.exit("rovctl did not start the view")
    threading.Thread(target=lambda: [None for _ in p.stderr], daemon=True).start()
    t0 = time.monotonic()
    time.sleep(a.seconds + 4)  # phase A: no clients
    stop = threading.Event()
    counts = [0] * (2 * a.clients)
    threads = []
    for i in range(a.clients):
        for j, path in enumerate(("stream.mjpg", "events")):
            t = threading.Thread(target=stream, args=(url + path, stop, counts, 2 * i + j),
                                 daemon=True)
            t.start()
            threads.append(t)
    b_start = time.monotonic() - t0
    time.sleep(a.seconds)
    stop.set()
    p.wait()
    rows = list(csv.DictReader(open(os.path.join(out, "trial_000.csv"))))
    def phase(lo, hi):
        sel = [r for r in rows if lo <= float(r["time_s"]) < hi]
        jit = [float(r["jitter_us"]) / 1000.0 for r in sel]
        skipped = int(sel[-1]["skipped_total"]) - int(sel[0]["skipped_total"]) if sel else -1
        return {"ticks": len(sel), "jitter_p99_ms": round(percentile(jit, 0.99), 3),
                "jitter_max_ms": round(max(jit), 3) if jit else None, "overruns": skipped}
    # Sim time runs with the wall clock in --realtime; the first 2 s of each half are left out.
    res = {"clients": a.clients, "streams": 2 * a.clients,
           "bytes_received": sum(c for c in counts if c > 0),
           "client_errors": sum(1 for c in counts if c < 0),
           "without_clients": phase(2.0, a.seconds + 2.0),
           "with_clients": phase(b_start + 2.0, b_start + a.seconds - 1.0), "out": out}
    res["jitter_p99_delta_ms"] = round(res["with_clients"]["jitter_p99_ms"] -
                                       res["without_clients"]["jitter_p99_ms"], 3)
    print(json.dumps(res, indent=1))
    ok = (res["with_clients"]["overruns"] == 0 and res["jitter_p99_delta_ms"] <= 0.2 and
          res["client_errors"] == 0)
    sys.exit(0 if ok else 1)


main()
