#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""sbr_crossval: k-fold cross-validation of sbr's recogniser on GTSDB 00000-00599.

For each fold, both models (the part library, sbr_train, and the class stage,
sbr_train_picto) are trained on the other folds and the recogniser (sbr_detect) runs on
the held-out fold with them; sbr_eval scores each fold and the three folds' detections
pooled ("summed over folds": every image is scored once, by the models that did not see
it). Folds are consecutive image numbers: with 3 folds of GTSDB 00000-00599, fold 1 is
00000-00199, fold 2 00200-00399, fold 3 00400-00599.

    sbr_crossval.py --tools BUILD/native/host_tools --data DIR --out DIR
                    [--jobs N] [--seed S] [--models DIR | --parts DIR] [--baseline DIR]
                    [--train-args "..."] [--picto-args "..."] [--detect-args "..."]

--models DIR   reuse the fold models of an earlier run (DIR/fold*/model.sbrm, picto.sbrp)
               instead of training: for settings of the recogniser that need no retraining
               (with --detect-args)
--parts DIR    reuse only the part libraries of an earlier run (DIR/fold*/model.sbrm) and
               train the class stage anew: for variants of the class stage (--picto-args)
--baseline DIR an earlier run's --out: per fold and summed, the figures of both runs and
               the signs gained and lost (sbr_eval --baseline)
--*-args       extra options for sbr_train, sbr_train_picto and sbr_detect, to try a
               variant (e.g. --detect-args "--vote-error 0.15")

Writes DIR/crossval.txt (what it prints), DIR/crossval.json, DIR/detections_all.txt (the
pooled detections), DIR/pr_curve.png and per fold DIR/foldK/ (models, detections,
summary, evaluation). Only the Python standard library is needed.
"""
import argparse
import concurrent.futures
import json
import math
import os
import re
import shlex
import shutil
import subprocess
import sys
import time

SUPER = ["prohibitory", "mandatory", "danger", "other"]


def fold_spans(first, last, k):
    n = last - first + 1
    if k < 2 or n % k:
        raise SystemExit(f"sbr_crossval: {n} images do not split into {k} equal folds")
    size = n // k
    return [(first + i * size, first + (i + 1) * size - 1) for i in range(k)]


def ranges(spans):
    return ",".join(f"{a}-{b}" for a, b in spans)


def run(cmd, log):
    """Runs cmd, its output appended to log; raises with the log's tail on failure."""
    t0 = time.monotonic()
    with open(log, "a") as f:
        f.write("$ " + " ".join(shlex.quote(c) for c in cmd) + "\n")
        f.flush()
        r = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        with open(log) as f:
            tail = "".join(f.readlines()[-20:])
        raise RuntimeError(f"{os.path.basename(cmd[0])} failed (status {r.returncode}), see {log}:\n{tail}")
    return time.monotonic() - t0


def operating_point(summary):
    with open(summary) as f:
        m = re.search(r"operating point score >= ([0-9.eE+-]+)", f.read())
    if not m:
        raise RuntimeError(f"no operating point in {summary}")
    return float(m.group(1))


def eval_cmd(a, dets, rng, thr, plot, js, base):
    cmd = [os.path.join(a.tools, "sbr_eval"), "--detections", dets, "--gt", a.gt, "--range", rng,
           "--threshold", repr(thr), "--plot", plot, "--json", js]
    if base:
        cmd += ["--baseline", base]
    return cmd


