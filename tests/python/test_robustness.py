#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The robustness benchmark's smoke run (host_tools/robustness/sbr_robustness.py): two
GTSDB images, two corruptions at severity 2, the built-in models.

    test_robustness.py --script sbr_robustness.py --tools DIR --data GTSDB --doc robustness.md --work DIR

Checks: every condition scored (clean, grey, both corruptions); the cached images are the
corrupted pixels (not the originals), and a second cache made anew holds byte-identical
files (seeded per image); the clean figures equal sbr_detect + sbr_eval run directly; mPC
and rPC follow from the per-condition F1; a second run reuses the cache and shows the first
as its baseline; the plot is a PNG; the docs' corruption table is the code's.
"""
import argparse
import filecmp
import json
import os
import shutil
import subprocess
import sys

FAILURES = []


def check(what, ok, detail=""):
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + str(detail) if detail != '' else ''}")
    if not ok:
        FAILURES.append(what)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
    if r.returncode != 0:
        print(r.stdout[-3000:], r.stderr[-3000:])
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--script", required=True)
    ap.add_argument("--tools", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--doc", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    src = os.path.join(a.data, "FullIJCNN2013")
    if not os.path.isfile(os.path.join(src, "00444.jpg")):
        print("SKIP: no GTSDB")
        return 77
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    py = sys.executable
    cache, cache2 = os.path.join(a.work, "cache"), os.path.join(a.work, "cache2")
    base = [py, a.script, "--tools", a.tools, "--data", a.data, "--models", "builtin", "--first", "444",
            "--last", "445", "--folds", "2", "--corruptions", "motion_blur,jpeg", "--severities", "2", "--jobs", "2"]
    out1 = os.path.join(a.work, "run1")
    r = run(base + ["--cache", cache, "--out", out1])
    check("the smoke run exits 0", r.returncode == 0, r.returncode)
    if r.returncode != 0:
        return 1
    check("it made the corrupted images", "making 4 corrupted images" in r.stdout)
    with open(os.path.join(out1, "robustness.json")) as f:
        js = json.load(f)
    figs = js["figures"]
    check("every condition scored", sorted(figs) == ["clean", "grey", "jpeg-s2", "motion_blur-s2"], sorted(figs))

    # the cached pixels: corrupted, and the same when made again
    import cv2
    import numpy as np
    folders = sorted(os.listdir(cache))
    check("a cache folder per corruption and severity", len(folders) == 2 and
          all(f.startswith(("jpeg-s2-", "motion_blur-s2-")) for f in folders), folders)
    for fo in folders:
        for n in ("00444", "00445"):
            got = cv2.imread(os.path.join(cache, fo, n + ".png"))
            orig = cv2.imread(os.path.join(src, n + ".jpg"))
            diff = float(np.abs(got.astype(np.int16) - orig.astype(np.int16)).mean()) if got is not None else -1
            check(f"{fo}/{n}.png differs from the original", got is not None and got.shape == orig.shape
                  and diff > 0.5, f"mean abs difference {diff:.2f}")
    r2 = run(base + ["--cache", cache2, "--out", os.path.join(a.work, "run1b"), "--no-grey"])
    same = r2.returncode == 0 and all(
        filecmp.cmp(os.path.join(cache, fo, n), os.path.join(cache2, fo, n), shallow=False)
        for fo in folders for n in os.listdir(os.path.join(cache, fo)))
    check("a second cache made anew is byte-identical (seeded per image)", same)
    if r2.returncode == 0:
        with open(os.path.join(a.work, "run1b", "robustness.json")) as f:
            js2 = json.load(f)
        check("and scores the same", all(js2["figures"][c] == figs[c] for c in ("clean", "jpeg-s2", "motion_blur-s2")))

    # the clean condition against sbr_detect and sbr_eval run directly
    d = os.path.join(a.work, "direct")
    os.makedirs(d)
    dets = os.path.join(d, "all.txt")
    subprocess.run([os.path.join(a.tools, "sbr_detect"), "--input", a.data, "--range", "444-445", "--quiet",
                    "--detections", os.path.join(d, "op.txt"), "--all-detections", dets], check=True,
                   capture_output=True)
    subprocess.run([os.path.join(a.tools, "sbr_eval"), "--detections", dets, "--gt", os.path.join(src, "gt.txt"),
                    "--range", "444-445", "--threshold", "0.7", "--json", os.path.join(d, "e.json")], check=True,
                   capture_output=True)
    with open(os.path.join(d, "e.json")) as f:
        e = json.load(f)["eval"]
    check("clean F1 = sbr_eval's on a direct run", abs(figs["clean"]["f1"] - e["class_level"]["f1"]) < 1e-9,
          f"{figs['clean']['f1']} vs {e['class_level']['f1']}")
    check("clean prohibitory found = sbr_eval's",
          figs["clean"]["prohibitory"]["found"] == e["superclasses"]["prohibitory"]["tp"]
          and figs["clean"]["prohibitory"]["gt"] == e["superclasses"]["prohibitory"]["gt"] > 0,
          figs["clean"]["prohibitory"])
    mpc = (figs["jpeg-s2"]["f1"] + figs["motion_blur-s2"]["f1"]) / 2
    s = js["summary"]
    check("mPC is the mean F1 of the corruption runs", abs(s["mPC"] - mpc) < 1e-12, s)
    check("rPC = mPC / clean F1", abs(s["rPC"] - mpc / figs["clean"]["f1"]) < 1e-12)
    check("the worst corruption is the lower one", s["worst"] == min(("jpeg", "motion_blur"),
                                                                      key=lambda n: figs[n + "-s2"]["f1"]))

    # a second run: the cache reused, the first run as baseline
    out2 = os.path.join(a.work, "run2")
    r = run(base + ["--cache", cache, "--out", out2, "--baseline", out1])
    check("a second run reuses the cache", r.returncode == 0 and "making" not in r.stdout)
    check("and shows the baseline", "before F1" in r.stdout and "before: mPC" in r.stdout)
    with open(os.path.join(out2, "robustness.png"), "rb") as f:
        check("the plot is a PNG", f.read(8) == b"\x89PNG\r\n\x1a\n")

    r = run([py, a.script, "--print-table"])
    with open(a.doc) as f:
        doc = f.read()
    check("docs/usage/robustness.md holds the code's corruption table", r.stdout and r.stdout in doc)
    r = run(base + ["--cache", cache, "--out", out2, "--corruptions", "snow"])
    check("an unknown corruption is refused (exit 2)", r.returncode == 2 and "unknown snow" in r.stderr)

    print(f"{len(FAILURES)} failures" if FAILURES else "robustness smoke run: every check passed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
