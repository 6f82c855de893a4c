#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""sbr_robustness: the cross-validation's fold models on corrupted copies of each fold's
test images (docs/usage/robustness.md).

    sbr_robustness.py --tools BUILD/native/host_tools --data GTSDB --models CVDIR --out DIR
                      [--cache DIR] [--corruptions a,b|all] [--severities 1,2,3]
                      [--first 0 --last 599 --folds 3] [--jobs N] [--baseline DIR] [--no-grey]
                      [--detect-args "..."]

--models CVDIR  a cross-validation run (./sbr.sh crossval --out CVDIR): fold K's test images
                run with CVDIR/foldK/model.sbrm and picto.sbrp; `builtin`: the built-in
                models on every fold (for smoke runs; training-set figures on 0-599)
--cache DIR     the corrupted images, PNG, one folder per corruption, severity and
                parameter hash (default: $XDG_CACHE_HOME/sbr/robustness, else
                ~/.cache/sbr/robustness); made once, read by every later run
--baseline DIR  an earlier run's --out: its figures beside this run's, and in the plot

Every image's corruption is seeded by (corruption, severity, image number), so every run
sees the same pixels. The clean images are read as they are (the GTSDB files), the grey
run is sbr_detect --grey on them. Per condition the folds' detections are pooled and
scored by sbr_eval at the operating point: per superclass recall and precision, the
class-level F1. mPC: the mean class F1 over every corruption and severity run; rPC = mPC /
clean F1; the worst corruption (lowest mean F1 over its severities). Writes
DIR/robustness.txt (what it prints), DIR/robustness.json, DIR/robustness.png (F1 by
corruption and severity; with --baseline, before and after) and DIR/<condition>/foldK/.
Needs numpy, OpenCV (cv2), albumentations and Pillow: the project's venv (build/venv).
"""
import argparse
import concurrent.futures
import json
import os
import re
import shlex
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "crossval"))
import corruptions as C  # noqa: E402
from sbr_crossval import fold_spans, join_tool_args  # noqa: E402 - the cross-validation's folds, the same split

SUPER = ["prohibitory", "mandatory", "danger", "other"]
SCORED = ["prohibitory", "mandatory", "danger"]


def image_files(data):
    d = os.path.join(data, "FullIJCNN2013") if os.path.isdir(os.path.join(data, "FullIJCNN2013")) else data
    out = {}
    for f in os.listdir(d):
        stem, ext = os.path.splitext(f)
        if stem.isdigit() and ext.lower() in (".jpg", ".jpeg", ".png", ".ppm"):
            out[int(stem)] = os.path.join(d, f)
    return d, out


# --- the corrupted copies -------------------------------------------------------------

def _make_one(job):
    """One corrupted image into the cache (a worker process); returns the path."""
    name, sev, number, src, dst = job
    if os.path.isfile(dst):
        return dst
    import cv2
    cv2.setNumThreads(1)
    bgr = cv2.imread(src, cv2.IMREAD_COLOR)
    if bgr is None:
        raise RuntimeError(f"{src}: cannot be read")
    rgb = cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)
    t = C.build(name, sev)
    t.set_random_seed(C.seed(name, sev, number))
    out = t(image=rgb)["image"]
    tmp = f"{dst}.{os.getpid()}.tmp.png"
    if not cv2.imwrite(tmp, cv2.cvtColor(out, cv2.COLOR_RGB2BGR)):
        raise RuntimeError(f"{tmp}: cannot be written")
    os.replace(tmp, dst)  # whole or not at all
    return dst


def make_copies(a, conds, numbers, files):
    """Every condition's corrupted images in the cache; returns {condition: folder}."""
    import albumentations
    version = albumentations.__version__
    folders, jobs = {}, []
    for name, sev in conds:
        d = os.path.join(a.cache, f"{name}-s{sev}-{C.key(name, sev, version)}")
        os.makedirs(d, exist_ok=True)
        folders[(name, sev)] = d
        for n in numbers:
            dst = os.path.join(d, f"{n:05d}.png")
            if not os.path.isfile(dst):
                jobs.append((name, sev, n, files[n], dst))
    if jobs:
        t0 = time.monotonic()
        print(f"sbr_robustness: making {len(jobs)} corrupted images in {a.cache} ({a.jobs} processes)", flush=True)
        import multiprocessing
        with multiprocessing.get_context("spawn").Pool(a.jobs) as pool:
            for _ in pool.imap_unordered(_make_one, jobs, chunksize=4):
                pass
        print(f"sbr_robustness: made them in {time.monotonic() - t0:.0f} s", flush=True)
    return folders, version


# --- detection and scoring ------------------------------------------------------------

