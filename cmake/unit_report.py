#!/usr/bin/env python3
"""Unit sizes of the code base: the longest functions of the core, the host tools' main()s,
the README's line count (issue: a house a newcomer can read).

    unit_report.py --source DIR [--top N] [--max-core LINES] [--max-main LINES]
                   [--max-nesting DEPTH]

Function lengths (lines from the signature to the closing brace) and nesting depth (nested
control structures) come from lizard (pinned in tests/python/requirements.txt). The
generated model tables (lib/models/) are data, not code, and are left out.

Without a --max-* option it only reports (exit 0). With one, a unit over the limit is
listed as over and the exit status is 1 (the gate the CI runs)."""

import argparse
import os
import sys

import lizard
from lizard_ext import lizardns  # noqa: F401  (registers the nested-structures counter)


def units(root, sub, exts):
    """(path, name, start line, length, nesting) of every function under root/sub."""
    paths = []
    for d, _, files in os.walk(os.path.join(root, sub)):
        if os.path.relpath(d, root).startswith(os.path.join("lib", "models")):
            continue
        paths += [os.path.join(d, f) for f in sorted(files) if f.endswith(exts)]
    out = []
    for info in lizard.analyze_files(sorted(paths), exts=lizard.get_extensions(["ns"])):
        rel = os.path.relpath(info.filename, root)
        for fn in info.function_list:
            out.append((rel, fn.name, fn.start_line, fn.length,
                        getattr(fn, "max_nested_structures", 0)))
    return out


def table(title, rows, top, limit):
    print(f"{title}:")
    over = [r for r in rows if limit is not None and r[3] > limit]
    for rel, name, line, length, nest in sorted(rows, key=lambda r: -r[3])[:top]:
        mark = "  OVER" if limit is not None and length > limit else ""
        print(f"  {length:5d} lines  nesting {nest}  {name}  ({rel}:{line}){mark}")
    return over


# Public headers that belong to no module folder: the umbrella, the shared types and the
# statuses (lib/common/).
SHARED_HEADERS = {"sbr.h", "types.h", "status.h"}


def module_folders(root):
    """Public headers include/sbr/X.h whose module has no folder lib/X/ (folder = header)."""
    missing = []
    for h in sorted(os.listdir(os.path.join(root, "include", "sbr"))):
        if h.endswith(".h") and h not in SHARED_HEADERS and not os.path.isdir(os.path.join(root, "lib", h[:-2])):
            missing.append(h)
    return missing


def longest_files(root, sub, exts, top):
    """The longest source files under root/sub (lines), generated models left out."""
    rows = []
    for d, _, names in os.walk(os.path.join(root, sub)):
        if os.path.join("lib", "models") in os.path.relpath(d, root):
            continue
        for n in names:
            if n.endswith(exts):
                with open(os.path.join(d, n), encoding="utf-8", errors="replace") as f:
                    rows.append((sum(1 for _ in f), os.path.relpath(os.path.join(d, n), root)))
    return sorted(rows, reverse=True)[:top]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", required=True, help="the project root")
    ap.add_argument("--top", type=int, default=12, help="rows per table (default 12)")
    ap.add_argument("--max-core", type=int, help="longest core (lib/) function allowed, lines")
    ap.add_argument("--max-main", type=int, help="longest host tool main() allowed, lines")
    ap.add_argument("--max-nesting", type=int,
                    help="deepest nesting of a core function allowed (reported as over)")
    a = ap.parse_args()
    if a.top < 1:
        ap.error("--top: at least 1")

    core = units(a.source, "lib", (".c",))
    tools = units(a.source, "host_tools", (".cpp", ".c"))
    mains = [r for r in tools if r[1] == "main"]
    with open(os.path.join(a.source, "README.md"), encoding="utf-8") as f:
        readme = sum(1 for _ in f)

    print(f"README.md: {readme} lines")
    over = table(f"longest core functions ({len(core)} functions in lib/, generated models "
                 f"left out; {sum(1 for r in core if r[3] > 80)} over 80 lines)",
                 core, a.top, a.max_core)
    over += table(f"longest host tool main()s ({len(mains)}; "
                  f"{sum(1 for r in mains if r[3] > 80)} over 80 lines)", mains, a.top, a.max_main)
    table(f"longest other host tool functions ({sum(1 for r in tools if r[1] != 'main' and r[3] > 80)}"
          " over 80 lines)", [r for r in tools if r[1] != "main"], a.top, None)
    for sub, exts in (("lib", (".c", ".h", ".inc")), ("host_tools", (".cpp", ".hpp", ".c", ".py"))):
        print(f"longest files in {sub}/ (lines):")
        for n, rel in longest_files(a.source, sub, exts, 5):
            print(f"  {n:6d}  {rel}")
    missing = module_folders(a.source)
    print("every public header's module in a folder of its name (include/sbr/X.h, lib/X/): "
          + ("yes" if not missing else "no: " + ", ".join(missing)))
    over += [("module folder", h) for h in missing]
    deep = [r for r in core if a.max_nesting is not None and r[4] > a.max_nesting]
    if a.max_nesting is not None:
        print(f"core functions nested deeper than {a.max_nesting}: {len(deep)}")
        for rel, name, line, _, nest in deep:
            print(f"  nesting {nest}  {name}  ({rel}:{line})")
    if over:
        print(f"units over the limit: {len(over)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
