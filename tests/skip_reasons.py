#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The reason each skipped test gave, from ctest's log (./sbr.sh test's summary).

    skip_reasons.py BUILD/Testing/Temporary/LastTest.log NAME...

Prints "  NAME: REASON" per name: the test's line that starts with "SKIP" (the project's
tests print their reason so, then exit 77), else its last line of output, else "no
reason printed".
"""
import re
import sys


def reasons(log_text):
    """Per test name, its output lines."""
    out = {}
    for m in re.finditer(r'^\d+/\d+ Test: (\S+)\n.*?^Output:\n-+\n(.*?)^<end of output>', log_text, re.S | re.M):
        out[m.group(1)] = [ln.strip() for ln in m.group(2).splitlines() if ln.strip()]
    return out


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        with open(argv[1], errors="replace") as f:
            found = reasons(f.read())
    except OSError as e:
        print(f"skip_reasons.py: {argv[1]}: {e.strerror}", file=sys.stderr)
        return 2
    for name in argv[2:]:
        lines = found.get(name, [])
        why = next((ln for ln in lines if ln.startswith("SKIP")), lines[-1] if lines else "no reason printed")
        print(f"  {name}: {why}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
