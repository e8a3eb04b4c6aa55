"""Small vector helpers of the drawings (no matplotlib).

Examples
--------
>>> import numpy as np
>>> e1, e2 = perpendiculars(np.array([0.0, 0, 2]))
>>> float(e1 @ e2), float(e1 @ [0, 0, 1])
(0.0, 0.0)
>>> bool(np.array_equal(perpendiculars(np.array([1e-16, 0, 1]))[0], perpendiculars(np.array([0.0, 0, 1]))[0]))
True
>>> unique_points(np.array([[0.0, 0, 0], [1e-9, 0, 0], [1, 0, 0]]), 1e-6).shape
(2, 3)
>>> unique_points(np.repeat(np.eye(3), 10, axis=0) + 1e-9, 1e-6).shape   # the k-d tree route
(3, 3)
"""

from __future__ import annotations

import math
from typing import cast

import numpy as np

__all__ = ["SAME_POINT", "FLAT", "perpendiculars", "unique_points", "segment_samples", "arc", "helix", "plate_ring"]

SAME_POINT = 1e-6
"""Points closer than this fraction of the scene are drawn as one: a drawing
resolution (a millionth of the picture), not a tolerance of the analysis."""


def perpendiculars(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors completing ``d`` to a right-handed orthonormal frame ``(d, e1, e2)``.

    The axis ``d`` is crossed with is chosen on its components rounded to a
    millionth (:data:`SAME_POINT`), so round-off in ``d`` does not turn the frame.
    """
    d = np.asarray(d, dtype=float)
    d = d / np.linalg.norm(d)
    e1 = np.cross(d, np.eye(3)[int(np.argmin(np.round(np.abs(d), 6)))])
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(d, e1)


def unique_points(p: np.ndarray, eps: float) -> np.ndarray:
    """The points of ``p`` (rows) with those within ``eps`` of an earlier one left out.

    Beyond a few points the neighbours are found with a k-d tree (thousands of joints take milliseconds).
    """
    p = np.asarray(p, dtype=float).reshape(-1, 3)
    if len(p) <= _FEW:
        out: list[np.ndarray] = []
        for x in p:
            if all(np.linalg.norm(x - y) > eps for y in out):
                out.append(x)
        return np.array(out).reshape(-1, 3)
    from scipy.spatial import cKDTree

    near = cast(np.ndarray, cKDTree(p).query_ball_point(p, eps * (1.0 + 1e-9), p=2.0))  # a hair wider; the exact test follows; rows in: an array of lists out
    dropped = np.zeros(len(p), dtype=bool)
    for i in range(len(p)):
        if not dropped[i]:
            dropped[[k for k in near[i] if k > i and np.linalg.norm(p[k] - p[i]) <= eps]] = True
    return p[~dropped]


_FEW = 16
"""Up to this many points, :func:`unique_points` compares every pair directly."""


def segment_samples(start: np.ndarray, end: np.ndarray, n: int = 7) -> np.ndarray:
    """``n`` points evenly along the segment, both ends included (so that a hover finds the line anywhere along it)."""
    start = np.asarray(start, dtype=float)
    return start + np.linspace(0.0, 1.0, n)[:, None] * (np.asarray(end, dtype=float) - start)


def arc(centre: np.ndarray, axis: np.ndarray, radius: float, turn: float = 1.5 * math.pi, samples: int = 33) -> tuple[np.ndarray, np.ndarray]:
    """A circular arc about ``axis`` at ``centre`` in the right-hand sense; returns (points, unit tangent at the end)."""
    e1, e2 = perpendiculars(axis)
    t = np.linspace(0.0, turn, samples)
    points = centre + radius * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2)
    return points, -math.sin(turn) * e1 + math.cos(turn) * e2


FLAT = 0.05
"""Points whose third singular value (about their centroid) is at most this
fraction of the first lie nearly in a plane, and are drawn as a plate over
them when their second is above it (not nearly on a line): a drawing choice."""


def helix(centre: np.ndarray, axis: np.ndarray, radius: float, length: float, turns: float = 2.0, samples: int = 61) -> np.ndarray:
    """A right-handed helix of ``turns`` turns about ``axis``, ``length`` long, centred at ``centre`` (``samples`` points).

    Examples
    --------
    >>> h = helix(np.zeros(3), np.array([0.0, 0, 2]), 1.0, 4.0)
    >>> h.shape, h[0].round(12).tolist(), h[-1].round(12).tolist()
    ((61, 3), [0.0, 1.0, -2.0], [0.0, 1.0, 2.0])
    """
    e1, e2 = perpendiculars(axis)
    d = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    t = np.linspace(0.0, 2.0 * math.pi * turns, samples)
    s = np.linspace(-0.5, 0.5, samples) * length
    return centre + radius * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2) + s[:, None] * d


def plate_ring(points: np.ndarray, *, flatness: float = FLAT) -> list[int] | None:
    """The indices of ``points`` on their convex outline, in order round it, when they make a plate.

    ``None`` when the points are not nearly coplanar or are nearly collinear
    (singular values against ``flatness``). The ring starts at the lowest index,
    towards its lower-numbered neighbour.

    Examples
    --------
    >>> square = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 0]])
    >>> plate_ring(square), plate_ring(square[:3] * [1, 0, 0])
    ([0, 1, 2, 3], None)
    """
    from scipy.spatial import ConvexHull, QhullError

    p = np.asarray(points, dtype=float).reshape(-1, 3)
    if len(p) < 3:
        return None
    c = p.mean(axis=0)
    _, sv, vt = np.linalg.svd(p - c)
    if sv[1] <= flatness * sv[0] or (len(sv) > 2 and sv[2] > flatness * sv[0]):
        return None
    try:
        hull = ConvexHull((p - c) @ vt[:2].T)
    except QhullError:  # pragma: no cover - collinear after all
        return None
    order = [int(k) for k in hull.vertices]
    order = order[order.index(min(order)):] + order[: order.index(min(order))]
    if len(order) > 2 and order[1] > order[-1]:
        order = order[:1] + order[:0:-1]
    return order
