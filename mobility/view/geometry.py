"""Shapes of the 3D view as plain arrays: arrowheads, arcs, helices, plates.

Each shape is a polyline in the global frame (pieces separated by a row of NaN)
or a triangle :class:`Mesh`, built with the pictures' helpers
(:mod:`mobility.report.plotting.geometry`), so that the view and the PNG draw alike.

Examples
--------
>>> import numpy as np
>>> head = cone(np.array([0.0, 0, 1]), np.array([0.0, 0, 1]), 0.2, 0.05)
>>> head.vertices[0].tolist(), head.vertices.shape, head.faces.shape
([0.0, 0.0, 1.0], (14, 3), (24, 3))
>>> pieces(np.zeros((2, 3)), np.ones((2, 3))).shape   # two segments, one NaN row between
(5, 3)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.frozen import ReadOnlyArrays
from ..report.plotting.geometry import FLAT, arc, helix, perpendiculars, plate_ring

__all__ = ["Mesh", "cone", "pieces", "arc", "helix", "plate", "fan"]


@dataclass(frozen=True, eq=False)
class Mesh(ReadOnlyArrays):
    """Triangles: ``vertices`` (n, 3) and ``faces`` (m, 3), indices into the vertices."""

    vertices: np.ndarray
    faces: np.ndarray

    @staticmethod
    def merged(*meshes: "Mesh") -> "Mesh":
        """One mesh holding all of ``meshes``."""
        offsets = np.cumsum([0] + [len(m.vertices) for m in meshes])
        faces = np.concatenate([m.faces + k for m, k in zip(meshes, offsets)])
        return Mesh(np.concatenate([m.vertices for m in meshes]).reshape(-1, 3), faces.reshape(-1, 3).astype(int))


def cone(tip: np.ndarray, direction: np.ndarray, length: float, radius: float, sides: int = 12) -> Mesh:
    """A closed cone (an arrowhead) with its tip at ``tip``, pointing along ``direction``.

    Vertex 0 is the tip, then the ring of the base, then the centre of the base.
    """
    d = np.asarray(direction, dtype=float)
    d = d / np.linalg.norm(d)
    e1, e2 = perpendiculars(d)
    base = tip - length * d
    t = np.linspace(0.0, 2.0 * math.pi, sides, endpoint=False)
    ring = base + radius * (np.cos(t)[:, None] * e1 + np.sin(t)[:, None] * e2)
    vertices = np.vstack([tip, ring, base])
    k = np.arange(sides)
    side = np.stack([np.zeros(sides, dtype=int), 1 + k, 1 + (k + 1) % sides], axis=1)
    bottom = np.stack([np.full(sides, sides + 1), 1 + (k + 1) % sides, 1 + k], axis=1)
    return Mesh(vertices, np.vstack([side, bottom]))


def pieces(*polylines: np.ndarray) -> np.ndarray:
    """Polylines joined into one array, a row of NaN between two (a break in the drawn line)."""
    gap = np.full((1, 3), np.nan)
    joined = [piece for p in polylines for piece in (gap, np.asarray(p, dtype=float).reshape(-1, 3))][1:]
    return np.concatenate(joined) if joined else np.zeros((0, 3))


def plate(points: np.ndarray, *, flatness: float = FLAT) -> Mesh | None:
    """A flat convex plate over ``points`` (a fan of triangles over their convex hull in their plane).

    ``None`` when the points are not nearly coplanar (third singular value
    above ``flatness`` times the first) or are nearly collinear: such a link is
    better drawn as bars.

    Examples
    --------
    >>> square = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 0]])
    >>> p = plate(square)
    >>> len(p.vertices), len(p.faces)   # the hull's four corners, two triangles
    (4, 2)
    >>> plate(np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]])) is None
    True
    """
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    order = plate_ring(p, flatness=flatness)
    return None if order is None else fan(p[order])


def fan(ring: np.ndarray) -> Mesh:
    """Triangles fanning out from the first point of ``ring``, a convex polygon in order round it."""
    n = len(ring)
    return Mesh(ring, np.stack([np.zeros(n - 2, dtype=int), np.arange(1, n - 1), np.arange(2, n)], axis=1))
