# SPDX-License-Identifier: MIT
"""Scoring detections against GTSDB ground truth: sbr_eval's report, from the package.

    import sbr
    ev = sbr.evaluate("detections_all.txt", "gt.txt", images=range(400, 600), threshold=0.7,
                      plot="pr_curve.png")
    print(ev.text)          # the report sbr_eval prints, byte for byte
    ev.figures["eval"]["class_level"]["f1"]

The files are GTSDB's format (NNNNN.ext;left;top;right;bottom;class_id[;score]). The
scoring is the project's C++ evaluation (the same code as the sbr_eval tool): greedy
matching by score at IoU >= iou, per superclass, per class (with the DBC's class names)
and class-agnostic, AP, the most frequent errors, and with `baseline` the comparison with
an earlier version's detections of the same images. `plot` draws the precision-recall
curves as a PNG (Pillow, the 'regress' or 'notebook' extra).
"""
import json
from dataclasses import dataclass
from typing import Iterable, Optional

from . import _sbr

SUPERCLASSES = ("prohibitory", "mandatory", "danger", "other")
# the superclasses' colours of the pictures (host_tools/common/annotate.cpp), RGB
_COLOURS = ((220, 40, 40), (20, 90, 220), (230, 160, 20), (60, 160, 60))


@dataclass(frozen=True)
class Evaluation:
    """An evaluation: the report's text, its figures (sbr_eval --json's object), and with a
    baseline the largest drop and whether it passed max_drop."""
    text: str
    figures: dict
    worst_drop: float
    regression: bool


def evaluate(detections: str, gt: str, *, images: Optional[Iterable[int]] = None, iou: float = 0.5,
             threshold: float = 0.0, baseline: Optional[str] = None, plot: Optional[str] = None,
             confusion: int = 10, list_lines: int = 20, max_drop: Optional[float] = None) -> Evaluation:
    """Scores `detections` against `gt` over `images` (image numbers; None: every image
    named in either file). Raises ValueError naming the file (and line) it cannot read."""
    for name, v in (("iou", iou), ("threshold", threshold)):
        if not 0.0 <= v <= 1.0:
            raise ValueError(f"{name} {v}: must be in 0 .. 1")
    if max_drop is not None and not 0.0 <= max_drop <= 1.0:
        raise ValueError(f"max_drop {max_drop}: must be in 0 .. 1")
    r = _sbr.evaluate(str(detections), str(gt), str(baseline) if baseline else "",
                      sorted(set(int(i) for i in images)) if images is not None else [], float(iou),
                      float(threshold), int(confusion), int(list_lines), -1.0 if max_drop is None else float(max_drop),
                      str(plot) if plot else "")
    if plot:
        draw_pr(plot, r, images_title(images))
    return Evaluation(text=r["text"], figures=json.loads(r["json"]), worst_drop=r["worst_drop"],
                      regression=r["regression"])


def images_title(images) -> str:
    """The plot's title: the images scored ("400-599 (200 images)", "3 images from 400 to
    410", or every image named in the files)."""
    nums = sorted(set(int(i) for i in images)) if images is not None else []
    if not nums:
        return "precision-recall, images: every image named in the files"
    span = f"{nums[0]:05d}-{nums[-1]:05d}"
    if len(nums) == nums[-1] - nums[0] + 1:
        return f"precision-recall, images {span} ({len(nums)} images)"
    return f"precision-recall, {len(nums)} images from {span}"


def draw_pr(path: str, r: dict, title: str = "") -> None:
    """The precision-recall plot of sbr_eval: per superclass the curve down to the operating
    point (thick), on to the lowest score (thin), the operating point as a large dot. The
    axes zoom to the data (from the lowest recall or precision of a curve, rounded down to
    0.05, to just above 1), the range stated; the title names the images."""
    from PIL import Image, ImageDraw
    W, H, x0, y0, pw, ph = 760, 660, 60, 50, 660, 440
    plo, rlo = 1.0, 1.0
    for s in range(4):
        if r["n_gt"][s] == 0:
            continue
        for rc, p in r["curve_all"][s]:
            rlo, plo = min(rlo, rc), min(plo, p)
        rlo, plo = min(rlo, r["op_recall"][s]), min(plo, r["op_precision"][s])
    plo = min(0.95, int(max(0.0, plo - 0.02) * 20.0) / 20.0)
    rlo = min(0.95, int(max(0.0, rlo - 0.02) * 20.0) / 20.0)
    pmax, rmax = 1.0 + 0.04 * (1.0 - plo), 1.0 + 0.02 * (1.0 - rlo)
    step_p = 0.1 if 1.0 - plo > 0.5 else 0.05
    step_r = 0.1 if 1.0 - rlo > 0.5 else 0.05

    def px(rec, prec):
        return (x0 + round((rec - rlo) / (rmax - rlo) * pw), y0 + ph - round((prec - plo) / (pmax - plo) * ph))

    img = Image.new("RGB", (W, H), "white")
    d = ImageDraw.Draw(img)
    k = 0
    while rlo + k * step_r <= 1.0 + 1e-9:
        v = rlo + k * step_r
        gx, _ = px(v, plo)
        d.line([(gx, y0), (gx, y0 + ph)], fill=(225, 225, 225))
        d.text((gx - 10, y0 + ph + 6), f"{v:.2f}", fill="black")
        k += 1
    k = 0
    while plo + k * step_p <= 1.0 + 1e-9:
        v = plo + k * step_p
        _, gy = px(rlo, v)
        d.line([(x0, gy), (x0 + pw, gy)], fill=(225, 225, 225))
        d.text((x0 - 34, gy - 6), f"{v:.2f}", fill="black")
        k += 1
    d.rectangle([x0, y0, x0 + pw, y0 + ph], outline="black")
    d.text((5, 6), title or images_title(None), fill="black")
    d.text((x0 + pw // 2 - 50, y0 + ph + 24), f"recall (axis {rlo:.2f}-1)", fill="black")
    d.text((5, y0 - 18), f"precision (axis {plo:.2f}-1)", fill="black")
    for s, name in enumerate(SUPERCLASSES):
        c = _COLOURS[s]
        for curve, width in ((r["curve_all"][s], 1), (r["curve_op"][s], 3)):
            if len(curve) > 1:
                d.line([px(*p) for p in curve], fill=c, width=width)
        if r["n_gt"][s] > 0:
            cx, cy = px(r["op_recall"][s], r["op_precision"][s])
            d.ellipse([cx - 7, cy - 7, cx + 7, cy + 7], fill=c)
        ly = y0 + ph + 50 + 20 * s
        d.ellipse([x0 + 4, ly, x0 + 14, ly + 10], fill=c)
        d.text((x0 + 22, ly), f"{name}: AP {r['ap'][s]:.3f}, operating point precision {r['op_precision'][s]:.3f} "
                              f"recall {r['op_recall'][s]:.3f}", fill=c)
    d.text((x0 + 10, H - 18), "thick: down to the operating point (large dot); thin: lower scores", fill=(90, 90, 90))
    img.save(path)