def fold_models(a, k):
    if a.models == "builtin":
        return []
    d = os.path.join(a.models, f"fold{k + 1}")
    model, picto = os.path.join(d, "model.sbrm"), os.path.join(d, "picto.sbrp")
    if not (os.path.isfile(model) and os.path.isfile(picto)):
        raise SystemExit(f"sbr_robustness: --models {a.models}: no model.sbrm and picto.sbrp in {d}")
    return ["--model", model, "--picto", picto]


def detect(a, cond, folder, k, span, extra):
    """sbr_detect on one fold of one condition; returns (condition, fold, operating point)."""
    d = os.path.join(a.out, cond, f"fold{k + 1}")
    os.makedirs(d, exist_ok=True)
    summary = os.path.join(d, "summary.txt")
    cmd = [os.path.join(a.tools, "sbr_detect"), "--input", folder, "--range", f"{span[0]}-{span[1]}",
           "--detections", os.path.join(d, "detections.txt"),
           "--all-detections", os.path.join(d, "detections_all.txt"),
           "--summary", summary, "--quiet"] + fold_models(a, k) + extra + shlex.split(a.detect_args)
    with open(os.path.join(d, "log.txt"), "w") as log:
        r = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT)
    if r.returncode not in (0, 3):
        raise RuntimeError(f"sbr_detect failed (status {r.returncode}) on {cond} fold {k + 1}: see {d}/log.txt")
    with open(summary) as f:
        m = re.search(r"operating point score >= ([0-9.eE+-]+)", f.read())
    return cond, k, float(m.group(1))


def score(a, cond, spans, thr):
    """The folds' detections pooled and scored: sbr_eval's JSON figures."""
    d = os.path.join(a.out, cond)
    pooled = os.path.join(d, "detections_all.txt")
    with open(pooled, "w") as o:
        for k in range(len(spans)):
            with open(os.path.join(d, f"fold{k + 1}", "detections_all.txt")) as f:
                o.write(f.read())
    js = os.path.join(d, "eval.json")
    with open(os.path.join(d, "evaluation.txt"), "w") as f:
        subprocess.run([os.path.join(a.tools, "sbr_eval"), "--detections", pooled, "--gt", a.gt,
                        "--range", ",".join(f"{s}-{e}" for s, e in spans), "--threshold", repr(thr), "--json", js],
                       stdout=f, check=True)
    with open(js) as f:
        e = json.load(f)["eval"]
    fig = {"f1": e["class_level"]["f1"]}
    for s in SUPER:
        x = e["superclasses"][s]
        fig[s] = {"found": x["tp"], "gt": x["gt"], "fp": x["fp"],
                  "recall": x["recall"] if x["gt"] else None,
                  "precision": x["precision"] if x["tp"] + x["fp"] else None}
    return fig


def cond_name(name, sev):
    return f"{name}-s{sev}"


def summarise(figs, corr):
    """mPC, rPC and the worst corruption from the figures of every condition."""
    runs = [figs[cond_name(n, s)]["f1"] for n, s in corr]
    if not runs:
        return {}
    mpc = sum(runs) / len(runs)
    clean = figs["clean"]["f1"]
    per = {}
    for n, s in corr:
        per.setdefault(n, []).append(figs[cond_name(n, s)]["f1"])
    worst = min(per, key=lambda n: sum(per[n]) / len(per[n]))
    return {"mPC": mpc, "rPC": mpc / clean if clean > 0 else 0.0, "worst": worst,
            "worst_f1": sum(per[worst]) / len(per[worst])}


def fmt(v, digits=3):
    return "-" if v is None else f"{v:.{digits}f}"


