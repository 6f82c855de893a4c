# SPDX-License-Identifier: MIT
"""sbr: shape-based recognition of traffic signs, the C core for numpy images.

    import sbr, numpy as np
    rec = sbr.Recognizer()                      # the built-in models (GTSDB 00000-00599)
    dets = rec.detect(image_bgr)                # H x W x 3 uint8, BGR (OpenCV's order)
    dets = rec.detect(image_rgb, order="rgb")
    for d in dets:
        print(d.class_id, d.class_name, d.box, d.score)

Also: sbr.Tracker (the channel-representation tracker), sbr.ellipse_fit, sbr.fd (Fourier
descriptors and their matching), sbr.can (the DBC's messages with their E2E check),
sbr.evaluate (detections scored against GTSDB ground truth, sbr_eval's report).

The core runs on a zero-copy view of the array (each row's pixels must be contiguous; any
row stride, e.g. a crop `image[y0:y1, x0:x1]`, is accepted); the GIL is released while it
runs, so threads scale. Every bad input raises ValueError (TypeError for a non-array)
with what is wrong, from the core's own checks.
"""
from dataclasses import dataclass
from typing import List, Optional, Sequence, Tuple

import numpy as np

from . import _sbr, can, fd
from .evaluation import Evaluation, evaluate
from ._points import as_points

__all__ = ["Recognizer", "Detection", "Tracker", "Target", "SignTracker", "Sign", "Ellipse", "ellipse_fit", "class_name", "superclass",
           "SUPERCLASSES", "CONFIG_FIELDS", "CONFIG_TABLE", "TRACKER_FIELDS", "fd", "can", "evaluate", "Evaluation"]

#: GTSDB's superclasses, by superclass()'s index.
SUPERCLASSES = ("prohibitory", "mandatory", "danger", "other")
#: The configuration fields Recognizer takes as keyword arguments: the core's table
#: (docs/usage/configuration.md), in its order. Per-map-kind fields take a list of 1 to 4
#: integers (intensity, red, blue, yellow).
CONFIG_FIELDS = tuple(_sbr.field_names())
#: The same table: name -> (kind "int" or "float", values, low, high, default, meaning).
CONFIG_TABLE = dict(_sbr.field_table())


def class_name(class_id: int) -> str:
    """Name of a GTSDB class, as the DBC's value tables name it ("SpeedLimit70", "GiveWay",
    ...; "?" outside 0..42)."""
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
    point (`threshold`) unless given. strips: the strip configuration (sbr_detect --strips):
    each frame in bands of 256 rows overlapping by 128, with a band's bounds and workspace
    (1,942,760 bytes at 1360 wide); fields given still apply.
    """

    def __init__(self, config: Optional[dict] = None, model: Optional[str] = None,
                 picto: Optional[str] = None, no_picto: bool = False, strips: bool = False, **fields):
        given = dict(config or {})
        given.update(fields)
        for k, v in given.items():
            if isinstance(v, bool):
                given[k] = int(v)
        if picto is not None and no_picto:
            raise ValueError("picto and no_picto exclude each other")
        self._core = _sbr.Recognizer(given, str(model or ""), str(picto or ""), bool(no_picto), bool(strips))

    @property
    def threshold(self) -> float:
        """The operating point: detections with score >= threshold count as signs."""
        return self._core.threshold

    @property
    def config(self) -> dict:
        """The configuration fields in effect."""
        return self._core.config

    def workspace_size(self, width: int, height: int) -> int:
        """Bytes of the core's workspace for a width x height frame (or ROI; with strips, one
        band's)."""
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


#: The tracker's configuration fields (include/sbr/track.h documents each).
def _check_fields(fields: dict, allowed: Sequence[str], what: str) -> None:
    """ValueError for a keyword that is not a field of `allowed`, or a value that is not a number."""
    unknown = sorted(set(fields) - set(allowed))
    if unknown:
        raise ValueError(f"unknown {what} field: {unknown[0]} (fields: {', '.join(allowed)})")
    for k, v in fields.items():
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise ValueError(f"{k}: a number is needed, not {v!r}")


TRACKER_FIELDS = ("max_targets", "window", "meas_sigma", "gate", "confirm_hits", "max_misses")


