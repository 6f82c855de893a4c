#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The summary of ./sbr.sh test: every part that decides its exit status, counted.

    test_summary.py --ctest NAME=JUNIT.xml [--ctest ...] --matrix LOG --fuzz LOG

Reads each build's ctest JUnit file (ctest --output-junit, with the whole test output
kept): the entries passed, failed and skipped, each skipped entry's reason (its "SKIP"
line), and the Unity test cases of its output; the build matrix's and the fuzz smoke
run's last lines ("build matrix: P passed, F failed", "fuzz: P passed, F failed"). Prints
one line per build, the reasons, the matrix and fuzz lines and a `total:` line that
counts all of them. Exit status 0 when nothing failed, 1 otherwise.
"""
import argparse
import re
import sys
import xml.etree.ElementTree as ET


def junit(path):
    """(passed, failed, skipped, [(name, reason)], unity cases, unity failures)."""
    root = ET.parse(path).getroot()
    passed = failed = 0
    skipped = []
    cases = case_failures = 0
    for tc in root.iter("testcase"):
        out = tc.findtext("system-out") or ""
        for m in re.finditer(r"^(\d+) Tests (\d+) Failures", out, re.M):
            cases += int(m.group(1))
            case_failures += int(m.group(2))
        status = tc.get("status")
        if status == "notrun" or tc.find("skipped") is not None:
            reason = next((ln.strip() for ln in out.splitlines() if ln.strip().startswith("SKIP")), None)
            skipped.append((tc.get("name"), reason or (tc.find("skipped").get("message") if tc.find("skipped")
                                                        is not None else "no reason printed")))
        elif status == "fail" or tc.find("failure") is not None:
            failed += 1
        else:
            passed += 1
    return passed, failed, skipped, cases, case_failures


def last_counts(path, prefix):
    """(passed, failed, line) of the log's last '<prefix> P passed, F failed' line."""
    try:
        with open(path, errors="replace") as f:
            lines = [ln.strip() for ln in f if ln.startswith(prefix)]
    except OSError:
        lines = []
    m = re.search(r"(\d+) passed, (\d+) failed", lines[-1]) if lines else None
    if not m:
        return 0, 1, f"{prefix} did not run"
    return int(m.group(1)), int(m.group(2)), lines[-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ctest", action="append", default=[], metavar="NAME=JUNIT")
    ap.add_argument("--matrix", required=True)
    ap.add_argument("--fuzz", required=True)
    a = ap.parse_args()
    tp = tf = ts = entries = 0
    for spec in a.ctest:
        name, _, path = spec.partition("=")
        try:
            p, f, s, cases, cf = junit(path)
        except (OSError, ET.ParseError) as e:
            print(f"{name}: no ctest results ({e})")
            tf += 1
            continue
        names = ",".join(n for n, _ in s)
        print(f"{name}: ctest {p} passed, {f} failed, {len(s)} skipped{f' ({names})' if s else ''} "
              f"({cases} Unity test cases, {cf} failed)")
        for n, why in s:
            print(f"  {n}: {why}")
        tp, tf, ts, entries = tp + p, tf + f, ts + len(s), entries + p + f + len(s)
    mp, mf, mline = last_counts(a.matrix, "build matrix: ")
    fp, ff, fline = last_counts(a.fuzz, "fuzz: ")
    print(f"{mline} (core, every build type)")
    print(f"{fline.replace('fuzz:', 'fuzz smoke:', 1)} (harnesses)")
    print(f"total: {tp + mp + fp} passed, {tf + mf + ff} failed, {ts} skipped "
          f"(ctest {entries}, build matrix {mp + mf}, fuzz harnesses {fp + ff})")
    return 1 if tf + mf + ff else 0


if __name__ == "__main__":
    sys.exit(main())
