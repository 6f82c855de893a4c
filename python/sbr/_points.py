# SPDX-License-Identifier: MIT
"""Point arrays for the core: N x 2 float32, C-contiguous (a copy when needed)."""
import numpy as np


def as_points(points, what: str = "points") -> np.ndarray:
    """N x 2 (or OpenCV's N x 1 x 2) real coordinates as a float32 N x 2 array; ValueError
    otherwise. Non-finite values pass through: the core refuses them with its status."""
    a = np.asarray(points)
    if a.dtype.kind not in "iuf":
        raise ValueError(f"{what}: real coordinates are needed, not dtype {a.dtype}")
    if a.ndim == 3 and a.shape[1] == 1:
        a = a[:, 0, :]  # OpenCV's contour layout
    if a.ndim != 2 or a.shape[1] != 2:
        raise ValueError(f"{what}: an N x 2 array (x, y) is needed, not shape {a.shape}")
    return np.ascontiguousarray(a, dtype=np.float32)