def report(a, figs, corr, summ, base, elapsed):
    out = []
    p = out.append
    p(f"robustness of sbr's recogniser: GTSDB {a.first:05d}-{a.last:05d} in {a.folds} folds, models "
      + ("built-in (every fold)" if a.models == "builtin" else f"of {a.models} (each fold's own)")
      + f"; corruptions: albumentations {figs['_version']}, seeded per image (docs/usage/robustness.md)")
    p("operating point of the class stage, IoU >= 0.5, the folds pooled; recall (found/total) and precision per "
      "superclass; F1 class level; 'of clean': F1 / clean F1"
      + ("; 'before': the baseline " + a.baseline if base else ""))
    p("")
    head = f"{'condition':22s}" + "".join(f"{s + ' R/P':>22s}" for s in SCORED) + f"{'F1':>8s}{'of clean':>10s}"
    if base:
        head += f"{'before F1':>11s}{'of clean':>10s}"
    p(head)
    clean = figs["clean"]["f1"]
    bclean = base["figures"]["clean"]["f1"] if base else None
    for cond in ["clean", "grey"] + [cond_name(n, s) for n, s in corr]:
        if cond not in figs:
            continue
        f = figs[cond]
        cells = "".join(f"{fmt(f[s]['recall'])} ({f[s]['found']:>3d}) / {fmt(f[s]['precision'])}".rjust(22)
                        for s in SCORED)
        line = f"{cond:22s}{cells}{f['f1']:8.3f}{f['f1'] / clean if clean else 0:10.3f}"
        if base:
            b = base["figures"].get(cond)
            line += (f"{b['f1']:11.3f}{b['f1'] / bclean if bclean else 0:10.3f}" if b else f"{'-':>11s}{'-':>10s}")
        p(line)
    p("")
    if summ:
        s = summ
        p(f"mPC (mean class F1 over {len(corr)} corruption runs) {s['mPC']:.4f}; clean F1 {clean:.4f}; "
          f"rPC {s['rPC']:.4f}; worst corruption: {s['worst']} (mean F1 {s['worst_f1']:.3f})")
        if base and base.get("summary"):
            b = base["summary"]
            p(f"before: mPC {b['mPC']:.4f}, clean F1 {bclean:.4f}, rPC {b['rPC']:.4f}, worst {b['worst']}")
        sev2 = [cond_name(n, 2) for n in dict(corr) if cond_name(n, 2) in figs]
        if sev2:
            low = [c for c in sev2 if figs[c]["f1"] < 0.85 * clean]
            p(f"severity 2 below 0.85 of the clean F1: {', '.join(low) if low else 'none'}")
        keep = []
        for n in ("under_exposure", "over_exposure", "backlight"):
            c = cond_name(n, 2)
            if c in figs:
                for sc in SCORED:
                    r, r0 = figs[c][sc]["recall"], figs["clean"][sc]["recall"]
                    if r is not None and r0:
                        keep.append(f"{n} {sc} {r / r0:.3f}")
        if keep:
            p("exposure at severity 2, recall kept of clean: " + ", ".join(keep))
    p(f"time: {elapsed / 60:.1f} min")
    return "\n".join(out) + "\n"