@dataclass(frozen=True)
class Target:
    """One tracked target after a step: id (stable for its life, from 1), position x, y
    (pixels), velocity vx, vy (pixels per model period), certainty (0..1), hits, misses
    (consecutive), age (steps), detection (index of this step's detection used, or None),
    and whether it is confirmed, was updated or was born in this step."""
    id: int
    x: float
    y: float
    vx: float
    vy: float
    certainty: float
    hits: int
    misses: int
    age: int
    detection: Optional[int]
    confirmed: bool
    updated: bool
    born: bool


class Tracker:
    """The channel-representation tracker (the thesis's paper E; include/sbr/track.h).

    model: "kitti" (learned from KITTI car and cyclist tracks: 1242 x 375 images at 10 frames
    per second, window 25 unless given) or "cv" (constant velocity over a width x height
    frame, `period` seconds per frame, vel_count velocity channels vel_spacing pixels per
    period apart, the velocity changing by accel_sigma pixels per period, a new target's
    velocity prior birth_sigma). Configuration fields (TRACKER_FIELDS) as keyword arguments;
    a refused one raises ValueError naming it.
    """

    def __init__(self, model: str = "kitti", width: Optional[float] = None, height: Optional[float] = None,
                 period: float = 0.1, vel_count: int = 41, vel_spacing: float = 4.0, accel_sigma: float = 4.0,
                 birth_sigma: float = 20.0, **fields):
        if model == "cv" and (width is None or height is None):
            raise ValueError("a constant-velocity model needs width and height")
        _check_fields(fields, TRACKER_FIELDS, "tracker")
        self._core = _sbr.Tracker(str(model), float(width or 0.0), float(height or 0.0), float(period),
                                  int(vel_count), float(vel_spacing), float(accel_sigma), float(birth_sigma),
                                  dict(fields))

    @property
    def config(self) -> dict:
        """The configuration fields in effect."""
        return self._core.config

    @property
    def workspace_size(self) -> int:
        """Bytes of the core's workspace (all target densities)."""
        return self._core.workspace_size

    @property
    def period(self) -> float:
        """Seconds between the frames the motion model describes."""
        return self._core.period

    @property
    def extent(self) -> Tuple[float, float]:
        """The model's image width and height: detections must lie inside."""
        return self._core.extent

    @property
    def capacity_hit(self) -> bool:
        """The last step could not start a target for some detection (max_targets live)."""
        return self._core.capacity_hit

    def reset(self) -> None:
        """Drop every target; ids start again at 1."""
        self._core.reset()

    def step(self, detections, dt: Optional[float] = None) -> List[Target]:
        """One frame: `dt` seconds after the previous one (default: the model's period).

        detections: an N x 2 (x, y; certainty 1) or N x 3 (x, y, certainty in (0, 1]) array,
        or a list of Detection (box centres, certainty = score). Returns every live target,
        confirmed ones first.
        """
        if isinstance(detections, (list, tuple)) and detections and isinstance(detections[0], Detection):
            rows = [(d.box[0] + d.box[2] / 2.0, d.box[1] + d.box[3] / 2.0, min(1.0, max(1e-3, d.score)))
                    for d in detections]
            arr = np.asarray(rows, dtype=np.float32)
        else:
            arr = np.asarray(detections, dtype=np.float32) if len(detections) else np.zeros((0, 3), np.float32)
        if arr.ndim != 2 or arr.shape[1] not in (2, 3):
            raise ValueError(f"detections: an N x 2 or N x 3 array is needed, not shape {arr.shape}")
        if arr.shape[1] == 2:
            arr = np.concatenate([arr, np.ones((arr.shape[0], 1), np.float32)], axis=1)
        dt_s = self.period if dt is None else float(dt)
        if not (dt_s > 0.0 and dt_s * 1e6 < 2.0 ** 32):
            raise ValueError(f"dt: seconds > 0 are needed, not {dt!r}")
        out = self._core.step(np.ascontiguousarray(arr), max(1, int(round(dt_s * 1e6))))
        return [Target(i, x, y, vx, vy, c, h, m, a, None if det < 0 else det, bool(f & _sbr.TRACK_CONFIRMED),
                       bool(f & _sbr.TRACK_UPDATED), bool(f & _sbr.TRACK_BORN))
                for i, x, y, vx, vy, c, h, m, a, det, f in out]


SIGN_FIELDS = ("class_count", "max_tracks", "confirm_hits", "confirm_share", "max_misses", "meas_sigma",
               "min_certainty")


