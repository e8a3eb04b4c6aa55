"""The joint twists of many poses, each in its own normalised coordinates.

What :func:`mobility.core.joint_screws.joint_screws` gives for one mechanism,
for every pose of a sweep at once, each pose normalised by its own centre and
length: its rank decisions are those :func:`mobility.analyze` makes on the pose
rebuilt as a mechanism.  Each joint's geometry is carried by its link (a ``U``
joint's second axis by ``links[1]``).

Examples
--------
>>> import numpy as np
>>> import mobility
>>> from mobility.core.joint_screws import joint_screws
>>> from mobility.core.kinematics import kinematics
>>> m = mobility.load("mechanisms/3prs.yaml")
>>> posed = posed_screws(kinematics(m), np.zeros((1, 15)))
>>> bool(np.allclose(posed.twists[0], joint_screws(m).twists))
True
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.model import Mechanism
from ..core.joint_screws import unit_twists
from ..core.tolerance import characteristic_scales
from ..core.kinematics import Kinematics
from ..core.transforms import Motion

__all__ = ["PosedScrews", "posed_screws", "joint_geometry"]


@dataclass(frozen=True, eq=False)
class PosedScrews:
    """Unit joint twists of ``N`` poses, each in its own normalised coordinates.

    Attributes
    ----------
    twists : ndarray, shape (N, 6, f)
        Columns as in :attr:`mobility.core.joint_screws.JointScrews.twists`.
    offsets : tuple of int
        Columns of joint ``j`` are ``offsets[j]:offsets[j+1]``.
    centres : ndarray, shape (N, 3)
    lengths : ndarray, shape (N,)
        The normalisation of each pose (global frame, file unit).
    points : dict of str to ndarray (N, 3)
        The moved point of each joint that has one (global frame).
    reference : ndarray, shape (N, 3)
        The end effector's reference point, normalised coordinates of each pose.
    """

    twists: np.ndarray
    offsets: tuple[int, ...]
    centres: np.ndarray
    lengths: np.ndarray
    points: dict[str, np.ndarray]
    reference: np.ndarray

    def normalised(self, points: np.ndarray) -> np.ndarray:
        """Global points ``(N, 3)`` in each pose's normalised coordinates."""
        return (points - self.centres) / self.lengths[:, None]


def joint_geometry(mechanism: Mechanism, motions: dict[str, Motion], centre: np.ndarray, length: float) -> list[dict[str, Any]]:
    """The global geometry of every joint at every pose: ``point``, ``axis``, ``normal``, ``axes`` arrays of shape ``(N, 3)``.

    ``motions`` are the link displacements in the normalised coordinates
    (``centre``, ``length``) of the file's pose.
    """
    out = []
    for joint in mechanism.world_joints:
        rot_a, shift_a = motions[joint.links[0]]
        rot_b, _ = motions[joint.links[1]]
        geometry: dict[str, Any] = {}  # arrays (N, 3); "axes" a pair of them
        if joint.point is not None:
            p = (np.asarray(joint.point) - centre) / length
            geometry["point"] = centre + length * (np.einsum("ijn,j->ni", rot_a, p) + shift_a.T)
        for key in ("axis", "normal"):
            value = getattr(joint, key)
            if value is not None:
                geometry[key] = _unit(np.einsum("ijn,j->ni", rot_a, np.asarray(value)))
        if joint.axes is not None:
            geometry["axes"] = (_unit(np.einsum("ijn,j->ni", rot_a, np.asarray(joint.axes[0]))), _unit(np.einsum("ijn,j->ni", rot_b, np.asarray(joint.axes[1]))))
        out.append(geometry)
    return out


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.sqrt(np.einsum("ni,ni->n", v, v))[:, None]


def _freedoms(joint_type: str, g: dict, count: int, pitch: float | None) -> list[tuple[bool, np.ndarray, np.ndarray, float]]:
    """``(prismatic, axis, point, pitch)`` of each freedom, arrays ``(N, 3)``, as :meth:`Joint.freedoms` orders them."""
    zero = np.zeros((count, 3))
    if joint_type == "R":
        return [(False, g["axis"], g["point"], 0.0)]
    if joint_type == "P":
        return [(True, g["axis"], zero, 0.0)]
    if joint_type == "H":
        assert pitch is not None  # an H joint has its pitch
        return [(False, g["axis"], g["point"], float(pitch))]
    if joint_type == "C":
        return [(False, g["axis"], g["point"], 0.0), (True, g["axis"], zero, 0.0)]
    if joint_type == "U":
        return [(False, g["axes"][0], g["point"], 0.0), (False, g["axes"][1], g["point"], 0.0)]
    if joint_type == "S":
        return [(False, np.broadcast_to(e, (count, 3)), g["point"], 0.0) for e in np.eye(3)]
    # E: two slides in the plane, then the rotation about the normal
    n = g["normal"]
    pick = np.eye(3)[np.argmin(np.abs(n), axis=1)]
    u1 = _unit(np.cross(n, pick))
    u2 = np.cross(n, u1)
    return [(True, u1, zero, 0.0), (True, u2, zero, 0.0), (False, n, g.get("point", zero), 0.0)]


def posed_screws(bk: Kinematics, q: np.ndarray) -> PosedScrews:
    """Unit joint twists of the poses ``q`` ``(N, n)``, each pose in its own normalised coordinates."""
    mechanism = bk.mechanism
    norm = bk.normalisation
    count = len(q)
    geometry = joint_geometry(mechanism, bk.link_motions(q), norm.centre, norm.length)
    freedoms: list[tuple[bool, np.ndarray, np.ndarray, float]] = []
    offsets = [0]
    for joint, g in zip(mechanism.world_joints, geometry):
        freedoms += _freedoms(joint.type, g, count, joint.pitch)
        offsets.append(len(freedoms))
    prismatic, axes, points, pitches = zip(*freedoms)
    located = [g["point"] for g in geometry if "point" in g]
    on_end_effector = [g["point"] for j, g in zip(mechanism.world_joints, geometry) if "point" in g and mechanism.end_effector in j.links]
    pitch_a = np.array(pitches, dtype=float)
    centres, lengths = characteristic_scales(np.stack(located, axis=1) if located else np.zeros((count, 0, 3)), pitches=pitch_a[pitch_a != 0.0])
    ax = np.stack(axes, axis=2)  # (N, 3, f)
    pt = np.stack(points, axis=2)
    tw = unit_twists(np.array(prismatic, dtype=bool), ax, pt - centres[:, :, None], pitch_a, lengths)
    reference = (np.mean(np.stack(on_end_effector, axis=1), axis=1) - centres) / lengths[:, None] if on_end_effector else np.zeros((count, 3))
    named = {j.name: g["point"] for j, g in zip(mechanism.joints, geometry) if "point" in g}
    return PosedScrews(tw, tuple(offsets), centres, lengths, named, reference)

