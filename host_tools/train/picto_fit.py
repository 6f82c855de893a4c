#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""sbr_train_picto's library trainer (--trainer sklearn): the class stage's network fitted
by scikit-learn instead of the hand-written trainer of picto_net.cpp.

    picto_fit.py --samples FILE --out FILE [--hidden 128] [--epochs 20] [--seed 1]
                 [--lr 0.001] [--alpha 0.1] [--batch 256] [--bg-fraction 0.3]
                 [--box-alpha 1.0] [--threads 2]

Reads the standardised training samples sbr_train_picto writes (format below), fits

- the classifier, one layer of rectified units and a softmax over the classes and
  "no sign" (sklearn.neural_network.MLPClassifier, Adam): each epoch one partial_fit over
  every sign sample, every hard sample and a fresh `bg_fraction` of the background
  samples, weighted up to match, as picto_net.cpp's epochs are;
- the box outputs, a ridge regression (sklearn.linear_model.Ridge) of the box targets
  on the classifier's hidden units, so that the recogniser's refinement reuses the
  hidden units the classifier computed (sbr_picto_look_refine);

and writes the weights in picto_net.cpp's training layout for sbr_train_picto to fold
the standardisation into and check with the core. Deterministic: fixed seed, and the
BLAS thread count fixed by --threads (threadpoolctl).

Samples file (little-endian): 8 bytes "SBRSMP01"; int32 n, F, K, R; float32 X[n][F];
int32 label[n] (0..K-1, -1: box regression only); float32 weight[n]; uint8 has_box[n];
uint8 hard[n]; float32 target[n][R] (already in training units).
Weights file: 8 bytes "SBRNET01"; int32 h, F, K, R; float32 w1[h][F+1], w2[K][h+1],
w3[R][h+1] (each row its weights, then its bias).
"""
import argparse
import struct
import sys
import time

import numpy as np
from sklearn.linear_model import Ridge
from sklearn.neural_network import MLPClassifier
from threadpoolctl import threadpool_limits

SAMPLES_MAGIC = b"SBRSMP01"
WEIGHTS_MAGIC = b"SBRNET01"


def read_samples(path):
    with open(path, "rb") as f:
        if f.read(8) != SAMPLES_MAGIC:
            raise ValueError(f"{path}: not a samples file")
        n, nf, nk, nr = struct.unpack("<4i", f.read(16))
        if n <= 0 or nf <= 0 or nk <= 1 or nr < 0:
            raise ValueError(f"{path}: bad header {n} {nf} {nk} {nr}")
        x = np.fromfile(f, dtype="<f4", count=n * nf).reshape(n, nf)
        label = np.fromfile(f, dtype="<i4", count=n)
        weight = np.fromfile(f, dtype="<f4", count=n)
        has_box = np.fromfile(f, dtype="u1", count=n).astype(bool)
        hard = np.fromfile(f, dtype="u1", count=n).astype(bool)
        target = np.fromfile(f, dtype="<f4", count=n * nr).reshape(n, nr)
        if target.size != n * nr or f.read(1):
            raise ValueError(f"{path}: size does not match its header")
    return x, label, weight, has_box, hard, target, nk


def fit_classifier(a, x, label, weight, hard, nk):
    """The MLP over the labelled samples; background (label nk-1, not hard) sampled per epoch."""
    rng = np.random.default_rng(a.seed)
    labelled = label >= 0
    bg = np.flatnonzero(labelled & (label == nk - 1) & ~hard)
    fg = np.flatnonzero(labelled & ~((label == nk - 1) & ~hard))
    w = weight.astype(np.float64)
    w[bg] /= a.bg_fraction
    take = int(len(bg) * a.bg_fraction)
    clf = MLPClassifier(hidden_layer_sizes=(a.hidden,), activation="relu", solver="adam", alpha=a.alpha,
                        batch_size=a.batch, learning_rate_init=a.lr, shuffle=True, random_state=a.seed)
    classes = np.arange(nk)
    t0 = time.time()
    for e in range(a.epochs):
        idx = np.concatenate([fg, rng.permutation(bg)[:take]])
        idx.sort()
        clf.partial_fit(x[idx], label[idx], sample_weight=w[idx], classes=classes)
        if e % 5 == 4 or e + 1 == a.epochs:
            print(f"picto_fit: epoch {e + 1} loss {clf.loss_:.4f} ({time.time() - t0:.1f} s)", file=sys.stderr)
    return clf


def hidden_units(clf, x):
    return np.maximum(x @ clf.coefs_[0] + clf.intercepts_[0], 0.0)


def fit_box(a, clf, x, has_box, target):
    """Ridge regression of the box targets on the hidden units: (R, h+1) rows."""
    nr = target.shape[1]
    h = clf.coefs_[0].shape[1]
    if nr == 0 or not has_box.any():
        return np.zeros((nr, h + 1), dtype=np.float32)
    hid = hidden_units(clf, x[has_box])
    reg = Ridge(alpha=a.box_alpha).fit(hid, target[has_box])
    return np.hstack([reg.coef_, reg.intercept_[:, None]]).astype(np.float32)


def write_weights(path, clf, w3, nk):
    w1 = np.hstack([clf.coefs_[0].T, clf.intercepts_[0][:, None]]).astype(np.float32)
    w2 = np.hstack([clf.coefs_[1].T, clf.intercepts_[1][:, None]]).astype(np.float32)
    if w2.shape[0] != nk:
        raise ValueError(f"classifier has {w2.shape[0]} outputs, expected {nk}")
    h, nf = w1.shape[0], w1.shape[1] - 1
    with open(path, "wb") as f:
        f.write(WEIGHTS_MAGIC)
        f.write(struct.pack("<4i", h, nf, nk, w3.shape[0]))
        for m in (w1, w2, w3):
            f.write(np.ascontiguousarray(m, dtype="<f4").tobytes())


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--samples", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--hidden", type=int, default=128)
    p.add_argument("--epochs", type=int, default=20)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--lr", type=float, default=0.001, help="Adam's learning rate")
    # the best of the configurations measured on the cross-validation (docs/results/crossval.md)
    p.add_argument("--alpha", type=float, default=0.1, help="L2 penalty (sklearn's alpha)")
    p.add_argument("--batch", type=int, default=256)
    p.add_argument("--bg-fraction", type=float, default=0.3)
    p.add_argument("--box-alpha", type=float, default=1.0, help="ridge penalty of the box outputs")
    p.add_argument("--threads", type=int, default=2)
    a = p.parse_args(argv)
    if a.hidden < 1 or a.epochs < 1 or a.batch < 1 or not 0.0 < a.bg_fraction <= 1.0:
        p.error("--hidden, --epochs, --batch >= 1 and 0 < --bg-fraction <= 1")
    with threadpool_limits(limits=a.threads):
        x, label, weight, has_box, hard, target, nk = read_samples(a.samples)
        clf = fit_classifier(a, x, label, weight, hard, nk)
        w3 = fit_box(a, clf, x, has_box, target)
    write_weights(a.out, clf, w3, nk)
    return 0


if __name__ == "__main__":
    sys.exit(main())
