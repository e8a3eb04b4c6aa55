"""Where each joint is drawn, and the size of the scene (no matplotlib).

A prismatic joint (or a planar joint without a point) has no location in the
file, so it is drawn between the located joints of its two links, or beside
the one it has.

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

from dataclasses import dataclass

import numpy as np

from ...core.joint_screws import joint_screws
from ...core.model import Mechanism
from ...core.tolerance import DEFAULT_TOLERANCE

__all__ = ["Sketch", "sketch"]

ROUND_OFF = DEFAULT_TOLERANCE.round_off
"""Lengths below this fraction of the scene are round-off (the policy's rule): a scene that small has no extent."""


@dataclass(frozen=True, eq=False)
class Sketch:
    """Where each joint is drawn, and the size of the scene.

    Attributes
    ----------
    names, types : tuple of str
        Joint names and types, in the mechanism's order.
    points : ndarray, shape (J, 3)
        Drawn location of each joint (global frame).
    located : ndarray of bool, shape (J,)
        True where the location comes from the file (``point``); false for a
        placed prismatic or planar joint.
    link_joints : dict
        Link name -> indices of its joints.
    centre : ndarray, shape (3,)
        Centre of the drawn joints.
    size : float
        Extent of the scene (largest side of the joints' bounding box, or the
        mechanism's characteristic length when the joints do not spread).
    end_effector_centre : ndarray, shape (3,)
        Centroid of the located joints of the end effector (where its freedoms
        are drawn); the drawn joints when none is located.
    """

    names: tuple[str, ...]
    types: tuple[str, ...]
    points: np.ndarray
    located: np.ndarray
    link_joints: dict[str, tuple[int, ...]]
    centre: np.ndarray
    size: float
    end_effector_centre: np.ndarray


def sketch(mechanism: Mechanism) -> Sketch:
    """Compute where each joint of ``mechanism`` is drawn.

    A joint without a point (prismatic, or planar without ``point``) is drawn
    midway between the located joints of its two links; when only one of its
    links has located joints, a quarter of the scene away from them along its
    axis, on the side away from the end effector; when neither has, after the
    others are placed, from those.

    Parameters
    ----------
    mechanism : Mechanism

    Returns
    -------
    Sketch
    """
    joints = mechanism.world_joints
    n = len(joints)
    pts = np.zeros((n, 3))
    located = np.array([j.point is not None for j in joints])
    for i, j in enumerate(joints):
        if j.point is not None:
            pts[i] = j.point
    link_joints: dict[str, list[int]] = {}
    for i, j in enumerate(joints):
        for x in j.links:
            link_joints.setdefault(x, []).append(i)
    norm = joint_screws(mechanism).normalisation
    if located.any():
        lp = pts[located]
        size = float(np.max(np.ptp(lp, axis=0)))
        centre = lp.mean(axis=0)
    else:
        size, centre = 0.0, np.zeros(3)
    if size <= ROUND_OFF * norm.length:  # every located joint at one point
        size = 2.0 * norm.length if norm.length > 0 else 1.0
    ee = [i for i in link_joints[mechanism.end_effector] if located[i]]
    ee_centre = pts[ee].mean(axis=0) if ee else centre

    placed = located.copy()

    def anchors(i: int, link: str, usable: np.ndarray) -> np.ndarray | None:
        idx = [k for k in link_joints[link] if k != i and usable[k]]
        return pts[idx].mean(axis=0) if idx else None

    for usable_from_placed in (False, True):
        for i, j in enumerate(joints):
            if placed[i]:
                continue
            usable = placed if usable_from_placed else located
            a = anchors(i, j.links[0], usable)
            b = anchors(i, j.links[1], usable)
            if a is not None and b is not None:
                pts[i] = 0.5 * (a + b)
            elif a is not None or b is not None:
                x = a if a is not None else b
                direction = np.asarray(j.axis if j.axis is not None else (0.0, 0.0, 0.0), dtype=float)
                away = x - ee_centre
                if np.linalg.norm(away) <= ROUND_OFF * size:
                    away = x - centre
                if direction @ away < 0:
                    direction = -direction
                pts[i] = x + 0.25 * size * direction
            elif usable_from_placed:
                pts[i] = centre
            else:
                continue
            placed[i] = True
    if not located.any():
        centre = pts.mean(axis=0)
        ee_centre = pts[link_joints[mechanism.end_effector]].mean(axis=0)
        spread = float(np.max(np.ptp(pts, axis=0)))
        size = spread if spread > 0 else size
    for arr in (pts, located):
        arr.setflags(write=False)
    return Sketch(
        tuple(j.name for j in joints),
        tuple(j.type for j in joints),
        pts,
        located,
        {k: tuple(v) for k, v in link_joints.items()},
        centre,
        size,
        ee_centre,
    )
