#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Gate: an image that calls only sbr_fft_init_64 contains the FFT tables of N <= 64
and none of the larger lengths (per-length init + --gc-sections work as documented).

usage: check_gc_tables.py --nm NM IMAGE.elf
"""
import argparse
import subprocess
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--nm", default="nm")
    ap.add_argument("image")
    a = ap.parse_args()
    out = subprocess.run([a.nm, "-S", a.image], capture_output=True, text=True, check=True)
    syms = {}
    for line in out.stdout.splitlines():
        p = line.split()
        if len(p) == 4:
            syms[p[3]] = int(p[1], 16)
    need = ["sbr_fft_bitrev_64", "sbr_fft_tw_4", "sbr_fft_tw_16"]
    gone = ["sbr_fft_bitrev_128", "sbr_fft_bitrev_256", "sbr_fft_bitrev_512",
            "sbr_fft_bitrev_1024", "sbr_fft_tw_64", "sbr_fft_tw_256", "sbr_fft_tw_8",
            "sbr_fft_tw_32", "sbr_fft_tw_128", "sbr_fft_init_1024", "sbr_fft_init"]
    bad = 0
    for s in need:
        if s not in syms:
            print(f"FAIL: {s} missing from the image")
            bad = 1
    for s in gone:
        if s in syms:
            print(f"FAIL: {s} ({syms[s]} bytes) kept although unused")
            bad = 1
    kept = sum(v for k, v in syms.items() if k.startswith("sbr_fft_tw_") or k.startswith("sbr_fft_bitrev_"))
    print(f"FFT tables kept in an image using only N = 64: {kept} bytes "
          f"({', '.join(sorted(k for k in syms if k.startswith(('sbr_fft_tw_', 'sbr_fft_bitrev_'))))})")
    if not bad:
        print("OK: the tables of unused lengths were dropped by the linker")
    return bad


if __name__ == "__main__":
    sys.exit(main())
