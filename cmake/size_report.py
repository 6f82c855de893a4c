#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Report for the Cortex-M build of the core: code size (text), static RAM (data + bss,
must be 0) per object and in total, and the largest stack frames per function from the
-fstack-usage files. Fails when static RAM is not 0 or a frame is dynamic (VLA/alloca).

usage: size_report.py --size SIZE --archive LIB --su-dir DIR [--top N]
"""
import argparse
import glob
import os
import subprocess
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="size")
    ap.add_argument("--archive", required=True)
    ap.add_argument("--su-dir", required=True)
    ap.add_argument("--top", type=int, default=12)
    a = ap.parse_args()

    out = subprocess.run([a.size, "-t", a.archive], capture_output=True, text=True)
    if out.returncode != 0:
        print(out.stderr)
        return 1
    rows = []
    total = None
    for line in out.stdout.splitlines()[1:]:
        p = line.split()
        if len(p) >= 6 and p[0].isdigit():
            text, data, bss = int(p[0]), int(p[1]), int(p[2])
            name = p[5] if len(p) > 5 else ""
            if "(TOTALS)" in line:
                total = (text, data, bss)
            else:
                rows.append((name.split("(ex ")[0], text, data, bss))
    if total is None:
        total = tuple(sum(r[i] for r in rows) for i in (1, 2, 3))
    print("== sbr core, Cortex-M4F (arm-none-eabi, -mcpu=cortex-m4 -mfloat-abi=hard) ==")
    print(f"{'object':32s} {'text':>8s} {'data':>6s} {'bss':>6s}")
    for name, text, data, bss in sorted(rows, key=lambda r: -r[1]):
        print(f"{name:32s} {text:8d} {data:6d} {bss:6d}")
    print(f"{'TOTAL':32s} {total[0]:8d} {total[1]:6d} {total[2]:6d}")
    print(f"code size (text, includes const tables): {total[0]} bytes")
    print(f"static RAM (data + bss): {total[1] + total[2]} bytes")

    frames = []
    for su in glob.glob(os.path.join(a.su_dir, "**", "*.su"), recursive=True):
        with open(su, encoding="utf-8") as fh:
            for line in fh:
                p = line.rstrip("\n").split("\t")
                if len(p) >= 3:
                    loc = p[0]
                    func = loc.split(":")[-1]
                    src = os.path.basename(loc.split(":")[0])
                    frames.append((int(p[1]), p[2], func, src))
    if not frames:
        print("FAIL: no -fstack-usage files found under", a.su_dir)
        return 1
    frames.sort(key=lambda f: -f[0])
    print(f"largest stack frames (of {len(frames)} functions; -fstack-usage, bytes):")
    for size, kind, func, src in frames[: a.top]:
        print(f"  {size:6d}  {kind:8s} {func} ({src})")
    bad = 0
    if total[1] + total[2] != 0:
        print("FAIL: the core must have no static RAM (data + bss = 0)")
        bad = 1
    dyn = [f for f in frames if "dynamic" in f[1]]
    for f in dyn:
        print(f"FAIL: dynamic stack frame in {f[2]} ({f[3]})")
        bad = 1
    if not bad:
        print("OK: static RAM 0 bytes, every stack frame static")
    return bad


if __name__ == "__main__":
    sys.exit(main())
