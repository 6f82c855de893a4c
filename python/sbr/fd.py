# SPDX-License-Identifier: MIT
"""sbr.fd: Fourier descriptors of closed contours and their correlation matching (the
thesis's papers C and D; include/sbr/fd.h documents the maths).

    from sbr import fd
    a = fd.descriptor(contour_a)            # N x 2 points (or OpenCV's N x 1 x 2)
    b = fd.descriptor(contour_b)
    m = fd.match(a, b)                      # error 0 (same shape) .. 4, rotation, shift
    results, best = fd.match_table(a, [b, b.mirror()])

A descriptor is invariant to translation and scale (kept aside: `centroid`, `scale`) and
to the contour's start point; matching is rotation covariant by default (a 6 is not a 9)
or invariant (`mode="invariant"`). Bad input raises ValueError with the core's status.
"""
import math
from dataclasses import dataclass
from typing import List, Sequence, Tuple

import numpy as np

from . import _sbr
from ._points import as_points

__all__ = ["Descriptor", "Match", "descriptor", "from_coefficients", "match", "match_table", "MAX_M"]

#: A descriptor (the core's sbr_fd_t): m, scale, centroid, coefficients (C(-M)..C(M),
#: complex64, C(0) = 0), mirror() (the mirror image's descriptor), smooth(sigma).
Descriptor = _sbr.FD
#: Largest M.
MAX_M = int(_sbr.FD_MAX_M)


@dataclass(frozen=True)
class Match:
    """One correlation: error = 2 - 2 max (0 .. 4); rotation of the query relative to the
    prototype (radians, (-pi, pi]); shift of the start point (fraction of the length,
    [0, 1)); scale_ratio = query scale / prototype scale."""
    error: float
    rotation: float
    shift: float
    scale_ratio: float


def descriptor(points, m: int = 12, samples: int = 128) -> Descriptor:
    """Descriptor of a closed contour (the last point connects to the first), resampled at
    `samples` points (a power of two, 16 .. 1024, > 2m) equally spaced in arc length, M =
    `m` coefficients on each side (the recogniser's defaults: 12 and 128)."""
    return _sbr.fd_descriptor(as_points(points), int(m), int(samples))


def from_coefficients(coefficients, scale: float = 1.0, centroid: Tuple[float, float] = (0.0, 0.0)) -> Descriptor:
    """A descriptor from stored values (2M + 1 complex coefficients C(-M)..C(M)), checked as
    the matcher checks it (finite, positive scale)."""
    c = np.ascontiguousarray(np.asarray(coefficients), dtype=np.complex64)
    if c.ndim != 1:
        raise ValueError(f"coefficients: a 1-D array is needed, not shape {c.shape}")
    return _sbr.fd_from_coefficients(c, float(scale), float(centroid[0]), float(centroid[1]))


def _lags(m: int, lags) -> int:
    if lags is not None:
        return int(lags)
    p = 32  # the recogniser's match_p
    while p < 2 * m + 1:
        p *= 2
    return p


def match_table(query: Descriptor, prototypes: Sequence[Descriptor], mode: str = "covariant",
                max_rotation: float = math.pi, refine: bool = True, max_error: float = 0.0,
                lags=None) -> Tuple[List[Match], int]:
    """Correlate `query` with every prototype (same M): the matches in table order and the
    index of the best (smallest error). mode: "covariant" (rotation costs; only peaks with
    |rotation| <= max_rotation count) or "invariant". max_error > 0 screens prototypes that
    certainly match worse (they get error 4) without changing any match up to it. lags:
    the correlation's length P (power of two >= 2M + 1; default the smallest of 32, 64, ...
    that holds it)."""
    if mode not in ("covariant", "invariant"):
        raise ValueError(f"mode: 'covariant' or 'invariant', not {mode!r}")
    if not isinstance(query, Descriptor):
        raise TypeError(f"query: a descriptor is needed, not {type(query).__name__}")
    protos = list(prototypes)
    for p in protos:
        if not isinstance(p, Descriptor):
            raise TypeError(f"prototypes: descriptors are needed, not {type(p).__name__}")
    e, r, s, k, best = _sbr.fd_match(query, protos, 1 if mode == "covariant" else 0, float(max_rotation),
                                     bool(refine), float(max_error), _lags(query.m, lags))
    return [Match(*v) for v in zip(e, r, s, k)], int(best)


def match(query: Descriptor, prototype: Descriptor, **options) -> Match:
    """Correlate `query` with one prototype (options as match_table())."""
    results, _ = match_table(query, [prototype], **options)
    return results[0]