@dataclass(frozen=True)
class Sign:
    """A confirmed sign after a frame (include/sbr/signs.h): id (stable for its pass, from
    1), its class by the evidence of all its frames, its position x, y and last box size
    (pixels), its best score, its class's share of the evidence, the detections it got,
    the frames since its confirmation, and whether it was confirmed (new) or renamed in
    this frame or given a detection (seen)."""
    id: int
    class_id: int
    x: float
    y: float
    width: float
    height: float
    score: float
    share: float
    hits: int
    frames: int
    new: bool
    renamed: bool
    seen: bool

    @property
    def class_name(self) -> str:
        return class_name(self.class_id)


class SignTracker:
    """The core's sign tracking (include/sbr/signs.h), as the ECU runs it: the detections
    of consecutive frames become tracks (the channel tracker, a constant-velocity model);
    a track's class is the one with the most summed score; a sign is confirmed once per
    pass (confirm_hits detections and confirm_share of its evidence).

    width, height: the frames' size in pixels; period: seconds between frames. Fields
    (SIGN_FIELDS) as keyword arguments; a refused one raises ValueError naming it.
    """

    def __init__(self, width: float = 1360.0, height: float = 800.0, period: float = 0.1, **fields):
        _check_fields(fields, SIGN_FIELDS, "sign-tracking")
        if not (isinstance(period, (int, float)) and 0.0 < period <= 4294.0):
            raise ValueError(f"period: seconds > 0 are needed, not {period!r}")
        self._period = float(period)
        self._core = _sbr.SignTracker(dict(fields, width=float(width), height=float(height),
                                           period_us=int(round(period * 1e6))))
        self._t = None

    @property
    def config(self) -> dict:
        """The configuration in effect."""
        return self._core.config

    @property
    def workspace_size(self) -> int:
        """Bytes of the core's workspace."""
        return self._core.workspace_size

    @property
    def capacity_hit(self) -> bool:
        """The last frame had more detections or signs than the tracking holds."""
        return self._core.capacity_hit

    def reset(self) -> None:
        """Drop every track (ids go on, never reused)."""
        self._core.reset()

    def update(self, detections: Sequence[Detection], time: Optional[float] = None) -> Tuple[List[Sign], List[int]]:
        """One frame's detections at `time` seconds (default: one period after the previous
        frame). Returns the confirmed signs after the frame (by id) and, per detection, the
        id of the sign it was given to (0: none yet)."""
        t = (0.0 if self._t is None else self._t + self._period) if time is None else float(time)
        if not (t >= 0.0 and t * 1e6 < 2.0 ** 63):
            raise ValueError(f"time: seconds >= 0 are needed, not {time!r}")
        rows = [(*d.box, d.class_id, d.score) for d in detections]
        signs, det_sign = self._core.update(rows, int(round(t * 1e6)))
        self._t = t
        return ([Sign(i, c, x, y, w, h, sc, sh, hits, fr, bool(f & _sbr.SIGN_NEW), bool(f & _sbr.SIGN_RENAMED),
                      bool(f & _sbr.SIGN_SEEN)) for i, c, f, x, y, w, h, sc, sh, hits, fr in signs], list(det_sign))


@dataclass(frozen=True)
class Ellipse:
    """An ellipse: centre (cx, cy), semi-axes (semi_major >= semi_minor), angle of the major
    axis (radians, (-pi/2, pi/2], from +x towards +y); conic (a, b, c, d, e, f) of
    a x^2 + 2b xy + c y^2 + 2d x + 2e y + f = 0; rms and max_residual: the points' Sampson
    distances to it (pixels)."""
    cx: float
    cy: float
    semi_major: float
    semi_minor: float
    angle: float
    conic: Tuple[float, float, float, float, float, float]
    rms: float
    max_residual: float


def ellipse_fit(points) -> Ellipse:
    """Direct least-squares ellipse fit (Fitzgibbon, Halir-Flusser) of N >= 5 points (N x 2,
    or OpenCV's N x 1 x 2). ValueError when the points determine no ellipse (collinear,
    too few distinct, a hyperbola's) or hold non-finite values."""
    conic, (cx, cy, a, b, ang), rms, mx = _sbr.ellipse_fit(as_points(points))
    return Ellipse(cx, cy, a, b, ang, tuple(conic), rms, mx)
