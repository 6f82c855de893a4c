#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The host tools' command lines (CLI11): --help exits 0 and describes every option; a
malformed or out-of-range value is refused with exit 2 and a message naming the option;
an unknown option is refused.

    test_cli.py --tools DIR --tests DIR [--sbr-sh PATH]

--tools: the host tools' folder; --tests: the folder of the C++ test programs (tests/host),
each of which must be there."""

import argparse
import os
import re
import subprocess
import tempfile
import sys

# tool: (arguments that satisfy its required options, [(option, bad value), ...])
CASES = {
    "sbr_detect": (["--input", "in", "--detections", "d.txt"],
                   [("--threshold", "abc"), ("--threshold", "nan"), ("--threshold", "1.5"),
                    ("--range", "99999999999999999999-1"), ("--range", "5-3"), ("--repeat", "0"),
                    ("--max-parts", "-1"), ("--map-subsample", "2,9"), ("--roi", "1,2,3")]),
    "sbr_eval": (["--detections", "d.txt", "--gt", "gt.txt"],
                 [("--threshold", "abc"), ("--iou", "2"), ("--range", "1-x")]),
    "sbr_bench_mser": ([], [("--rounds", "0"), ("--map", "red"), ("--first", "x")]),
    "sbr_bench_picto": ([], [("--images", "13"), ("--boxes", "1e3")]),
    "sbr_bench_fft": ([], [("--sizes", "100"), ("--rounds", "2"), ("--round-ms", "inf")]),
    "sbr_canlog": (["--detections", "d.txt", "--out", "o.log"], [("--images", "abc"), ("--first", "-1")]),
    "sbr_conics": ([], [("--trials", "0"), ("--seed", "-3")]),
    "sbr_fuzz_seeds": (["--out", "o"], [("--per-set", "0")]),
    "sbr_parts_coverage": (["--data", "d"], [("--range", "9-1"), ("--min-fill", "2"), ("--delta", "0")]),
    "test_builtin_models_gtsdb": (["--data", "d", "--min-recall", "0.5", "--min-crop-recall", "0.5"],
                                  [("--max-fp-rate", "-1"), ("--range", "a-b")]),
    "sbr_shapes": (["--data", "d"], [("--n", "100"), ("--sigma", "x")]),
    "sbr_track": (["--labels", "l"], [("--noise", "abc"), ("--particles", "5"), ("--bench-targets", "33")]),
    "sbr_train_track": (["--labels", "l"], [("--em", "-1"), ("--vel-count", "3"), ("--tail", "nan")]),
    "sbr_train": ([], [("--vote-error", "0"), ("--max-protos", "70000"), ("--range", "1-")]),
    "sbr_train_picto": ([], [("--hidden", "abc"), ("--bg-swap", "sideways"), ("--eval-range", "2-1"),
                             ("--gate-recall", "0"), ("--gtsrb-cap", "0")]),
    "sbr_to_ppm": (["--out", "o", __file__], []),
    "sbr_gtsrb_eval": ([], [("--threads", "0"), ("--split", "test")]),
    "sbr_config": ([], []),
}


def table_rows(tools):
    """The core's configuration tables as sbr_config prints them: (field, option, type,
    range, default) per row."""
    out = run([os.path.join(tools, "sbr_config")]).stdout
    rows = []
    for m in re.finditer(r"^\| `(\w+)` \| `(--[a-z0-9-]+)` \| ([^|]+) \| ([^|]+) \| ([^|]+) \|", out, re.M):
        rows.append(tuple(x.strip() for x in m.groups()))
    return rows


def check_detect_docs(tools, sbr_sh):
    """docs/usage/detect.md against sbr_detect --help (the one source): each of the tool's
    own options is described there (the core's tables' options in configuration.md), and
    every option the page names is one of sbr_detect's, sbr_eval's or ./sbr.sh detect's and
    train's (the tools the page covers)."""
    def options(cmd):
        return set(re.findall(r"--[a-z][a-z0-9-]*", run(cmd).stdout))
    page = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "usage", "detect.md")
    with open(page, encoding="utf-8") as f:
        named = set(re.findall(r"--[a-z][a-z0-9-]*", f.read()))
    detect = options([os.path.join(tools, "sbr_detect"), "--help"])
    own = detect - {r[1] for r in table_rows(tools)} - {"--help"}
    known = detect | options([os.path.join(tools, "sbr_eval"), "--help"])
    for tool in ("sbr_train", "sbr_train_picto"):
        known |= options([os.path.join(tools, tool), "--help"])
    if sbr_sh:
        known |= options(["bash", sbr_sh, "detect", "--help"]) | options(["bash", sbr_sh, "train", "--help"])
    undocumented, unknown = sorted(own - named), sorted(named - known)
    print(f"docs/usage/detect.md: {len(own)} options of sbr_detect's own"
          + (f"; not described there: {undocumented}" if undocumented else ", each described")
          + (f"; named there but no tool has them: {unknown}" if unknown else ""))
    return int(bool(undocumented)) + int(bool(unknown))


