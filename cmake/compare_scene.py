#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Same detections on the host and on a cross target (tests/test_recog_scene.c).

usage: compare_scene.py HOST_BINARY -- TARGET_COMMAND...

Runs both, reads their "SBRDET class x y width height score_ppm share_ppm parts" lines and
requires the same detections:
  - the same number of detections;
  - each host detection has its own target detection with the same class and number of
    parts, every box edge within 1 px, and score and class share within 1e-3.
Why a tolerance at all: both targets compute in IEEE single precision, but their libm
(expf, logf, atan2f) and the compiler's contraction of multiply-adds may differ in the
last bits; a box edge is rounded to whole pixels, so such a difference can move it by one.
Exit 0 when they agree, 1 when not, 77 (skipped) when the host binary is missing.
"""
import os
import subprocess
import sys

BOX_TOL = 1
PPM_TOL = 1000


def detections(cmd):
    out = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=900, check=False)
    text = out.stdout.decode("utf-8", "replace")
    dets = []
    for line in text.splitlines():
        if line.startswith("SBRDET "):
            dets.append([int(v) for v in line.split()[1:]])
    if out.returncode != 0 or "0 Failures" not in text:
        sys.exit("%s failed (exit %d):\n%s" % (" ".join(cmd), out.returncode, text[-2000:]))
    return dets


def same(a, b):
    return (a[0] == b[0] and a[7] == b[7] and all(abs(a[i] - b[i]) <= BOX_TOL for i in range(1, 5))
            and all(abs(a[i] - b[i]) <= PPM_TOL for i in (5, 6)))


def main():
    if "--" not in sys.argv or sys.argv.index("--") != 2:
        sys.exit(__doc__)
    host_bin = sys.argv[1]
    target_cmd = sys.argv[3:]
    if not os.path.exists(host_bin):
        print("host binary %s not built: skipped" % host_bin)
        return 77
    host = detections([host_bin])
    target = detections(target_cmd)
    print("host: %d detections, target: %d detections" % (len(host), len(target)))
    if not host:
        print("FAIL: no detections to compare")
        return 1
    if len(host) != len(target):
        print("FAIL: different numbers of detections")
        return 1
    free = list(range(len(target)))
    for h in host:
        match = next((j for j in free if same(h, target[j])), None)
        if match is None:
            print("FAIL: host detection %s has no counterpart within tolerance" % h)
            return 1
        free.remove(match)
        print("  same: %s ~ %s" % (h, target[match]))
    print("OK: identical detections within 1 px and 1e-3")
    return 0


if __name__ == "__main__":
    sys.exit(main())