def one_fold(a, k, test, train):
    d = os.path.join(a.out, f"fold{k + 1}")
    os.makedirs(d, exist_ok=True)
    log = os.path.join(d, "log.txt")
    open(log, "w").close()
    times = {}
    model, picto = os.path.join(d, "model.sbrm"), os.path.join(d, "picto.sbrp")
    if a.models:
        src = os.path.join(a.models, f"fold{k + 1}")
        model, picto = os.path.join(src, "model.sbrm"), os.path.join(src, "picto.sbrp")
        if not (os.path.isfile(model) and os.path.isfile(picto)):
            raise RuntimeError(f"--models {a.models}: no model.sbrm and picto.sbrp in {src}")
    else:
        if a.parts:
            src = os.path.join(a.parts, f"fold{k + 1}", "model.sbrm")
            if not os.path.isfile(src):
                raise RuntimeError(f"--parts {a.parts}: no {src}")
            shutil.copyfile(src, model)
        else:
            times["sbr_train"] = run([os.path.join(a.tools, "sbr_train"), "--data", a.data, "--range",
                                      ranges(train), "--out-model", model] + shlex.split(a.train_args), log)
        # the class stage learns from --gtsrb's training tracks too, and without --gtsrb from
        # GTSDB alone (not from the trainer's default data folder), unless the picto
        # arguments say otherwise
        extra = shlex.split(a.picto_args)
        if not any(x.split("=")[0] in ("--gtsrb", "--no-gtsrb") for x in extra):
            extra = (["--gtsrb", a.gtsrb] if a.gtsrb else ["--no-gtsrb"]) + extra
        times["sbr_train_picto"] = run([os.path.join(a.tools, "sbr_train_picto"), "--data", a.data,
                                        "--range", ranges(train), "--model", model, "--seed", str(a.seed),
                                        "--out", picto] + extra, log)
    gtsrb = None
    if a.gtsrb:
        # the fold's class stage on GTSRB's validation tracks (never trained on)
        gj = os.path.join(d, "gtsrb.json")
        with open(os.path.join(d, "gtsrb.txt"), "w") as f:
            subprocess.run([os.path.join(a.tools, "sbr_gtsrb_eval"), "--gtsrb", a.gtsrb, "--picto", picto,
                            "--threads", "1", "--json", gj], stdout=f, check=True)
        with open(gj) as f:
            gtsrb = json.load(f)
    dets = os.path.join(d, "detections_all.txt")
    summary = os.path.join(d, "summary.txt")
    times["sbr_detect"] = run([os.path.join(a.tools, "sbr_detect"), "--input", a.data, "--range", ranges([test]),
                               "--model", model, "--picto", picto, "--detections", os.path.join(d, "detections.txt"),
                               "--all-detections", dets, "--summary", summary, "--quiet"]
                              + shlex.split(a.detect_args), log)
    thr = operating_point(summary)
    base = os.path.join(a.baseline, f"fold{k + 1}", "detections_all.txt") if a.baseline else None
    with open(os.path.join(d, "evaluation.txt"), "w") as f:
        subprocess.run(eval_cmd(a, dets, ranges([test]), thr, os.path.join(d, "pr_curve.png"),
                                os.path.join(d, "eval.json"), base), stdout=f, check=True)
    with open(os.path.join(d, "eval.json")) as f:
        ev = json.load(f)
    return {"fold": k + 1, "test": list(test), "train": [list(s) for s in train], "threshold": thr,
            "times": times, "eval": ev, "gtsrb": gtsrb}


def mean_sd(v):
    m = sum(v) / len(v)
    sd = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1)) if len(v) > 1 else 0.0
    return m, sd


