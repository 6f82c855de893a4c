#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""sbr_crossval on a small GTSDB subset: the folds, the pooled figures, reuse and baseline.

Three folds of four images each (GTSDB 00400-00411; each fold's models are trained on the
other eight images, which is enough to run, not to recognise well). Checked, independently
of the script's own sums:
  - each fold's evaluation covers its four images and the ground truth in them (counted
    here from gt.txt); its models were trained on the other two folds' ranges;
  - the pooled ("summed") detections are the three folds' files one after the other, and
    the summed TP, FP, FN and ground truth of every superclass and at class level are the
    sums over the folds (the folds' images are disjoint);
  - the printed table has the summed signs line with those counts;
  - a second run with --models (the first run's, no training) and --baseline (the first
    run) gives byte-identical detections, 0 signs gained and 0 lost;
  - folds that do not split the images evenly are refused;
  - a tool option without a value of its own is passed on (`--picto-args --no-mirror`).

usage: test_crossval.py --script sbr_crossval.py --tools DIR --data DIR --work DIR
(exit 77 without the data)
"""
import argparse
import importlib.util
import json
import os
import shutil
import subprocess
import sys

SUPER = ["prohibitory", "mandatory", "danger", "other"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--script", required=True)
    ap.add_argument("--tools", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    gt_path = os.path.join(a.data, "FullIJCNN2013", "gt.txt")
    if not os.path.exists(gt_path):
        print(f"SKIP: no GTSDB at {a.data}")
        return 77
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    base = [sys.executable, a.script, "--tools", a.tools, "--data", a.data, "--first", "400", "--last", "411"]
    first = os.path.join(a.work, "first")
    r = subprocess.run(base + ["--out", first], capture_output=True, text=True)
    print(r.stdout, r.stderr)
    if r.returncode != 0:
        return 1
    ok = True
    gt_in = {}
    for line in open(gt_path):
        p = line.strip().split(";")
        if len(p) >= 6:
            gt_in.setdefault(int(p[0][:5]), []).append(int(p[5]))
    with open(os.path.join(first, "crossval.json")) as f:
        cv = json.load(f)
    folds = cv["folds"]
    want_spans = [[400, 403], [404, 407], [408, 411]]
    ok &= [f["test"] for f in folds] == want_spans
    for f, span in zip(folds, want_spans):
        others = [s for s in want_spans if s != span]
        n_gt = sum(len(gt_in.get(i, [])) for i in range(span[0], span[1] + 1))
        good = f["train"] == others and f["eval"]["images"] == 4 and f["eval"]["gt"] == n_gt
        print(f"fold {f['fold']}: test {f['test']}, train {f['train']}, images {f['eval']['images']}, "
              f"gt {f['eval']['gt']} (counted {n_gt}): {'OK' if good else 'WRONG'}")
        ok &= good
    pooled = "".join(open(os.path.join(first, f"fold{k}", "detections_all.txt")).read() for k in (1, 2, 3))
    same_file = pooled == open(os.path.join(first, "detections_all.txt")).read()
    print(f"pooled detections are the folds' files: {same_file} ({pooled.count(chr(10))} lines)")
    ok &= same_file
    summed = cv["summed"]["eval"]
    for s in SUPER:
        for key in ("tp", "fp", "fn", "gt"):
            total = sum(f["eval"]["eval"]["superclasses"][s][key] for f in folds)
            if summed["superclasses"][s][key] != total:
                print(f"summed {s} {key}: {summed['superclasses'][s][key]}, folds add up to {total}: WRONG")
                ok = False
    for key in ("tp", "fp", "fn"):
        total = sum(f["eval"]["eval"]["class_level"][key] for f in folds)
        if summed["class_level"][key] != total:
            print(f"summed class-level {key}: {summed['class_level'][key]}, folds add up to {total}: WRONG")
            ok = False
    line = "signs found (superclass level) / total, summed over folds: " + ", ".join(
        f"{s} {sum(f['eval']['eval']['superclasses'][s]['tp'] for f in folds)}/"
        f"{sum(f['eval']['eval']['superclasses'][s]['gt'] for f in folds)}" for s in SUPER)
    print(f"expecting '{line}'")
    ok &= line in r.stdout and "class-level F1" in r.stdout

    again = os.path.join(a.work, "again")
    r2 = subprocess.run(base + ["--out", again, "--models", first, "--baseline", first], capture_output=True,
                        text=True)
    print(r2.stdout, r2.stderr)
    with open(os.path.join(again, "crossval.json")) as f:
        cv2 = json.load(f)
    ident = open(os.path.join(again, "detections_all.txt")).read() == pooled
    changes = [(len(f["eval"]["gained"]), len(f["eval"]["lost"])) for f in cv2["folds"]]
    changes.append((len(cv2["summed"]["gained"]), len(cv2["summed"]["lost"])))
    print(f"reused models: detections identical {ident}, gained/lost per fold and summed {changes}")
    ok &= r2.returncode == 0 and ident and changes == [(0, 0)] * 4 and "signs gained 0, lost 0" in r2.stdout
    ok &= "sbr_train" not in cv2["folds"][0]["times"]

    bad = subprocess.run(base + ["--out", os.path.join(a.work, "bad"), "--folds", "5"], capture_output=True,
                         text=True)
    print(f"--folds 5 of 12 images: exit {bad.returncode}, {bad.stderr.strip()}")
    ok &= bad.returncode != 0 and "equal folds" in bad.stderr

    spec = importlib.util.spec_from_file_location("sbr_crossval", a.script)
    cvmod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(cvmod)
    joined = cvmod.join_tool_args(["--picto-args", "--no-mirror", "--out", "x", "--detect-args", "--views 1"])
    want = ["--picto-args=--no-mirror", "--out", "x", "--detect-args=--views 1"]
    print(f"tool options joined: {joined}")
    ok &= joined == want
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
