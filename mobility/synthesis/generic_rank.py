"""Generic ranks of serial chains: the dimension of a chain's set of finite motions.

The set of finite motions of a chain of one-DOF joints is the image of its
joint values; its dimension is the rank of the chain's twists at a generic pose.
:func:`generic_rank` takes the largest rank over a few random seeded poses
(angles in ``(-π, π)``, slides across the given length), in normalised
coordinates (lengths over that length, unit columns), decided by
:func:`mobility.core.tolerance.decide_rank`.

Examples
--------
>>> import numpy as np
>>> from mobility.core.finite_screws import ScrewJoint
>>> rng = np.random.default_rng(0)
>>> spherical = [ScrewJoint("R", e) for e in np.eye(3)]           # three R through the origin
>>> generic_rank(spherical, rng, 3, 1.0), generic_rank(spherical[:1] * 2, rng, 3, 1.0)
(3, 1)
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from ..core.finite_screws import ScrewJoint
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, decide_rank
from ..core.transforms import skew

__all__ = ["chain_twists", "sample_joint_values", "generic_rank"]


def chain_twists(joints: Sequence[ScrewJoint], q: np.ndarray) -> np.ndarray:
    """Spatial twists of a chain at many poses at once: shape ``(samples, 6, n)``.

    Column ``j`` is joint ``j``'s twist carried by the joints before it,
    ``Ad(T_1 ... T_{j-1}) ξ_j``: the derivative of the finite screw mapped by
    Eq. 5 (:meth:`~mobility.core.finite_screws.Limb.twists`, pinned by a test).
    ``q``: joint values, one pose per row.
    """
    samples, n = q.shape
    rot = np.broadcast_to(np.eye(3), (samples, 3, 3)).copy()
    pos = np.zeros((samples, 3))
    out = np.empty((samples, 6, n))
    for j, joint in enumerate(joints):
        s = np.asarray(joint.axis)
        w = rot @ s
        if joint.kind == "P":
            out[:, :3, j] = 0.0
            out[:, 3:, j] = w
            pos = pos + w * q[:, j : j + 1]
            continue
        point = np.asarray(joint.point)
        r = np.einsum("kij,j->ki", rot, point) + pos  # the axis point, carried
        out[:, :3, j] = w
        out[:, 3:, j] = np.cross(r, w) + joint.pitch * w
        # T <- T @ exp(q ξ): rotation about the carried axis through r (plus pitch slide), by Rodrigues
        k = skew(s)
        th = q[:, j][:, None, None]
        local = np.eye(3) + np.sin(th) * k + (1.0 - np.cos(th)) * (k @ k)
        p_local = point - local @ point + joint.pitch * q[:, j][:, None] * s
        pos = pos + np.einsum("kij,kj->ki", rot, p_local)
        rot = rot @ local
    return out


def sample_joint_values(joints: Sequence[ScrewJoint], rng: np.random.Generator, samples: int, length: float) -> np.ndarray:
    """Random joint values, shape ``(samples, n)``: angles in ``(-π, π)``, slides in ``(-length, length)``."""
    q = rng.uniform(-math.pi, math.pi, (samples, len(joints)))
    for j, joint in enumerate(joints):
        if joint.kind == "P":
            q[:, j] = rng.uniform(-length, length, samples)
    return q


def generic_rank(joints: Sequence[ScrewJoint], rng: np.random.Generator, samples: int, length: float, tol: Tolerance = DEFAULT_TOLERANCE) -> int:
    """Largest rank of the chain's twists over ``samples`` random poses (normalised coordinates, unit columns).

    ``length`` is the characteristic length: lengths are divided by it, slides range over it.
    """
    if not joints:
        return 0
    tw = chain_twists(joints, sample_joint_values(joints, rng, samples, length))
    tw[:, 3:, :] /= length
    tw /= np.linalg.norm(tw, axis=1, keepdims=True)
    sv = np.linalg.svd(tw, compute_uv=False)
    return max(decide_rank(s, tol).rank for s in sv)
