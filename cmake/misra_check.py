#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Gate: cppcheck (warning, style, performance, portability) + the MISRA C:2012 addon over
lib/. Every finding must be covered by a deviation of MISRA.md; otherwise it fails.

A deviation row names its rule and a scope: entries `path:NAME`, each a function (the
finding lies in the function NAME of that file) or a declared name (the finding's line
holds the identifier NAME: a macro, a type, a table). Paths are exact, no patterns. An
entry that covers no finding any more is stale and fails the gate too, so the table says
exactly where the code deviates.

usage: misra_check.py --cppcheck CPPCHECK --source ROOT --work DIR [--paths P ...]
                      [--deviations FILE] [--expect-unlisted | --expect-stale]
--paths          what to check, relative to ROOT (default: lib)
--expect-unlisted  self-test: succeed only if unlisted findings are found
--expect-stale     self-test: succeed only if a deviation entry covers no finding
"""
import argparse
import os
import re
import shutil
import subprocess
import sys


def read_deviations(path):
    rows = []
    with open(path, encoding="utf-8") as fh:
        for line in fh:
            m = re.match(r"^\|\s*(\d+\.\d+)\s*\|\s*([^|]+?)\s*\|\s*(.+?)\s*\|\s*$", line)
            if m:
                entries = []
                for e in (x.strip().strip("`") for x in m.group(2).split(",")):
                    if not e:
                        continue
                    fm = re.match(r"^([\w./-]+):(\w+)$", e)
                    entries.append({"file": fm.group(1), "name": fm.group(2), "used": 0} if fm else
                                   {"file": None, "name": e, "used": 0})
                rows.append({"rule": m.group(1), "entries": entries})
    return rows


_FUNC = re.compile(r"^(?:static\s+)?(?:inline\s+)?[A-Za-z_][\w \*]*?\b([A-Za-z_]\w*)\s*\(")


class Sources:
    """Source lines, and the function each line lies in (a definition starts at column 0)."""

    def __init__(self, root):
        self.root = root
        self.cache = {}

    def lines(self, path):
        if path not in self.cache:
            with open(os.path.join(self.root, path), encoding="utf-8", errors="replace") as fh:
                self.cache[path] = fh.read().split("\n")
        return self.cache[path]

    def function_at(self, path, line):
        ls = self.lines(path)
        for i in range(min(line, len(ls)) - 1, -1, -1):
            t = ls[i]
            if t.startswith("}") and i < line - 1:
                return None  # after the end of a function: not in one
            m = _FUNC.match(t)
            if m and not t.startswith("#"):
                # a definition if its parameter list is followed by '{', not ';'
                rest = " ".join(ls[i:min(len(ls), i + 12)])
                brace, semi = rest.find("{"), rest.find(";")
                if brace >= 0 and (semi < 0 or brace < semi):
                    return m.group(1)
                return None
        return None

    def line_has(self, path, line, name):
        ls = self.lines(path)
        return 0 < line <= len(ls) and re.search(r"\b" + re.escape(name) + r"\b", ls[line - 1]) is not None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cppcheck", default="cppcheck")
    ap.add_argument("--source", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--paths", nargs="*", default=["lib"])
    ap.add_argument("--expect-unlisted", action="store_true")
    ap.add_argument("--deviations", default="MISRA.md", help="the deviation table, relative to ROOT")
    ap.add_argument("--expect-stale", action="store_true",
                    help="self-test: succeed only if a stale deviation entry is reported")
    a = ap.parse_args()

    # a fresh analysis every time: cppcheck's build-dir cache has reported findings at the
    # old lines of an edited header (about 25 s for lib/ without it)
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work, exist_ok=True)
    cmd = [a.cppcheck, "--addon=misra", "--std=c99",
           "--enable=warning,style,performance,portability", "--inline-suppr",
           "--suppress=missingIncludeSystem", "--error-exitcode=0",
           "-I", "include", "-I", "lib/fft", f"--cppcheck-build-dir={a.work}",
           "--template={file}:{line}:{id}:{severity}:{message}",
           # a generated table of 25,215 floats (constant initialisers and a 15-line
           # accessor, see MISRA.md) takes cppcheck's MISRA addon over 5 minutes; it is
           # left out of this analysis
           "-i", "lib/models/sbr_track_model_kitti.c",
           # likewise the class stage's generated weights (about 62,000 floats, an 11-line
           # accessor written by sbr_train_picto)
           "-i", "lib/models/sbr_picto_gtsdb.c"] + a.paths
    run = subprocess.run(cmd, cwd=a.source, capture_output=True, text=True)
    findings = []
    for line in run.stderr.splitlines():
        m = re.match(r"^([^:]+):(\d+):([\w.\-]+):(\w+):(.*)$", line)
        if m:
            findings.append((m.group(1), int(m.group(2)), m.group(3), m.group(4), m.group(5)))
        elif "error" in line.lower() and "addon" in line.lower():
            print("FAIL: cppcheck addon error:", line)
            return 1
    deviations = read_deviations(os.path.join(a.source, a.deviations))
    if not deviations:
        print("FAIL: no deviation table found in MISRA.md")
        return 1
    malformed = [(d["rule"], e["name"]) for d in deviations for e in d["entries"] if e["file"] is None]
    if malformed:
        for rule, e in malformed:
            print(f"FAIL: MISRA.md deviation {rule}: scope entry '{e}' is not path:NAME")
        return 1

    src = Sources(a.source)
    unlisted = []
    by_rule = {}
    for f in findings:
        fname, line, fid = f[0], f[1], f[2]
        m = re.match(r"misra-c2012-(\d+\.\d+)", fid)
        rule = m.group(1) if m else None
        covered = False
        if rule:
            func = src.function_at(fname, line) if os.path.isfile(os.path.join(a.source, fname)) else None
            cands = [e for d in deviations if d["rule"] == rule for e in d["entries"] if e["file"] == fname]
            # the enclosing function first, then a declared name on the finding's line
            hit = next((e for e in cands if e["name"] == func), None) or \
                next((e for e in cands if src.line_has(fname, line, e["name"])), None)
            if hit is not None:
                hit["used"] += 1
                covered = True
        key = rule or fid
        by_rule[key] = by_rule.get(key, 0) + 1
        if not covered:
            unlisted.append(f)

    print(f"cppcheck + MISRA C:2012 over {' '.join(a.paths)}: {len(findings)} findings")
    for key in sorted(by_rule):
        print(f"  {key:12s} {by_rule[key]:4d}")
    misra_seen = any(f[2].startswith("misra-") for f in findings)
    if a.expect_unlisted:
        if unlisted and misra_seen:
            print(f"OK: the gate rejects {len(unlisted)} unlisted findings, e.g. "
                  f"{unlisted[0][0]}:{unlisted[0][1]} {unlisted[0][2]}")
            return 0
        print("FAIL: the gate accepted code that breaks unlisted rules")
        return 1
    if not misra_seen:
        # The listed deviations exist in the code, so a run without any MISRA finding
        # means the addon did not run.
        print("FAIL: no MISRA findings at all: did the misra addon run?")
        print(run.stderr[-2000:])
        return 1
    stale = [(d["rule"], e) for d in deviations for e in d["entries"] if e["used"] == 0]
    if a.expect_stale:
        if stale:
            print(f"OK: the gate rejects a stale deviation ({stale[0][0]} {stale[0][1]['file']}:{stale[0][1]['name']})")
            return 0
        print("FAIL: the gate accepted a deviation entry that covers nothing")
        return 1
    for rule, e in stale:
        print(f"FAIL: MISRA.md deviation {rule} {e['file']}:{e['name']} covers no finding any more: remove it")
    if unlisted:
        for f in unlisted:
            print(f"FAIL: {f[0]}:{f[1]}: {f[2]} ({f[3]}) is neither fixed nor listed in MISRA.md")
    if unlisted or stale:
        return 1
    print("OK: every finding is a deviation listed with its reason in MISRA.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
