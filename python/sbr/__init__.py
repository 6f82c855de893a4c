"""sbr: shape-based recognition of traffic signs, the C core for numpy images.

    import sbr, numpy as np
    rec = sbr.Recognizer()                      # the built-in models (GTSDB 00000-00599)
    dets = rec.detect(image_bgr)                # H x W x 3 uint8, BGR (OpenCV's order)
    dets = rec.detect(image_rgb, order="rgb")
    for d in dets:
        print(d.class_id, d.class_name, d.box, d.score)

The core runs on a zero-copy view of the array (each row's pixels must be contiguous; any
row stride, e.g. a crop `image[y0:y1, x0:x1]`, is accepted); the GIL is released while it
runs, so threads scale. Every bad input raises ValueError (TypeError for a non-array)
with what is wrong, from the core's own checks.
"""
from dataclasses import dataclass
from typing import List, Optional, Sequence, Tuple

import numpy as np

from . import _sbr

__all__ = ["Recognizer", "Detection", "class_name", "superclass", "SUPERCLASSES", "CONFIG_FIELDS"]

#: GTSDB's superclasses, by superclass()'s index.
SUPERCLASSES = ("prohibitory", "mandatory", "danger", "other")
#: The configuration fields Recognizer takes as keyword arguments (include/sbr/recognizer.h
#: documents each; maps, subsample and max_nodes are parts.maps, parts.subsample and
#: parts.mser.max_nodes).
CONFIG_FIELDS = tuple(sorted(_sbr.field_names()))


def class_name(class_id: int) -> str:
    """Short name of a GTSDB class ("30", "give way", ...; "?" outside 0..42)."""
    return _sbr.class_name(int(class_id))


def superclass(class_id: int) -> int:
    """0 prohibitory, 1 mandatory, 2 danger, 3 other (GTSDB's ReadMe)."""
    return _sbr.superclass(int(class_id))


@dataclass(frozen=True)
class Detection:
    """One detected sign. box = (x, y, width, height) in pixels of the whole image; score
    in 0..1; share: the class's share of the evidence; parts: prototypes that supported it."""
    class_id: int
    box: Tuple[int, int, int, int]
    score: float
    share: float
    parts: int

    @property
    def class_name(self) -> str:
        return class_name(self.class_id)

    def gtsdb_line(self, image_name: str) -> str:
        """The line sbr_detect writes: NAME;left;top;right;bottom;class_id;score."""
        x, y, w, h = self.box
        return f"{image_name};{x};{y};{x + w - 1};{y + h - 1};{self.class_id};{self.score:.4f}"


def _check_image(image) -> np.ndarray:
    if not isinstance(image, np.ndarray):
        raise TypeError(f"image: a numpy array is needed, not {type(image).__name__}")
    if image.dtype != np.uint8:
        raise ValueError(f"image: dtype uint8 is needed, not {image.dtype}")
    if image.ndim not in (2, 3) or (image.ndim == 3 and image.shape[2] not in (1, 3)):
        raise ValueError(f"image: H x W, H x W x 1 or H x W x 3 is needed, not shape {image.shape}")
    if image.size == 0:
        raise ValueError(f"image: empty (shape {image.shape})")
    channels = image.shape[2] if image.ndim == 3 else 1
    if image.ndim == 3 and channels == 1:
        image = image[:, :, 0]  # the same memory; a length-1 axis has no meaningful stride
    if image.strides[1] != channels or (image.ndim == 3 and image.strides[2] != 1) or image.strides[0] < 0:
        raise ValueError("image: each row's pixels must be contiguous (numpy.ascontiguousarray makes a copy "
                         f"that is); strides {image.strides}")
    return image


class Recognizer:
    """The recogniser with its configuration and models.

    config: a dict of configuration fields, and/or the same as keyword arguments
    (CONFIG_FIELDS; e.g. views=3, max_candidates=128); each is checked by the core and a
    refused one raises ValueError naming the field. model, picto: files written by
    sbr_train --out-model and sbr_train_picto --out (default: the built-in models);
    no_picto: without the class stage. As sbr_detect, min_score defaults to the operating
    point (`threshold`) unless given.
    """

    def __init__(self, config: Optional[dict] = None, model: Optional[str] = None,
                 picto: Optional[str] = None, no_picto: bool = False, **fields):
        given = dict(config or {})
        given.update(fields)
        for k, v in given.items():
            if isinstance(v, bool):
                given[k] = int(v)
        if picto is not None and no_picto:
            raise ValueError("picto and no_picto exclude each other")
        self._core = _sbr.Recognizer(given, str(model or ""), str(picto or ""), bool(no_picto))

    @property
    def threshold(self) -> float:
        """The operating point: detections with score >= threshold count as signs."""
        return self._core.threshold

    @property
    def config(self) -> dict:
        """The configuration fields in effect."""
        return self._core.config

    def workspace_size(self, width: int, height: int) -> int:
        """Bytes of the core's workspace for a width x height frame (or ROI)."""
        return self._core.workspace_size(int(width), int(height))

    @property
    def last_stats(self) -> dict:
        """The last detect() call's counters and per-stage times (ms, the core's clock)."""
        return self._core.stats

    def detect(self, image: np.ndarray, roi: Optional[Sequence[int]] = None,
               order: str = "bgr") -> List[Detection]:
        """Signs in an image, highest score first, down to the configuration's min_score.

        image: H x W x 3 uint8 (order "bgr", OpenCV's, or "rgb"), or H x W / H x W x 1 grey.
        roi: (x, y, width, height): run on that region only; boxes stay in image pixels.
        """
        if order not in ("bgr", "rgb"):
            raise ValueError(f"order: 'bgr' or 'rgb', not {order!r}")
        img = _check_image(image)
        out = self._core.detect(img, order == "bgr", None if roi is None else tuple(int(v) for v in roi))
        return [Detection(c, (x, y, w, h), s, sh, p) for c, x, y, w, h, s, sh, p in out]
