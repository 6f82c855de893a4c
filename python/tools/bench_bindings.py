# SPDX-License-Identifier: MIT
"""The binding's per-call overhead against the C call (not a test: prints figures).

    python python/tools/bench_bindings.py --data ../shared/data/gtsdb [--range 400-419] [--repeat 3]

For each image, the fastest of --repeat calls of Recognizer.detect() (wall clock around
the Python call) and, for that call, the core's own time (the sum of its stage clock,
sbr_recog_detect from its first stage to its last); overhead = (Python - core) / Python,
summed over the images. Decoding is outside both.
"""
import argparse
import os
import time

import numpy as np
from PIL import Image

import sbr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", required=True)
    ap.add_argument("--range", default="400-419")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    d = os.path.join(a.data, "FullIJCNN2013") if os.path.isdir(os.path.join(a.data, "FullIJCNN2013")) else a.data
    lo, hi = (int(x) for x in a.range.split("-"))
    rec = sbr.Recognizer()
    py_total = core_total = 0.0
    for n in range(lo, hi + 1):
        img = np.asarray(Image.open(os.path.join(d, f"{n:05d}.jpg")).convert("RGB"))
        best = None
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            rec.detect(img, order="rgb")
            py = (time.perf_counter() - t0) * 1000.0
            core = sum(rec.last_stats["stage_ms"].values())
            if best is None or py < best[0]:
                best = (py, core)
        py_total += best[0]
        core_total += best[1]
    k = hi - lo + 1
    print(f"images={k} python_ms_per_call={py_total / k:.2f} core_ms_per_call={core_total / k:.2f} "
          f"overhead_pct={(py_total - core_total) / py_total * 100.0:.2f}")


if __name__ == "__main__":
    main()
