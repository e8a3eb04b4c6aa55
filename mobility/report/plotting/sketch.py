"""Where each joint is drawn, and the size of the scene (no matplotlib).

A picture is drawn in *drawing units*: the file's lengths times :attr:`Sketch.scale` (:func:`drawing_scale`).

Examples
--------
>>> import mobility
>>> m = mobility.loads('''
... name: R-P arm
... ground: g
... end_effector: hand
... joints:
...   - {name: R1, type: R, links: [g, arm], axis: [0, 0, 1], point: [0, 0, 0]}
...   - {name: P1, type: P, links: [arm, hand], axis: [1, 0, 0]}
...   - {name: R2, type: R, links: [hand, tool], axis: [1, 0, 0], point: [2, 0, 0]}
... ''')
>>> s = sketch(m)
>>> s.points[s.names.index("P1")].tolist()   # midway between R1 and R2
[1.0, 0.0, 0.0]
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...core.frozen import ReadOnlyArrays
from ...core.joint_screws import joint_screws
from ...core.model import Mechanism
from ...core.tolerance import DEFAULT_TOLERANCE, binary_scale
from ...errors import MechanismFileError, clipped

__all__ = ["Sketch", "sketch", "drawing_scale", "PLAIN_SIZES"]

PLAIN_SIZES = (2.0**-20, 2.0**20)
"""Sizes of a mechanism drawn in its file's own numbers (drawing scale 1): about 1e-6 to 1e6."""


def drawing_scale(length: float) -> float:
    """The power of two that lengths are multiplied by in a picture of a mechanism of size ``length``.

    1 within :data:`PLAIN_SIZES`, else the power of two bringing ``length`` near 1
    (:func:`~mobility.core.tolerance.binary_scale`): a drawing library squares
    coordinates, which would overflow at 1e200 and underflow at 1e-250.

    Examples
    --------
    >>> drawing_scale(250.0), drawing_scale(1e-3)
    (1.0, 1.0)
    >>> [0.5 <= drawing_scale(x) * x < 1.0 for x in (1e200, 1e-250)]
    [True, True]
    """
    return 1.0 if PLAIN_SIZES[0] <= length <= PLAIN_SIZES[1] else binary_scale(length)

DRAWING_REACH = 1e150
"""Farthest from the origin a joint is drawn, in drawing units (the mechanism's size about 1): a drawing library
squares coordinates, which stays finite up to the square root of the largest float; no picture resolves a joint farther out."""


def _require_drawable(mechanism: Mechanism, joints: tuple, pts: np.ndarray, located: np.ndarray, length: float) -> None:
    """Refuse to draw a mechanism whose located joints lie beyond :data:`DRAWING_REACH` (or past the largest float)."""
    with np.errstate(over="ignore", invalid="ignore"):
        reach = np.where(located, np.max(np.abs(pts), axis=1), 0.0)
    far = np.flatnonzero(~(reach <= DRAWING_REACH))
    if far.size == 0:
        return
    i = int(far[0])
    joint = joints[i]
    point = max(abs(float(x)) for x in joint.point)
    unit = f" {mechanism.length_unit}" if mechanism.length_unit else ""
    key, line = mechanism.joint_key(i, "point")
    raise MechanismFileError(
        f"{key} (joint {clipped(joint.name)})",
        f"its point lies {point:.3g}{unit} from the origin, {point / length if length > 0 else math.inf:.3g} times the mechanism's size: too far out to draw; "
        f"expected joints within {DRAWING_REACH:.0e} sizes of the origin for a picture or a view (move the file's origin near the mechanism; the analysis itself is unaffected)",
        file=mechanism.source or "<string>", line=line)


ROUND_OFF = DEFAULT_TOLERANCE.round_off
"""Lengths below this fraction of the scene are round-off (the policy's rule): a scene that small has no extent."""


