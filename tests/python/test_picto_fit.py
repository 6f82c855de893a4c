#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The class stage's library trainer (host_tools/train/picto_fit.py, sbr_train_picto
--trainer sklearn).

On constructed samples whose answers are known by construction:
  - three Gaussian classes and a background class in 24 dimensions, well apart: the
    fitted network (read back from its weights file and run here in numpy, as the core
    runs it) names at least 97 % of fresh samples right;
  - box targets that are a known linear function of the features: the box rows on the
    hidden units predict fresh samples' targets with R^2 >= 0.9;
  - with a tenth of the samples box-only (label -1); the weights file has the header
    and sizes of its format; two runs with the same seed write the same bytes and
    another seed other bytes; a truncated samples file is refused (non-zero exit).
And the tool end to end (with --tools): sbr_train_picto --trainer sklearn on a few GTSDB
images writes a class stage that sbr_detect loads and runs; a missing interpreter is a
named failure (exit 1), not a crash.

usage: test_picto_fit.py --script picto_fit.py [--tools DIR --data DIR] --work DIR
"""
import argparse
import os
import shutil
import struct
import subprocess
import sys

import numpy as np

F, K, R = 24, 4, 4


def make_samples(rng, n):
    centres = rng.normal(0.0, 1.0, (K, F)) * 3.0
    label = rng.integers(0, K, n).astype(np.int32)
    x = (centres[label] + rng.normal(0.0, 1.0, (n, F))).astype(np.float32)
    a = rng.normal(0.0, 0.3, (F, R))
    target = (x @ a).astype(np.float32)
    return centres, a, x, label, target


def write_samples(path, x, label, weight, has_box, hard, target, truncate=False):
    n = x.shape[0]
    blob = b"SBRSMP01" + struct.pack("<4i", n, F, K, R)
    blob += x.astype("<f4").tobytes() + label.astype("<i4").tobytes() + weight.astype("<f4").tobytes()
    blob += has_box.astype("u1").tobytes() + hard.astype("u1").tobytes() + target.astype("<f4").tobytes()
    with open(path, "wb") as f:
        f.write(blob[:-100] if truncate else blob)


def read_weights(path):
    with open(path, "rb") as f:
        blob = f.read()
    assert blob[:8] == b"SBRNET01", "magic"
    h, nf, nk, nr = struct.unpack("<4i", blob[8:24])
    v = np.frombuffer(blob[24:], dtype="<f4")
    sizes = [h * (nf + 1), nk * (h + 1), nr * (h + 1)]
    assert v.size == sum(sizes), f"weights file holds {v.size} values, its header says {sum(sizes)}"
    w1 = v[: sizes[0]].reshape(h, nf + 1)
    w2 = v[sizes[0] : sizes[0] + sizes[1]].reshape(nk, h + 1)
    w3 = v[sizes[0] + sizes[1] :].reshape(nr, h + 1)
    return (h, nf, nk, nr), w1, w2, w3


def forward(w1, w2, w3, x):
    hid = np.maximum(x @ w1[:, :-1].T + w1[:, -1], 0.0)
    logits = hid @ w2[:, :-1].T + w2[:, -1]
    box = hid @ w3[:, :-1].T + w3[:, -1]
    return logits.argmax(axis=1), box


def fit(script, samples, out, seed, extra=()):
    cmd = [sys.executable, script, "--samples", samples, "--out", out, "--hidden", "32", "--epochs", "8",
           "--seed", str(seed), "--batch", "32", "--bg-fraction", "0.5", *extra]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=600)


def check_constructed(a):
    rng = np.random.default_rng(7)
    centres, lin, x, label, target = make_samples(rng, 4000)
    has_box = rng.random(4000) < 0.5
    # a tenth of the samples are box-only (label -1), with a class the classifier must not see
    box_only = rng.random(4000) < 0.1
    label_in = label.copy()
    label_in[box_only] = -1
    has_box |= box_only
    weight = np.ones(4000, dtype=np.float32)
    hard = np.zeros(4000, dtype=bool)
    samples = os.path.join(a.work, "samples.bin")
    write_samples(samples, x, label_in, weight, has_box, hard, target)
    ok = True
    outs = []
    for run, seed in enumerate((3, 3, 4)):
        out = os.path.join(a.work, f"weights{run}.bin")
        r = fit(a.script, samples, out, seed)
        if r.returncode != 0:
            print(r.stdout, r.stderr)
            print(f"picto_fit.py run {run}: exit {r.returncode}: WRONG")
            return False
        outs.append(open(out, "rb").read())
    head, w1, w2, w3 = read_weights(os.path.join(a.work, "weights0.bin"))
    good = head == (32, F, K, R)
    print(f"weights header {head}: {'OK' if good else 'WRONG'}")
    ok &= good
    # fresh samples of the same classes and box relation
    label_t = rng.integers(0, K, 2000)
    x_t = (centres[label_t] + rng.normal(0.0, 1.0, (2000, F))).astype(np.float32)
    pred, box = forward(w1, w2, w3, x_t)
    acc = float((pred == label_t).mean())
    good = acc >= 0.97
    print(f"class accuracy on fresh samples {acc:.4f} (>= 0.97): {'OK' if good else 'WRONG'}")
    ok &= good
    t_t = x_t @ lin
    r2 = 1.0 - float(((box - t_t) ** 2).sum() / ((t_t - t_t.mean(axis=0)) ** 2).sum())
    good = r2 >= 0.9
    print(f"box rows' R^2 on fresh samples {r2:.4f} (>= 0.9): {'OK' if good else 'WRONG'}")
    ok &= good
    good = outs[0] == outs[1] and outs[0] != outs[2]
    print(f"same seed same bytes: {outs[0] == outs[1]}, another seed other bytes: {outs[0] != outs[2]}: "
          f"{'OK' if good else 'WRONG'}")
    ok &= good
    bad = os.path.join(a.work, "truncated.bin")
    write_samples(bad, x, label_in, weight, has_box, hard, target, truncate=True)
    r = fit(a.script, bad, os.path.join(a.work, "never.bin"), 3)
    good = r.returncode != 0 and not os.path.exists(os.path.join(a.work, "never.bin"))
    print(f"truncated samples file: exit {r.returncode}, no weights written: {'OK' if good else 'WRONG'}")
    ok &= good
    return ok


def check_tool(a):
    train = os.path.join(a.tools, "sbr_train_picto")
    detect = os.path.join(a.tools, "sbr_detect")
    out = os.path.join(a.work, "sk.sbrp")
    base = [train, "--data", a.data, "--range", "400-411", "--epochs", "2", "--no-gtsrb", "--no-gate",
            "--rounds", "1", "--trainer", "sklearn", "--seed", "2"]
    r = subprocess.run(base + ["--python", sys.executable, "--out", out], capture_output=True, text=True, timeout=900)
    good = r.returncode == 0 and os.path.getsize(out) > 0 and "picto_fit: epoch 2" in r.stderr
    print(f"sbr_train_picto --trainer sklearn: exit {r.returncode}: {'OK' if good else 'WRONG'}")
    if not good:
        print(r.stderr[-3000:])
        return False
    dets = os.path.join(a.work, "dets.txt")
    r = subprocess.run([detect, "--input", a.data, "--range", "400-401", "--picto", out, "--detections", dets,
                        "--quiet"], capture_output=True, text=True, timeout=600)
    good = r.returncode == 0 and os.path.exists(dets)
    print(f"sbr_detect with that class stage: exit {r.returncode}: {'OK' if good else 'WRONG'}")
    ok = good
    r = subprocess.run(base + ["--python", os.path.join(a.work, "no-such-python"), "--out",
                                    os.path.join(a.work, "never.sbrp")], capture_output=True, text=True, timeout=900)
    good = r.returncode == 1 and "library trainer failed" in r.stderr and not os.path.exists(
        os.path.join(a.work, "never.sbrp"))
    print(f"missing interpreter: exit {r.returncode}, named: {'OK' if good else 'WRONG'}")
    return ok and good


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--script", required=True)
    ap.add_argument("--tools")
    ap.add_argument("--data")
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    ok = check_constructed(a)
    if a.tools and a.data and os.path.isdir(os.path.join(a.data, "FullIJCNN2013")):
        ok &= check_tool(a)
    else:
        print("sbr_train_picto end to end: no GTSDB, not run")
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
