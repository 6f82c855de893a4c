#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Smoke test of the cost benchmark (host_tools/bench_cost/sbr_cost.py) on one frame.

usage: test_cost.py --bin DIR --gtsdb DIR [--m4-elf ELF] --work DIR

Checks what the figures must satisfy whatever the code's speed (no timing is asserted):
  - callgrind saw every stage of the frame: maps, regions, contours + FDs, matching +
    votes, grouping + cascade and the class stage each executed instructions, and the
    stages add up to the frame's total;
  - the total is a plausible count for a 1360 x 800 frame (10^7 .. 10^11);
  - on the emulated Cortex-M4F (when the image is given): the timer calibration is
    qemu's 40 instructions a tick (-icount shift=0, 25 MHz), the stage figures are at
    most the call's total, the whole frame fitted, and the detections are the host's on
    the same pixels;
  - the five hostile frames measured on both (every stage adding up; on the Cortex-M4F
    the whole frame, a status of success or of a bound reached);
  - the strip configuration on both: every stage adding up, more instructions than the
    whole frame's (its bands overlap), and on the Cortex-M4F a workspace within 2 MiB,
    success, and the host's --strips detections.
Exit 0 on success, 1 on a failed check, 77 (skipped) without valgrind.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "host_tools", "bench_cost", "sbr_cost.py")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--gtsdb", required=True)
    ap.add_argument("--m4-elf")
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    if shutil.which("valgrind") is None or shutil.which("callgrind_annotate") is None:
        print("valgrind not installed: skipped")
        return 77
    shutil.rmtree(a.work, ignore_errors=True)
    cmd = [sys.executable, TOOL, "--bin", a.bin, "--gtsdb", a.gtsdb, "--range", "400-400",
           "--no-wall", "--out", a.work]
    if a.m4_elf and os.path.exists(a.m4_elf):
        cmd += ["--m4-elf", a.m4_elf]
    else:
        cmd += ["--no-m4"]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=1200)
    print(r.stdout)
    if r.returncode != 0:
        print("FAIL: sbr_cost.py exited %d" % r.returncode)
        return 1
    with open(os.path.join(a.work, "cost.json")) as f:
        rep = json.load(f)
    bad = []
    fr = rep["host"].get("00400")
    if fr is None:
        print("FAIL: no callgrind figures for frame 00400")
        return 1
    stages = ["maps", "regions", "contours+FDs", "matching+votes", "grouping+cascade", "class stage"]
    for s in stages:
        if fr[s] <= 0:
            bad.append("stage %s has no instructions" % s)
    if fr["total"] != sum(fr[s] for s in stages + ["set-up+output"]):
        bad.append("stages do not add up to the total")
    if not 1e7 <= fr["total"] <= 1e11:
        bad.append("implausible total %d" % fr["total"])
    if "cortex_m4" in rep:
        m4 = rep["cortex_m4"]["00400"]
        if abs(m4["calibration"] - 40.0) > 0.5:
            bad.append("Cortex-M4 calibration %.3f, not 40" % m4["calibration"])
        if sum(m4["stages"].values()) > m4["total"] or m4["total"] <= 0:
            bad.append("Cortex-M4 stages exceed the total")
        if not m4["view"].startswith("0 0 1360 800"):
            bad.append("Cortex-M4 did not process the whole frame: %s" % m4["view"])
        if m4["status"] != "SBR_OK":
            bad.append("Cortex-M4 status %s" % m4["status"])
        if not m4["same_as_host"] or m4["host_dets"] == 0:
            bad.append("Cortex-M4 detections differ from the host's (%d on the host)" % m4["host_dets"])
        # one class-stage look: every box side and outline measured; the classifier does
        # the same work whatever the box, the features' resampling grows with it
        looks = rep.get("cortex_m4_picto_look", {}).get("looks", [])
        if len(looks) != 18:
            bad.append("Cortex-M4 class-stage looks measured: %d, not 18" % len(looks))
        else:
            cls = [lk[3] for lk in looks]
            if min(cls) <= 0 or max(cls) > 1.01 * min(cls):
                bad.append("Cortex-M4 classifier cost varies with the box: %s" % cls)
            feat = {(lk[0], lk[1]): lk[2] for lk in looks}
            if not feat[(144, 0)] > 2 * feat[(16, 0)]:
                bad.append("Cortex-M4 features of a 144 px box (%d) not above twice a 16 px box's (%d)"
                           % (feat[(144, 0)], feat[(16, 0)]))
    # the hostile frames: all five measured, each frame's stages adding up, the worst's
    # ratio to the GTSDB median reported (not asserted: a figure, not a timing)
    names = ["hostile_checker", "hostile_colour_blocks", "hostile_grey_blocks", "hostile_noise", "hostile_rings"]
    hh = rep.get("host_hostile", {})
    if sorted(hh) != names:
        bad.append("hostile frames measured: %s, not %s" % (sorted(hh), names))
    for n, hf in hh.items():
        if hf["total"] != sum(hf[s] for s in stages + ["set-up+output"]) or hf["total"] <= 0:
            bad.append("%s: stages do not add up to the total" % n)
    if not rep.get("host_hostile_worst_ratio", 0) > 0:
        bad.append("no hostile worst ratio")
    if "cortex_m4" in rep:
        m4h = rep.get("cortex_m4_hostile", {})
        if sorted(m4h) != names:
            bad.append("Cortex-M4 hostile frames: %s" % sorted(m4h))
        for n, hf in m4h.items():
            if hf.get("status") not in ("SBR_OK", "SBR_ERR_CAPACITY") or not hf["view"].startswith("0 0 1360 800"):
                bad.append("Cortex-M4 %s: status %s, view %s" % (n, hf.get("status"), hf.get("view")))
    # the strip configuration
    sf = rep.get("host_strips", {}).get("00400")
    if sf is None:
        bad.append("no strip configuration figures for frame 00400")
    else:
        if sf["total"] != sum(sf[s] for s in stages + ["set-up+output"]) or min(sf[s] for s in stages) <= 0:
            bad.append("strip configuration: stages missing or not adding up to the total")
        if not sf["total"] > fr["total"]:
            bad.append("strip configuration: %d instructions, not above the whole frame's %d" % (sf["total"], fr["total"]))
    if "cortex_m4" in rep:
        m4s = rep.get("cortex_m4_strips", {}).get("00400")
        if m4s is None:
            bad.append("no Cortex-M4 strip configuration figures")
        else:
            if not 0 < m4s.get("workspace", 0) <= 2 * 1024 * 1024:
                bad.append("Cortex-M4 strip workspace %s bytes, not within 2 MiB" % m4s.get("workspace"))
            if m4s.get("status") != "SBR_OK" or not m4s["view"].startswith("strips of 256 rows"):
                bad.append("Cortex-M4 strips: status %s, view %s" % (m4s.get("status"), m4s.get("view")))
            if not m4s["same_as_host"] or m4s["host_dets"] == 0:
                bad.append("Cortex-M4 strip detections differ from the host's --strips")
    for b in bad:
        print("FAIL: " + b)
    if not bad:
        print("cost smoke: OK")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
