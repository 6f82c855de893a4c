#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Run a test command and keep its exit status visible to ctest.

    run_checked.py -- COMMAND [ARGS...]

ctest ignores the exit status of a test that has PASS_REGULAR_EXPRESSION, so a program
that printed its '=met' line and then crashed or returned an error would pass. This wrapper
passes the output through and, when the command exits non-zero (or dies by a signal),
prints "run_checked: FAILED, exit status N"; such tests also set FAIL_REGULAR_EXPRESSION
"run_checked: FAILED". Exit 77 (a documented skip) is passed through unmarked.
"""
import subprocess
import sys


def main():
    args = sys.argv[1:]
    if args[:1] == ["--"]:
        args = args[1:]
    if not args:
        print("usage: run_checked.py -- COMMAND [ARGS...]", file=sys.stderr)
        return 2
    sys.stdout.flush()
    rc = subprocess.call(args)
    if rc == 77:
        return 77
    if rc != 0:
        print(f"\nrun_checked: FAILED, exit status {rc}")
    return rc


if __name__ == "__main__":
    sys.exit(main())