def check_recogniser_options(tools):
    """sbr_detect's recogniser options are the core's tables, row for row: each option with
    its default, a value one beyond its range refused naming it, a broken rule between
    fields refused naming the field the table blames."""
    failures = 0
    rows = table_rows(tools)
    names = {r[0] for r in rows}
    if len(rows) < 50 or not {"max_parts", "map_polarity", "refine_score"} <= names:
        print(f"sbr_config: {len(rows)} table rows")
        return 1
    exe = os.path.join(tools, "sbr_detect")
    h = run([exe, "--help"]).stdout
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "00000.ppm"), "wb") as f:
            f.write(b"P6 64 64 255\n" + bytes(64 * 64 * 3))
        base = [exe, "--input", tmp, "--detections", os.path.join(tmp, "d.txt"), "--quiet"]
        for field, opt, typ, rng, default in rows:
            lo, hi = (x.split(" (")[0] for x in rng.split(" .. "))
            shown = re.search(r"^\s+" + re.escape(opt) + r" [^\n]*", h, re.M)
            want = default.replace(", ", ",")
            good = shown is not None and (("=" + want) in shown.group(0) or "trained: " + want in shown.group(0))
            if typ.startswith("uint32"):
                r = run(base + [opt, str(int(hi) + 1)])
                good = good and r.returncode == 2 and opt in r.stderr
            else:
                r = run(base + [opt, "nan"])
                good = good and r.returncode == 2 and opt in r.stderr
            if not good:
                print(f"sbr_detect {opt}: help {shown.group(0).strip() if shown else 'missing'!r}, "
                      f"beyond its range: exit {r.returncode}")
                failures += 1
        r = run(base + ["--min-size", "50", "--max-size", "20"])
        good = r.returncode == 2 and "--max-size 20" in r.stderr and "at least min_size" in r.stderr
        print(f"sbr_detect --min-size 50 --max-size 20: exit {r.returncode}: {r.stderr.strip()[:100]!r}")
        failures += not good
    print(f"sbr_detect: the {len(rows)} options of the core's tables: "
          + ("each with its default and range" if failures == 0 else f"{failures} disagree"))
    return failures


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=60)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tools", required=True)
    ap.add_argument("--tests", required=True, help="folder of the C++ test programs (tests/host)")
    ap.add_argument("--sbr-sh", help="./sbr.sh: each subcommand's --help prints its usage, runs nothing")
    a = ap.parse_args()
    failures = 0
    if a.sbr_sh:
        for sub in ["test", "detect", "train", "crossval", "cost", "track", "learn-tracker", "fuzz", "setup"]:
            r = run(["bash", a.sbr_sh, sub, "--help"])
            good = r.returncode == 0 and f"./sbr.sh {sub}" in r.stdout and "==" not in r.stdout
            print(f"sbr.sh {sub} --help: exit {r.returncode}{'' if good else ' (usage missing or it ran)'}")
            failures += not good
        # a missing input folder is refused before anything is set up or written
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "out")
            missing = os.path.join(tmp, "no-such-folder")
            r = run(["bash", a.sbr_sh, "detect", "--input", missing, "--out", out, "--threshold", "0.5"])
            good = r.returncode == 2 and missing in r.stderr and not os.path.exists(out)
            print(f"sbr.sh detect --input MISSING: exit {r.returncode}, output folder "
                  f"{'created' if os.path.exists(out) else 'not created'}")
            failures += not good
            # an option without its value, a missing --baseline or --model file, an
            # unknown command: named, exit 2, nothing run or written
            for args, says in ((["detect", "--input"], "--input needs a value"),
                               (["detect", "--baseline", missing, "--out", out], f"--baseline {missing}: no such file"),
                               (["detect", "--model", missing, "--out", out], f"--model {missing}: no such file"),
                               (["bogus"], "unknown command 'bogus'")):
                r = run(["bash", a.sbr_sh] + args)
                good = r.returncode == 2 and says in r.stderr and not os.path.exists(out) and not re.search(r"line [0-9]+:", r.stderr)
                print(f"sbr.sh {' '.join(args[:2])}: exit {r.returncode}, {r.stderr.strip()[:90]!r}")
                failures += not good
        r = run(["bash", a.sbr_sh, "--help"])
        good = r.returncode == 0 and "./sbr.sh detect" in r.stdout and not re.search(r"^#", r.stdout, re.M)
        print(f"sbr.sh --help: exit {r.returncode}{'' if good else ' (comment marks or usage missing)'}")
        failures += not good
    def where(prog):
        return os.path.join(a.tests if prog.startswith("test_") else a.tools, prog)

    for tool, (required, bad) in CASES.items():
        exe = where(tool)
        h = run([exe, "--help"])
        opts = sorted(set(re.findall(r"^\s+(?:-\w,)?(--[a-z][a-z0-9-]*)", h.stdout, re.M)))
        # every option has a description: its help block (its line and the indented lines
        # under it) holds words besides the option's name and its type column
        undescribed = []
        lines = h.stdout.splitlines()
        for o in opts:
            if o == "--help":
                continue
            k = next(i for i, l in enumerate(lines) if re.match(r"^\s+(?:-\w,)?" + re.escape(o) + r"\b", l))
            block = [lines[k].split(o, 1)[1]]
            for l in lines[k + 1:]:
                if not l.strip() or re.match(r"^\s+-", l):
                    break
                block.append(l)
            words = re.sub(r"\b[A-Z]+\b|\[[^\]]*\]|\S*:\S*|=\S+", " ", " ".join(block))
            if not re.search(r"[a-z]{3,}", words):
                undescribed.append(o)
        ok = h.returncode == 0 and len(opts) >= 2 and not undescribed
        print(f"{tool} --help: exit {h.returncode}, {len(opts)} options"
              + (f", without a description: {undescribed}" if undescribed else ""))
        failures += not ok
        for opt, val in bad:
            r = run([exe] + required + [opt, val])
            good = r.returncode == 2 and opt in r.stderr
            print(f"{tool} {opt} {val}: exit {r.returncode}: {r.stderr.strip().splitlines()[0] if r.stderr.strip() else ''}")
            failures += not good
        r = run([exe] + required + ["--no-such-option"])
        print(f"{tool} --no-such-option: exit {r.returncode}")
        failures += r.returncode != 2
    # the host test programs: --help says what they test (exit 0, nothing run); an option
    # they do not take is named (exit 2), never read as a path
    for prog in ["test_mser_opencv", "test_contour_opencv", "test_annotate", "test_geometry",
                 "test_model_files", "test_builtin_models_gtsdb", "test_cli_state"]:
        exe = where(prog)
        if not os.path.exists(exe):
            print(f"{prog}: missing from {os.path.dirname(exe)}")
            failures += 1
            continue
        h = run([exe, "--help"])
        b = run([exe, "--no-such-option"])
        good = (h.returncode == 0 and re.search(r"(?i)usage", h.stdout) is not None and "SKIP" not in h.stdout
                and b.returncode == 2 and ("--no-such-option" in b.stderr or prog == "test_builtin_models_gtsdb"))
        print(f"{prog} --help: exit {h.returncode}; --no-such-option: exit {b.returncode}")
        failures += not good
    failures += check_recogniser_options(a.tools)
    failures += check_detect_docs(a.tools, a.sbr_sh)
    print("cli: " + ("OK" if failures == 0 else f"{failures} FAILED"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