def report(a, folds, pooled, spans, elapsed):
    out = []
    p = out.append
    k = len(folds)
    p(f"cross-validation of sbr's recogniser: {k} folds of GTSDB {spans[0][0]:05d}-{spans[-1][1]:05d}, "
      "each fold's models trained on the other folds")
    p("folds: " + ", ".join(f"{i + 1}: {a_:05d}-{b:05d}" for i, (a_, b) in enumerate(spans)))
    thrs = sorted({f["threshold"] for f in folds})
    p(f"operating point: score >= {', '.join(f'{t:g}' for t in thrs)}; IoU >= 0.5; "
      f"mean ± sd: over the {k} folds (sample standard deviation; '-': no ground truth or no detection); "
      "summed: the folds pooled")
    if a.models:
        p(f"models: reused from {a.models} (no training)")
    if a.parts:
        p(f"part libraries: reused from {a.parts} (class stage trained anew)")
    extra = [f"{n} {v}" for n, v in (("sbr_train", a.train_args), ("sbr_train_picto", a.picto_args),
                                      ("sbr_detect", a.detect_args)) if v]
    p("options: " + ("; ".join(extra) if extra else "defaults") + f"; class stage seed {a.seed}")
    p("")
    head = f"{'':24s}" + "".join(f"{'fold ' + str(f['fold']):>16s}" for f in folds) + f"{'mean ± sd':>18s}{'summed':>17s}"
    p(head)

    def row(name, get, count=None):
        # get(e) is None where the figure is undefined (no ground truth, no detections):
        # shown as "-" and left out of the mean
        vals = [get(f["eval"]["eval"]) for f in folds]
        known = [v for v in vals if v is not None]
        cells = []
        for f, v in zip(folds, vals):
            c = "-" if v is None else f"{v:.3f}"
            if count:
                c += f" ({count(f['eval']['eval'])})"
            cells.append(f"{c:>16s}")
        m, sd = mean_sd(known) if known else (None, None)
        ms = "-" if m is None else f"{m:.3f} ± {sd:.3f}"
        v = get(pooled["eval"])
        s = "-" if v is None else f"{v:.3f}"
        if count:
            s += f" ({count(pooled['eval'])})"
        p(f"{name:24s}" + "".join(cells) + f"{ms:>18s}{s:>17s}")

    def rec(x):
        return x["recall"] if x["tp"] + x["fn"] else None

    def prec(x):
        return x["precision"] if x["tp"] + x["fp"] else None

    for s in SUPER:
        g = lambda e, s=s: e["superclasses"][s]
        row(f"{s} recall", lambda e, g=g: rec(g(e)), lambda e, g=g: f"{g(e)['tp']}/{g(e)['gt']}")
        row(f"{s} precision", lambda e, g=g: prec(g(e)), lambda e, g=g: f"{g(e)['fp']} fp")
        row(f"{s} AP", lambda e, g=g: g(e)["ap"] if g(e)["gt"] else None)
    row("mean superclass AP", lambda e: sum(e["superclasses"][s]["ap"] for s in SUPER) / 4)
    c = lambda e: e["class_level"]
    row("class-level precision", lambda e: prec(c(e)), lambda e: f"{c(e)['fp']} fp")
    row("class-level recall", lambda e: rec(c(e)), lambda e: f"{c(e)['tp']}/{c(e)['tp'] + c(e)['fn']}")
    row("class-level F1", lambda e: c(e)["f1"])
    p("")
    p("signs found (superclass level) / total, summed over folds: " + ", ".join(
        f"{s} {pooled['eval']['superclasses'][s]['tp']}/{pooled['eval']['superclasses'][s]['gt']}" for s in SUPER))
    if a.baseline:
        p("")
        p(f"against the baseline {a.baseline} (class level; baseline -> this run):")
        for f in folds + [dict(fold="summed", eval=pooled)]:
            e, b = f["eval"]["eval"], f["eval"]["baseline"]
            name = f"fold {f['fold']}" if f["fold"] != "summed" else "summed"
            p(f"  {name:8s} F1 {b['class_level']['f1']:.4f} -> {e['class_level']['f1']:.4f}, "
              f"signs gained {len(f['eval']['gained'])}, lost {len(f['eval']['lost'])}; found "
              + ", ".join(f"{s} {b['superclasses'][s]['tp']}->{e['superclasses'][s]['tp']}" for s in SUPER)
              + "; fp " + ", ".join(f"{b['superclasses'][s]['fp']}->{e['superclasses'][s]['fp']}" for s in SUPER))
        for what in ("gained", "lost"):
            lst = pooled[what]
            p(f"  signs {what} (image;left;top;right;bottom;class): {len(lst)}" + (": " if lst else ""))
            for i in range(0, len(lst), 4):
                p("    " + "  ".join(lst[i:i + 4]))
    if all(f.get("gtsrb") for f in folds):
        p("")
        p(gtsrb_report(folds))
    p("")
    steps = {}
    for f in folds:
        for n, t in f["times"].items():
            steps.setdefault(n, []).append(t)
    p(f"time: {elapsed / 60:.1f} min in all with {a.jobs} folds at a time; per fold "
      + ", ".join(f"{n} {min(v) / 60:.1f}-{max(v) / 60:.1f} min" for n, v in steps.items()))
    return "\n".join(out) + "\n"


DANGER = [11, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31]


def gtsrb_report(folds):
    """Each fold's class stage on GTSRB's validation tracks: accuracy at the annotated box
    (the true class the most probable output, "no sign" included), per superclass, how often
    "no sign" wins, and the danger classes' confusions summed over the folds."""
    out = ["GTSRB validation tracks (sbr_gtsrb_eval; every fifth track of each class, never trained on), "
           "class stage of each fold at the annotated box:"]
    head = f"{'':24s}" + "".join(f"{'fold ' + str(f['fold']):>16s}" for f in folds) + f"{'mean':>10s}"
    out.append(head)

    def row(name, get):
        vals = [get(f["gtsrb"]) for f in folds]
        out.append(f"{name:24s}" + "".join(f"{v:>15.2f}%" for v in vals) + f"{sum(vals) / len(vals):>9.2f}%")

    pct = lambda a, b: 100.0 * a / b if b else 0.0
    row("accuracy", lambda g: pct(g["right"], g["crops"]))
    for s in SUPER:
        row(f"{s}", lambda g, s=s: pct(g["superclasses"][s]["right"], g["superclasses"][s]["crops"]))
    row("no sign most probable", lambda g: pct(g["no_sign"], g["crops"]))
    out.append("danger classes, summed over the folds (right / crops; most frequent other answers):")
    for c in DANGER:
        key = str(c)
        n = sum(f["gtsrb"]["classes"].get(key, {}).get("crops", 0) for f in folds)
        r = sum(f["gtsrb"]["classes"].get(key, {}).get("right", 0) for f in folds)
        bg = sum(f["gtsrb"]["classes"].get(key, {}).get("no_sign", 0) for f in folds)
        taken = {}
        for f in folds:
            for t, m in f["gtsrb"]["classes"].get(key, {}).get("taken_for", {}).items():
                taken[t] = taken.get(t, 0) + m
        worst = sorted(taken.items(), key=lambda x: -x[1])[:3]
        out.append(f"  {c:2d}: {pct(r, n):6.2f} % ({r}/{n}), no sign {bg}"
                   + "".join(f"; as {t}: {m}" for t, m in worst))
    return "\n".join(out)


