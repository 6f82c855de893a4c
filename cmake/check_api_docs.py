#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Every parameter of every public function is documented with its direction.

    check_api_docs.py --source DIR [--report]

For each function declared in include/sbr/*.h, the doc comment (/** ... */) right before
it must hold a `@param[in]`, `@param[out]` or `@param[in,out]` line for each of its
parameters (several names may share one line: `@param[out] rear, front ...`), in the
order of the signature, each with text of its own (not a filler line such as "length of
the array, in elements"). Prints the functions with an undocumented, untagged,
out-of-order or filler parameter; exit 1 if there is one (0 with --report)."""

import argparse
import os
import re
import sys

DECL = re.compile(r"^(?:[A-Za-z_][\w \*]*?)\b(sbr_\w+)\s*\(([^;{]*?)\)\s*;", re.M | re.S)


# Text that says nothing a parameter's name does not (what the first docs gate let through).
FILLER = ("length of the array, in elements", "its size in bytes")


def params_of(arglist):
    out = []
    for a in arglist.split(","):
        a = a.strip()
        if a in ("void", ""):
            continue
        m = re.search(r"(\w+)\s*(\[[^\]]*\])?\s*$", a)
        if m:
            out.append(m.group(1))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", required=True)
    ap.add_argument("--report", action="store_true", help="list only, exit 0")
    a = ap.parse_args()
    inc = os.path.join(a.source, "include", "sbr")
    bad = []
    total = 0
    for name in sorted(os.listdir(inc)):
        if not name.endswith(".h"):
            continue
        text = open(os.path.join(inc, name), encoding="utf-8").read()
        for m in DECL.finditer(text):
            func, args = m.group(1), m.group(2)
            if "#define" in text[text.rfind("\n", 0, m.start()):m.start()]:
                continue
            total += 1
            before = text[:m.start()].rstrip()
            # a group of declarations under one comment (e.g. per-length variants): the
            # comment above the first of them
            while not before.endswith("*/") and before and before.rfind("\n") >= 0:
                line = before[before.rfind("\n") + 1:]
                if not re.match(r"^\s*(?:sbr_status_t|void|size_t|uint32_t|int|float)?\b.*[,;(]\s*$|^\s+[\w ]*\*?\w+[,)]", line):
                    break
                before = before[:before.rfind("\n")].rstrip()
            doc = ""
            if before.endswith("*/"):
                start = before.rfind("/**")
                doc = before[start:] if start >= 0 else ""
            tagged = []
            for pm in re.finditer(r"@param\[(?:in|out|in,out)\]\s+(\w+(?:\s*,\s*\w+)*)([^\n]*)", doc):
                for n in pm.group(1).split(","):
                    tagged.append(n.strip())
                if pm.group(2).strip().rstrip(".") in FILLER:
                    bad.append((name, func, ["filler text for " + pm.group(1)]))
            sig = params_of(args)
            missing = [p for p in sig if p not in tagged]
            if missing:
                bad.append((name, func, missing))
            order = [p for p in tagged if p in sig]
            if order != [p for p in sig if p in order]:
                bad.append((name, func, ["@param order " + ", ".join(order) + " is not the signature's"]))
    for name, func, missing in bad:
        print(f"  {name}: {func}: {', '.join(missing)}")
    print(f"public functions: {total}; problems (a parameter not documented as @param[in|out|in,out], "
          f"out of order, or filler): {len(bad)}")
    return 0 if (a.report or not bad) else 1


if __name__ == "__main__":
    sys.exit(main())
