#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The ECU's whole job on the emulated Cortex-M4 and on the host: the same CAN bytes.

usage: compare_ecu_log.py --host-tools DIR --images DIR --first N --count N --work DIR
                          --elf M4_ELF -- QEMU_COMMAND...

The frames GTSDB NNNNN.jpg (first .. first + count - 1), in order, are one sequence
(100 ms apart). They are converted once to binary PPM (sbr_to_ppm) and named 00000.ppm,
00001.ppm, ... in WORK/run; then
  - the host: sbr_detect --sequence --canlog host.log --canlog-fixed-time over that folder;
  - the target: the image tests/bench_m4/sbr_ecu_m4.c under qemu in that folder, which
    runs sbr_ecu_frame() per frame and writes its frames with the candump port (ecu.log).
Both logs must be equal byte for byte. When they are not, the first differing lines are
printed with the message and the bytes that differ, and the frames' detections of both
sides, so that the floating-point divergence can be found. Exit 0 when equal, 1 when
not, 77 (skipped) when the host tools or the images are missing.
"""
import argparse
import os
import subprocess
import sys

MESSAGES = {"300": "SBR_ConfirmedSign", "301": "SBR_EcuStatus", "310": "SBR_Detection",
            "320": "SBR_TrackedObject"}


def run(cmd, cwd=None, timeout=3600):
    r = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout, check=False)
    text = r.stdout.decode("utf-8", "replace")
    if r.returncode != 0:
        sys.exit("%s failed (exit %d):\n%s" % (" ".join(cmd), r.returncode, text[-3000:]))
    return text


def explain(a, b):
    """What differs between two log lines."""
    ta, ia, fa = a.split()
    tb, ib, fb = b.split()
    ida, da = fa.split("#")
    idb, db = fb.split("#")
    if ta != tb or ida != idb:
        return "time or message differ: %s %s / %s %s" % (ta, ida, tb, idb)
    bytes_a = [da[i:i + 2] for i in range(0, len(da), 2)]
    bytes_b = [db[i:i + 2] for i in range(0, len(db), 2)]
    diff = [i for i in range(min(len(bytes_a), len(bytes_b))) if bytes_a[i] != bytes_b[i]]
    return "%s at %s: bytes %s differ (host %s, target %s)" % (
        MESSAGES.get(ida, ida), ta, diff, " ".join(bytes_a[i] for i in diff), " ".join(bytes_b[i] for i in diff))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--host-tools", required=True)
    ap.add_argument("--images", required=True)
    ap.add_argument("--first", type=int, default=400)
    ap.add_argument("--count", type=int, default=50)
    ap.add_argument("--work", required=True)
    ap.add_argument("--elf", required=True)
    ap.add_argument("qemu", nargs="+")
    a = ap.parse_args()
    detect = os.path.join(a.host_tools, "sbr_detect")
    to_ppm = os.path.join(a.host_tools, "sbr_to_ppm")
    names = [os.path.join(a.images, "%05d.jpg" % (a.first + k)) for k in range(a.count)]
    if not (os.path.exists(detect) and os.path.exists(to_ppm)):
        print("skipped: no host tools in %s" % a.host_tools)
        return 77
    if not all(os.path.exists(n) for n in names):
        print("skipped: the images %05d .. %05d are not all in %s" % (a.first, a.first + a.count - 1, a.images))
        return 77
    ppm = os.path.join(a.work, "ppm")
    rundir = os.path.join(a.work, "run")
    os.makedirs(ppm, exist_ok=True)
    os.makedirs(rundir, exist_ok=True)
    missing = [n for n in names if not os.path.exists(os.path.join(ppm, os.path.basename(n)[:-4] + ".ppm"))]
    if missing:
        run([to_ppm, "--out", ppm] + missing)
    for k, n in enumerate(names):
        link = os.path.join(rundir, "%05d.ppm" % k)
        if os.path.lexists(link):
            os.remove(link)
        os.symlink(os.path.abspath(os.path.join(ppm, os.path.basename(n)[:-4] + ".ppm")), link)
    for stale in ("ecu.log", "host.log"):
        if os.path.exists(os.path.join(a.work, stale)):
            os.remove(os.path.join(a.work, stale))
    host_log = os.path.join(a.work, "host.log")
    host_det = os.path.join(a.work, "host_detections.txt")
    run([detect, "--input", rundir, "--sequence", "--canlog", host_log, "--canlog-fixed-time", "--detections",
         host_det, "--quiet"])
    target_out = run(a.qemu + [os.path.abspath(a.elf)], cwd=rundir)
    target_log = os.path.join(rundir, "ecu.log")
    with open(host_log) as f:
        h = f.read().splitlines()
    with open(target_log) as f:
        t = f.read().splitlines()
    frames = [ln for ln in target_out.splitlines() if ln.startswith("frame ")]
    print("%d frames; host %d CAN frames, target %d CAN frames" % (len(frames), len(h), len(t)))
    if h == t:
        print("the Cortex-M4's CAN log equals the host's byte for byte (%d lines)" % len(h))
        return 0
    shown = 0
    for k in range(max(len(h), len(t))):
        x = h[k] if k < len(h) else "(none)"
        y = t[k] if k < len(t) else "(none)"
        if x != y:
            print("line %d:\n  host   %s\n  target %s" % (k + 1, x, y))
            if x != "(none)" and y != "(none)":
                print("  " + explain(x, y))
            shown += 1
            if shown >= 10:
                break
    print("target per frame (status, detections, confirmed, limit):\n  " + "\n  ".join(frames))
    with open(host_det) as f:
        print("host detections:\n  " + "  ".join(f.readlines()))
    return 1


if __name__ == "__main__":
    sys.exit(main())
