#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Gate: the core archive calls no heap, stdio or file-I/O function and has no mutable
static or global data. With --arm also no soft-float double helpers (__aeabi_d*, which
appear when C code does double arithmetic on a single-precision FPU).

usage: check_archive.py --nm NM [--arm] [--require f,g,...] [--expect-violations a,b,...] ARCHIVE
--require: functions the archive must define (so an empty or wrong archive cannot pass);
a missing one is reported as the violation "missing:NAME".
Double-precision libm calls (sin, sqrt, ...) are rejected on every target. Exit 0 when
clean. With --expect-violations (self-test of this gate) exit 0 only when
every named symbol is reported as a violation.
"""
import argparse
import re
import subprocess
import sys

HEAP = {"malloc", "calloc", "realloc", "free", "aligned_alloc", "posix_memalign",
        "memalign", "valloc", "pvalloc", "strdup", "strndup", "alloca", "__builtin_alloca"}
STDIO = {"printf", "fprintf", "sprintf", "snprintf", "vprintf", "vfprintf", "vsprintf",
         "vsnprintf", "dprintf", "puts", "fputs", "putchar", "fputc", "putc", "perror",
         "scanf", "fscanf", "sscanf", "getchar", "gets", "fgets", "fgetc", "getc",
         "iprintf", "siprintf", "fiprintf", "__printf_chk", "__fprintf_chk",
         "__sprintf_chk", "__snprintf_chk", "__vfprintf_chk", "__vsnprintf_chk",
         "__puts_chk"}
FILEIO = {"fopen", "fclose", "fread", "fwrite", "fseek", "ftell", "fflush", "freopen",
          "rewind", "remove", "rename", "tmpfile", "open", "close", "read", "write",
          "lseek", "_open", "_close", "_read", "_write", "_lseek", "stdin", "stdout",
          "stderr", "_impure_ptr", "_impure_data"}
# Double-precision libm (the core uses the f-suffixed float functions only).
DOUBLE_LIBM = {"sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh",
               "exp", "exp2", "expm1", "log", "log2", "log10", "log1p", "pow", "sqrt", "cbrt",
               "hypot", "fabs", "floor", "ceil", "round", "lround", "trunc", "fmod", "fmin",
               "fmax", "modf", "frexp", "ldexp", "sincos", "erf", "lgamma", "tgamma"}
# Soft-float double helpers of the ARM EABI run-time.
DOUBLE_HELPER = re.compile(r"^__aeabi_(d\w+|f2d|i2d|ui2d|l2d|ul2d|d2\w+)$")
# nm types of writable data: data, bss, common, small data/bss.
MUTABLE = set("DdBbCSsGg")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--nm", default="nm")
    ap.add_argument("--arm", action="store_true")
    ap.add_argument("--expect-violations", default="")
    ap.add_argument("--require", default="")
    ap.add_argument("archive")
    a = ap.parse_args()

    out = subprocess.run([a.nm, "-A", a.archive], capture_output=True, text=True)
    if out.returncode != 0:
        print(out.stderr)
        print(f"FAIL: {a.nm} could not read {a.archive}")
        return 1
    violations = []
    undefined = set()
    defined = set()
    objects = set()
    for line in out.stdout.splitlines():
        parts = line.split()
        if len(parts) < 2:
            continue
        where = parts[0].rstrip(":")
        if len(parts) == 2:
            typ, name = parts[1], None
            continue
        typ, name = parts[-2], parts[-1]
        # "archive:member:address" (or "archive:member: " for undefined symbols)
        fields = parts[0].split(":")
        objects.add(fields[1] if len(fields) > 2 else fields[0])
        if typ in ("T", "t"):
            defined.add(name)
        if typ == "U":
            undefined.add(name)
            base = name.split("@")[0]
            for group, names in (("heap", HEAP), ("stdio", STDIO), ("file I/O", FILEIO)):
                if base in names:
                    violations.append((base, f"{where}: calls {base} ({group})"))
            if base in DOUBLE_LIBM:
                violations.append((base, f"{where}: calls {base} (double-precision libm)"))
            if a.arm and DOUBLE_HELPER.match(base):
                violations.append((base, f"{where}: calls {base} (double arithmetic)"))
        elif typ in MUTABLE:
            violations.append((name, f"{where}: mutable static/global data '{name}' ({typ})"))

    if not objects:
        violations.append(("empty", f"{a.archive}: no object with symbols"))
    for req in (r for r in a.require.split(",") if r):
        if req not in defined:
            violations.append((f"missing:{req}", f"{a.archive}: does not define {req}"))

    if a.expect_violations:
        want = [w for w in a.expect_violations.split(",") if w]
        found = {v[0] for v in violations}
        missing = [w for w in want if not any(f == w or f.startswith(w + ".") for f in found)]
        for v in violations:
            print("  detected:", v[1])
        if missing:
            print("FAIL: the gate did not detect:", ", ".join(missing))
            return 1
        print(f"OK: the gate detects {', '.join(want)}")
        return 0

    print(f"{a.archive}: {len(objects)} objects, {len(undefined)} external references checked")
    if violations:
        for v in violations:
            print("FAIL:", v[1])
        return 1
    print("OK: no heap, no stdio, no file I/O, no mutable static data, no double libm"
          + (", no double arithmetic helpers" if a.arm else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
