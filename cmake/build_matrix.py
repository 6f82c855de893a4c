#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Build the core at every build type for every compiler with -Werror; print the matrix.

    build_matrix.py --source DIR --work DIR [--jobs N] [--only gcc,clang,arm-none-eabi]
                    [--types Debug,Release,RelWithDebInfo,MinSizeRel]

Each cell is a fresh configure + build of the core library alone (no tests, no host
tools) with SBR_WERROR=ON. Exit status 1 if any cell fails (its log is printed), 2 if a
compiler of the list is missing.
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

TYPES = ["Debug", "Release", "RelWithDebInfo", "MinSizeRel"]


def compilers(source):
    return {
        "gcc": {"env": {"CC": "gcc"}, "args": [], "needs": "gcc"},
        "clang": {"env": {"CC": "clang"}, "args": [], "needs": "clang"},
        "arm-none-eabi": {
            "env": {},
            "args": ["-DCMAKE_TOOLCHAIN_FILE=" + os.path.join(source, "cmake", "toolchain-cortex-m4f.cmake")],
            "needs": "arm-none-eabi-gcc",
        },
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--only", default="gcc,clang,arm-none-eabi")
    ap.add_argument("--types", default=",".join(TYPES))
    a = ap.parse_args()
    source = os.path.abspath(a.source)
    table = compilers(source)
    names = [n for n in a.only.split(",") if n]
    types = [t for t in a.types.split(",") if t]
    for n in names:
        if n not in table:
            print(f"unknown compiler {n}", file=sys.stderr)
            return 2
        if shutil.which(table[n]["needs"]) is None:
            print(f"{table[n]['needs']} not found", file=sys.stderr)
            return 2
    results = {}
    failed = []
    for n in names:
        for t in types:
            build = os.path.join(a.work, f"{n}-{t}")
            shutil.rmtree(build, ignore_errors=True)
            env = dict(os.environ, **table[n]["env"])
            start = time.monotonic()
            log = []
            ok = True
            for cmd in (["cmake", "-S", source, "-B", build, "-G", "Ninja", f"-DCMAKE_BUILD_TYPE={t}",
                         "-DSBR_BUILD_TESTS=OFF", "-DSBR_BUILD_HOST_TOOLS=OFF", "-DSBR_WERROR=ON"]
                        + table[n]["args"],
                        ["cmake", "--build", build, "-j", str(a.jobs), "--target", "sbr"]):
                p = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
                log.append(p.stdout)
                if p.returncode != 0:
                    ok = False
                    break
            secs = time.monotonic() - start
            results[(n, t)] = ("ok" if ok else "FAIL", secs)
            if not ok:
                failed.append((n, t, "".join(log)))
    width = max(len(t) for t in types) + 2
    print("core build matrix (-Werror, core library only): " + ", ".join(names))
    print("compiler".ljust(16) + "".join(t.ljust(width + 6) for t in types))
    for n in names:
        row = n.ljust(16)
        for t in types:
            st, secs = results[(n, t)]
            row += f"{st} {secs:4.0f}s".ljust(width + 6)
        print(row)
    for n, t, log in failed:
        print(f"\n---- {n} {t} failed:\n{log[-6000:]}")
    total = len(results)
    print(f"build matrix: {total - len(failed)} passed, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
