#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Throughput of the dashboard on a long candump log, replayed as fast as possible.

    python dashboard/tools/bench_log.py [--frames N] [--mode terminal|web|both] [--log FILE]

Writes (or reuses, with --log) a synthetic log of N frames (default 10^6) of sbr's
messages, cycle after cycle as the ECU sends them (signs, status, a detection, the tracked
object, valid E2E), 100 ms of log time a cycle; then replays it through the dashboard's
LogSource and Monitor as `--fast` does, with the view of the mode consuming the state as
it does in use: `terminal` renders a screen every 0.1 s; `web` serves the page's event
stream (a snapshot per change, at most every 0.1 s) to one connected client. Prints frames
per second (a live bus at 100 % load of classic CAN at 1 Mbit/s is about 8,000 frames/s)
and the process's resident memory at 10 %, 50 % and 100 % of the log (bounded: the trace
and the problems list keep a fixed number of entries). A benchmark tool: figures are
printed, not asserted.
"""
import argparse
import os
import sys
import threading
import time
import urllib.request

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests"))

from frames import Sender, model  # noqa: E402
from sbr_dashboard.monitor import Monitor  # noqa: E402
from sbr_dashboard.sources import LogSource  # noqa: E402
from sbr_dashboard.terminal import render  # noqa: E402


def rss_mib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def write_log(path, n):
    m = model()
    s = Sender(m)
    written = k = 0
    with open(path, "w") as f:
        while written < n:
            t = 1700000000.0 + 0.1 * k
            for fid, data in s.cycle(k % 65536, dets=[(1, 80, 400 + k % 50, 300)], signs=[(1, 30, 90, k % 20)] if k % 7 == 0 else ()):
                if written == n:
                    break
                f.write(f"({t:.6f}) can0 {fid:03X}#{data.hex().upper()}\n")
                written += 1
            k += 1
    return written


def replay(path, n, mode):
    mon = Monitor(model())
    src = LogSource(mon, path, rate=0.0)
    marks, stop = {}, threading.Event()

    def watch():
        while not stop.wait(0.05):
            f = mon.frames
            for p in (10, 50):
                if p not in marks and f >= n * p / 100:
                    marks[p] = rss_mib()

    threads = [threading.Thread(target=watch, daemon=True)]
    server = None
    if mode == "terminal":
        def screens():
            while not stop.wait(0.1):
                render(mon.snapshot(), 100)
        threads.append(threading.Thread(target=screens, daemon=True))
    else:
        from sbr_dashboard.web import WebServer
        server = WebServer(mon, "127.0.0.1", 0)
        server.start()

        def client():
            try:
                with urllib.request.urlopen(server.url + "events", timeout=30) as r:
                    while not stop.is_set():
                        if not r.readline():
                            break
            except OSError:
                pass  # the server stopped at the end
        threads.append(threading.Thread(target=client, daemon=True))
    for t in threads:
        t.start()
    t0 = time.monotonic()
    src.start()
    src.thread.join()
    secs = time.monotonic() - t0
    marks[100] = rss_mib()
    stop.set()
    if server:
        server.stop()
    snap = mon.snapshot()
    return snap["frames"], secs, marks, snap


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frames", type=int, default=1_000_000)
    ap.add_argument("--mode", choices=("terminal", "web", "both"), default="both")
    ap.add_argument("--log", help="replay this log instead of writing one (its frame count is --frames)")
    a = ap.parse_args()
    if a.frames < 1:
        ap.error("--frames: at least 1")
    if a.log and not os.path.isfile(a.log):
        print(f"bench_log.py: --log {a.log}: no such file", file=sys.stderr)
        return 2
    path = a.log or os.path.join(os.environ.get("TMPDIR", "/tmp"), f"sbr_bench_{a.frames}.log")
    if not a.log:
        t0 = time.monotonic()
        write_log(path, a.frames)
        print(f"log: {path}, {a.frames} frames, written in {time.monotonic() - t0:.1f} s")
    for mode in (("terminal", "web") if a.mode == "both" else (a.mode,)):
        frames, secs, marks, snap = replay(path, a.frames, mode)
        print(f"{mode}: {frames} frames in {secs:.1f} s = {frames / secs:,.0f} frames/s; valid "
              f"{snap['totals']['valid']}, E2E errors {snap['totals']['e2e_errors']}; resident memory "
              + ", ".join(f"{p} % {marks.get(p, float('nan')):.0f} MiB" for p in (10, 50, 100)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
