"""Viewpoints where nothing important overlaps (no matplotlib).

The cost is bounded whatever the size of the mechanism: pairs are scored
:data:`PAIR_BLOCK` at a time, and at most :data:`MAX_CONTEXT_POINTS` context
points (joints) take part; the points of the answer always do.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["view_axes", "view_scores", "thinned", "choose_views", "MAX_CONTEXT_POINTS", "PAIR_BLOCK", "MAX_VIEWS"]

MAX_CONTEXT_POINTS = 300
"""Context points (joints) scored at most; more are thinned evenly (a picture of thousands of joints
cannot keep them all apart anyway, and the pairs grow as the square of the points)."""

PAIR_BLOCK = 4096
"""Pairs of points scored at a time (bounds the memory of scoring to this many pairs times the views)."""

MAX_VIEWS = 3
"""The most views :func:`choose_views` always finds at its default separation: whatever the scores, its
grid of candidates holds at least three views 60 degrees apart from one another (a fourth may not exist)."""


def view_axes(elev: Any, azim: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Eye direction and screen x, y of orthographic views (matplotlib's elev/azim, degrees): 3-vectors, or shape (n, 3) for n views."""
    e, a = np.radians(elev), np.radians(azim)
    eye = np.stack([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)], axis=-1)
    sx = np.stack([-np.sin(a), np.cos(a), np.zeros_like(a)], axis=-1)
    return eye, sx, np.cross(eye, sx)


def view_scores(elev: np.ndarray, azim: np.ndarray, points: np.ndarray, directions: np.ndarray, size: float) -> np.ndarray:
    """Badness of each view: important points on top of each other, directions seen end-on."""
    eye, sx, sy = view_axes(elev, azim)
    bad = 0.008 * np.abs(elev - 25.0)  # a mild preference for a usual look
    if len(points) > 1:
        i, j = np.triu_indices(len(points), 1)
        d = points[i] - points[j]
        d3 = np.linalg.norm(d, axis=1)
        keep = d3 > 0.03 * size
        d, d3 = d[keep], d3[keep]
        if len(d):
            on_top, close, seen_length = (np.zeros(len(elev)) for _ in range(3))
            for start in range(0, len(d), PAIR_BLOCK):
                block, block3 = d[start : start + PAIR_BLOCK], d3[start : start + PAIR_BLOCK, None]
                d2 = np.hypot(block @ sx.T, block @ sy.T)  # (pairs, views)
                on_top += np.sum(d2 < 0.04 * size, axis=0)  # points drawn on top of each other
                close += np.sum(np.exp(-((d2 / (0.08 * size)) ** 2)) * (d2 < 0.5 * block3), axis=0)
                seen_length += np.sum(d2 / block3, axis=0)
            bad = bad + on_top + close + 6.0 * (1.0 - seen_length / len(d))  # the last: foreshortening, a flat scene seen edge-on
    if len(directions):
        seen = np.sqrt(np.maximum(0.0, 1.0 - (directions @ eye.T) ** 2))  # (directions, views)
        bad = bad + 4.0 * np.sum(seen < 0.35, axis=0) + np.sum(np.maximum(0.0, 0.6 - seen), axis=0)
    return bad


def thinned(points: np.ndarray, limit: int = MAX_CONTEXT_POINTS) -> np.ndarray:
    """At most ``limit`` of ``points`` (rows), evenly spread over them in order (all when there are no more).

    Examples
    --------
    >>> thinned(np.arange(30.0).reshape(10, 3), 4)[:, 0].tolist()
    [0.0, 9.0, 18.0, 27.0]
    """
    return points if len(points) <= limit else points[np.unique(np.linspace(0, len(points) - 1, limit).round().astype(int))]


def choose_views(points: np.ndarray, directions: np.ndarray, size: float, count: int = 2, *, separation: float = 60.0,
                 context: np.ndarray | None = None) -> list[tuple[float, float]]:
    """Viewpoints ``(elev, azim)`` in degrees where nothing important overlaps.

    Every candidate view on a grid is scored by the pairs of ``points`` within
    4 % of ``size`` of each other on the screen (softly, by pairs brought
    close), and by the unit ``directions`` (arrows, axes) seen nearly end-on. The best comes first,
    each at least ``separation`` degrees from the others.  ``context``: further points to keep apart
    (the joints), at most :data:`MAX_CONTEXT_POINTS` of them scored.

    Examples
    --------
    >>> import numpy as np
    >>> # a vertical axis must not be seen from above
    >>> elev, azim = choose_views(np.zeros((1, 3)), np.array([[0.0, 0, 1]]), 1.0, count=1)[0]
    >>> elev < 60
    True
    """
    points = thinned(np.asarray(points, dtype=float).reshape(-1, 3))
    if context is not None:
        points = np.concatenate([thinned(np.asarray(context, dtype=float).reshape(-1, 3)), points])
    directions = np.asarray(directions, dtype=float).reshape(-1, 3)
    elev, azim = (g.ravel().astype(float) for g in np.meshgrid([10, 20, 30, 40, 55, 70, 85], np.arange(0, 360, 10), indexing="ij"))
    scores = np.round(view_scores(elev, azim, points, directions, size), 9)
    eyes = view_axes(elev, azim)[0]
    chosen: list[int] = []
    cos_sep = math.cos(math.radians(separation))
    for k in np.lexsort((azim, elev, scores)):  # best first; ties to the lower view, then smaller azimuth
        if all(eyes[k] @ eyes[c] < cos_sep for c in chosen):
            chosen.append(int(k))
            if len(chosen) == count:
                break
    return [(float(elev[k]), float(azim[k])) for k in chosen]