@dataclass(frozen=True, eq=False)
class Sketch(ReadOnlyArrays):
    """Where each joint is drawn, and the size of the scene (drawing units: the file's lengths times ``scale``, :func:`~mobility.report.plotting.sketch.drawing_scale`).

    ``names``, ``types``, ``points`` (shape (J, 3), global frame) and ``located`` (True where the file gives the
    ``point``): the joints, in the mechanism's order; ``link_joints``: link name -> indices of its joints;
    ``centre``: of the drawn joints; ``size``: extent of the scene (largest side of the joints' bounding box,
    or the characteristic length); ``end_effector_centre``: centroid of the end effector's located joints.
    """

    names: tuple[str, ...]
    types: tuple[str, ...]
    points: np.ndarray
    located: np.ndarray
    link_joints: dict[str, tuple[int, ...]]
    centre: np.ndarray
    size: float
    end_effector_centre: np.ndarray
    scale: float = 1.0

    def drawn(self, point: np.ndarray) -> np.ndarray:
        """A point (or points) of the file in drawing units."""
        return np.asarray(point, dtype=float) * self.scale


def sketch(mechanism: Mechanism, scale: float | None = None) -> Sketch:
    """Compute where each joint of ``mechanism`` is drawn.

    A joint without a point is drawn midway between the located joints of its
    two links; with only one located, a quarter of the scene from it along its
    axis, away from the end effector; with neither, from those placed after.
    ``scale``: drawing units per file unit; default :func:`drawing_scale` of the
    mechanism's characteristic length (poses drawn together share one).
    """
    joints = mechanism.world_joints
    n = len(joints)
    norm = joint_screws(mechanism).normalisation
    scale = drawing_scale(norm.length) if scale is None else float(scale)
    length = norm.length * scale
    located = np.array([j.point is not None for j in joints], dtype=bool)
    pts = np.array([j.point if j.point is not None else (0.0, 0.0, 0.0) for j in joints], dtype=float).reshape(n, 3) * scale
    _require_drawable(mechanism, joints, pts, located, norm.length)
    link_joints: dict[str, list[int]] = {}
    for i, j in enumerate(joints):
        for name in j.links:
            link_joints.setdefault(name, []).append(i)
    if located.any():
        lp = pts[located]
        size = float(np.max(np.ptp(lp, axis=0)))
        centre = lp.mean(axis=0)
    else:
        size, centre = 0.0, np.zeros(3)
    if size <= ROUND_OFF * length:  # every located joint at one point
        size = 2.0 * length if length > 0 else 1.0
    ee = [i for i in link_joints[mechanism.end_effector] if located[i]]
    ee_centre = pts[ee].mean(axis=0) if ee else centre

    placed = located.copy()
    for usable in (located, placed):  # first from the located joints only, then from every joint placed so far
        means: dict[str, np.ndarray | None] = {}  # the mean of a link's usable joints, until one more is placed

        def anchor(link: str) -> np.ndarray | None:
            if link not in means:
                idx = [k for k in link_joints[link] if usable[k]]
                means[link] = pts[idx].mean(axis=0) if idx else None
            return means[link]

        for i, j in enumerate(joints):
            if placed[i]:
                continue
            a, b = anchor(j.links[0]), anchor(j.links[1])
            if a is not None and b is not None:
                pts[i] = 0.5 * (a + b)
            elif a is not None or b is not None:
                x = a if a is not None else b
                assert x is not None  # one of the two links has an anchor
                direction = np.asarray(j.axis if j.axis is not None else (0.0, 0.0, 0.0), dtype=float)
                away = x - ee_centre
                if np.linalg.norm(away) <= ROUND_OFF * size:
                    away = x - centre
                if direction @ away < 0:
                    direction = -direction
                pts[i] = x + 0.25 * size * direction
            elif usable is placed:
                pts[i] = centre
            else:
                continue
            placed[i] = True
            if usable is placed:  # the joint is usable from now on
                for link in j.links:
                    means.pop(link, None)
    if not located.any():
        centre = pts.mean(axis=0)
        ee_centre = pts[link_joints[mechanism.end_effector]].mean(axis=0)
        spread = float(np.max(np.ptp(pts, axis=0)))
        size = spread if spread > 0 else size
    for arr in (pts, located):
        arr.setflags(write=False)
    return Sketch(tuple(j.name for j in joints), tuple(j.type for j in joints), pts, located, {k: tuple(v) for k, v in link_joints.items()}, centre, size,
                  ee_centre, scale)