def plot(path, figs, corr, base):
    """F1 by corruption (groups) and severity (bars); the baseline's as grey bars beside."""
    from PIL import Image, ImageDraw
    names = list(dict.fromkeys(n for n, _ in corr))
    sevs = sorted({s for _, s in corr})
    n_bars = (len(names) * len(sevs) + 2) * (2 if base else 1)
    W, H, x0, y0, ph = 130 + n_bars * (12 if base else 22) + 30 * (len(names) + 2), 480, 60, 40, 380
    W = max(W, 720)
    img = Image.new("RGB", (W, H), "white")
    d = ImageDraw.Draw(img)
    for k in range(11):
        gy = y0 + ph - round(k / 10 * ph)
        d.line([(x0, gy), (W - 20, gy)], fill=(225, 225, 225))
        d.text((x0 - 30, gy - 6), f"{k / 10:.1f}", fill="black")
    d.text((5, 8), "class-level F1 by corruption and severity (1 light .. 3 dark bars)"
                   + ("; grey: before" if base else "") + "; line: clean F1", fill="black")
    shades = {1: (120, 170, 230), 2: (40, 110, 200), 3: (10, 50, 120)}
    groups = [("clean", [("clean", None)])] + ([("grey", [("grey", None)])] if "grey" in figs else []) + \
             [(n, [(cond_name(n, s), s) for s in sevs]) for n in names]
    x = x0 + 10
    bw = 12 if base else 22
    before = base["figures"] if base else {}
    for label, conds in groups:
        gx = x
        for cond, s in conds:
            bars = ([(before[cond], (170, 170, 170))] if cond in before else []) + \
                   [(figs[cond], shades.get(s, (60, 160, 60)))]
            for f, colour in bars:
                top = y0 + ph - round(f["f1"] * ph)
                d.rectangle([x, top, x + bw - 2, y0 + ph], fill=colour)
                x += bw
        d.text((gx, y0 + ph + 8 + 14 * (len(label) > 10 and groups.index((label, conds)) % 2)), label, fill="black")
        x += 30
    cy = y0 + ph - round(figs["clean"]["f1"] * ph)
    d.line([(x0, cy), (W - 20, cy)], fill=(220, 40, 40))
    d.rectangle([x0, y0, W - 20, y0 + ph], outline="black")
    img.save(path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tools", help="folder of sbr_detect and sbr_eval")
    ap.add_argument("--data", help="GTSDB folder (images and gt.txt)")
    ap.add_argument("--models", help="a cross-validation run's folder, or builtin")
    ap.add_argument("--out")
    ap.add_argument("--cache", default=os.path.join(os.environ.get("XDG_CACHE_HOME") or
                                                    os.path.join(os.path.expanduser("~"), ".cache"),
                                                    "sbr", "robustness"))
    ap.add_argument("--corruptions", default="all", help="names separated by commas, or all (default)")
    ap.add_argument("--severities", default="1,2,3")
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument("--last", type=int, default=599)
    ap.add_argument("--folds", type=int, default=3)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--baseline", help="an earlier run's --out")
    ap.add_argument("--no-grey", action="store_true", help="no grey (GRAY8) run")
    ap.add_argument("--detect-args", default="", help="extra sbr_detect options, e.g. \"--map-polarity 3,3,3\"")
    ap.add_argument("--print-table", action="store_true", help="print the corruption table (markdown) and stop")
    argv = sys.argv[1:] if argv is None else argv
    argv = join_tool_args(argv)  # --detect-args "--grey ..." as one value, as sbr_crossval takes it
    a = ap.parse_args(argv)
    if a.print_table:
        sys.stdout.write(C.markdown_table())
        return 0
    for opt in ("tools", "data", "models", "out"):
        if getattr(a, opt) is None:
            ap.error(f"--{opt} is needed")
    names = C.names() if a.corruptions == "all" else [n for n in a.corruptions.split(",") if n]
    bad = [n for n in names if n not in C.TABLE]
    if bad:
        ap.error(f"--corruptions: unknown {', '.join(bad)} (known: {', '.join(C.names())})")
    try:
        sevs = sorted({int(s) for s in a.severities.split(",")})
    except ValueError:
        sevs = [0]
    if not sevs or any(s not in C.SEVERITIES for s in sevs):
        ap.error("--severities: numbers from 1, 2, 3 separated by commas")
    if a.jobs < 1:
        ap.error("--jobs must be at least 1")
    for g in ("gt.txt", "FullIJCNN2013/gt.txt"):
        if os.path.isfile(os.path.join(a.data, g)):
            a.gt = os.path.join(a.data, g)
            break
    else:
        ap.error(f"--data {a.data}: no gt.txt there")
    base = None
    if a.baseline:
        try:
            with open(os.path.join(a.baseline, "robustness.json")) as f:
                base = json.load(f)
        except (OSError, ValueError) as e:
            ap.error(f"--baseline {a.baseline}: no readable robustness.json ({e})")
    # one fold: the images with the models of --models' fold1 (a pilot on one split)
    spans = [(a.first, a.last)] if a.folds == 1 else fold_spans(a.first, a.last, a.folds)
    for k in range(len(spans)):
        fold_models(a, k)  # every model file there before anything runs
    a.out = os.path.abspath(a.out)
    os.makedirs(a.out, exist_ok=True)
    t0 = time.monotonic()
    imgdir, files = image_files(a.data)
    numbers = [n for n in range(a.first, a.last + 1) if n in files]
    if not numbers:
        ap.error(f"--data {a.data}: no images numbered {a.first}-{a.last}")
    corr = [(n, s) for n in names for s in sevs]
    folders, version = make_copies(a, corr, numbers, files)
    conds = [("clean", imgdir, [])] + ([] if a.no_grey else [("grey", imgdir, ["--grey"])]) + \
            [(cond_name(n, s), folders[(n, s)], []) for n, s in corr]
    thr = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as ex:
        futs = [ex.submit(detect, a, c, folder, k, spans[k], extra)
                for c, folder, extra in conds for k in range(len(spans))]
        try:
            for f in concurrent.futures.as_completed(futs):
                c, k, t = f.result()
                thr[c] = t
        except RuntimeError as e:
            raise SystemExit(f"sbr_robustness: {e}")
    figs = {c: score(a, c, spans, thr[c]) for c, _, _ in conds}
    summ = summarise(figs, corr)
    figs["_version"] = version
    text = report(a, figs, corr, summ, base, time.monotonic() - t0)
    with open(os.path.join(a.out, "robustness.txt"), "w") as f:
        f.write(text)
    version = figs.pop("_version")
    with open(os.path.join(a.out, "robustness.json"), "w") as f:
        json.dump({"figures": figs, "summary": summ, "albumentations": version, "models": a.models,
                   "range": [a.first, a.last], "folds": a.folds, "corruptions": names, "severities": sevs,
                   "detect_args": a.detect_args, "cache": a.cache}, f, indent=1)
    plot(os.path.join(a.out, "robustness.png"), figs, corr, base)
    sys.stdout.write(text)
    print(f"plot: {os.path.join(a.out, 'robustness.png')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