TOOL_ARGS = ("--train-args", "--picto-args", "--detect-args")


def join_tool_args(argv):
    """`--picto-args --no-mirror` as `--picto-args=--no-mirror`: argparse would take a lone value
    that starts with '-' for an option of its own and refuse the command line."""
    out, i = [], 0
    while i < len(argv):
        if argv[i] in TOOL_ARGS and i + 1 < len(argv):
            out.append(f"{argv[i]}={argv[i + 1]}")
            i += 2
        else:
            out.append(argv[i])
            i += 1
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tools", required=True, help="folder of sbr_train, sbr_train_picto, sbr_detect, sbr_eval")
    ap.add_argument("--data", required=True, help="GTSDB folder (images and gt.txt)")
    ap.add_argument("--out", required=True)
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument("--last", type=int, default=599)
    ap.add_argument("--folds", type=int, default=3)
    ap.add_argument("--jobs", type=int, default=0, help="folds at a time (default: all)")
    ap.add_argument("--seed", type=int, default=2, help="class stage training seed (sbr.sh train's)")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--models")
    g.add_argument("--parts")
    ap.add_argument("--baseline")
    ap.add_argument("--gtsrb", help="GTSRB folder: each fold's class stage learns from its training tracks "
                                    "(unless --picto-args has --no-gtsrb) and is scored on its validation tracks")
    ap.add_argument("--train-args", default="")
    ap.add_argument("--picto-args", default="")
    ap.add_argument("--detect-args", default="")
    a = ap.parse_args(join_tool_args(sys.argv[1:]))
    a.out = os.path.abspath(a.out)
    for g in ("gt.txt", "FullIJCNN2013/gt.txt"):
        if os.path.isfile(os.path.join(a.data, g)):
            a.gt = os.path.join(a.data, g)
            break
    else:
        raise SystemExit(f"sbr_crossval: no gt.txt in {a.data}")
    if a.gtsrb and not os.path.isdir(a.gtsrb):
        raise SystemExit(f"sbr_crossval: --gtsrb {a.gtsrb}: no such folder")
    if a.baseline and not os.path.isfile(os.path.join(a.baseline, "detections_all.txt")):
        raise SystemExit(f"sbr_crossval: --baseline {a.baseline} holds no cross-validation run")
    spans = fold_spans(a.first, a.last, a.folds)
    a.jobs = a.jobs if a.jobs > 0 else len(spans)
    os.makedirs(a.out, exist_ok=True)
    t0 = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as ex:
        futs = [ex.submit(one_fold, a, k, spans[k], [s for j, s in enumerate(spans) if j != k])
                for k in range(len(spans))]
        try:
            folds = [f.result() for f in futs]
        except RuntimeError as e:
            raise SystemExit(f"sbr_crossval: {e}")
    pooled_dets = os.path.join(a.out, "detections_all.txt")
    with open(pooled_dets, "w") as o:
        for k in range(len(spans)):
            with open(os.path.join(a.out, f"fold{k + 1}", "detections_all.txt")) as f:
                o.write(f.read())
    thr = folds[0]["threshold"]
    if any(f["threshold"] != thr for f in folds):
        print("sbr_crossval: the folds' operating points differ; the pooled figures use fold 1's", file=sys.stderr)
    base = os.path.join(a.baseline, "detections_all.txt") if a.baseline else None
    js = os.path.join(a.out, "eval.json")
    with open(os.path.join(a.out, "evaluation.txt"), "w") as f:
        subprocess.run(eval_cmd(a, pooled_dets, ranges(spans), thr, os.path.join(a.out, "pr_curve.png"), js, base),
                       stdout=f, check=True)
    with open(js) as f:
        pooled = json.load(f)
    text = report(a, folds, pooled, spans, time.monotonic() - t0)
    with open(os.path.join(a.out, "crossval.txt"), "w") as f:
        f.write(text)
    with open(os.path.join(a.out, "crossval.json"), "w") as f:
        json.dump({"folds": folds, "summed": pooled, "seed": a.seed, "train_args": a.train_args,
                   "picto_args": a.picto_args, "detect_args": a.detect_args, "models": a.models, "parts": a.parts}, f, indent=1)
    sys.stdout.write(text)


if __name__ == "__main__":
    main()
