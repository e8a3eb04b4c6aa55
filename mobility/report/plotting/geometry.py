"""Small vector helpers of the drawings (no matplotlib).

Examples
--------
>>> import numpy as np
>>> e1, e2 = perpendiculars(np.array([0.0, 0, 2]))
>>> float(e1 @ e2), float(e1 @ [0, 0, 1])
(0.0, 0.0)
>>> unique_points(np.array([[0.0, 0, 0], [1e-9, 0, 0], [1, 0, 0]]), 1e-6).shape
(2, 3)
"""

from __future__ import annotations

import numpy as np

__all__ = ["SAME_POINT", "perpendiculars", "unique_points", "segment_samples"]

SAME_POINT = 1e-6
"""Points closer than this fraction of the scene are drawn as one: a drawing
resolution (a millionth of the picture), not a tolerance of the analysis."""


def perpendiculars(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors completing ``d`` to a right-handed orthonormal frame ``(d, e1, e2)``."""
    d = d / np.linalg.norm(d)
    e1 = np.cross(d, np.eye(3)[int(np.argmin(np.abs(d)))])
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(d, e1)


def unique_points(p: np.ndarray, eps: float) -> np.ndarray:
    """The points of ``p`` (rows) with those within ``eps`` of an earlier one left out."""
    out: list[np.ndarray] = []
    for x in p:
        if all(np.linalg.norm(x - y) > eps for y in out):
            out.append(x)
    return np.array(out).reshape(-1, 3)


def segment_samples(start: np.ndarray, end: np.ndarray, n: int = 7) -> np.ndarray:
    """``n`` points evenly along the segment, both ends included."""
    return start + np.linspace(0.0, 1.0, n)[:, None] * (end - start)
