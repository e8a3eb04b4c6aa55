"""The actuation wrench of one input at a stack of poses: the one computation behind one pose and a sweep.

An input is one freedom of an actuated joint of a limb.  Its *actuation
wrench* (docs/actuation.md, "Definitions") is the first left singular vector of
the limb's constraint wrenches with that freedom locked, less the limb's own;
none when the limb's other joints already produce the freedom's motion.  Its
*rate* is ``a o $``, ``$`` at unit angular speed (R, H) or one characteristic
length per unit time (P); its *transmission* ``|a o $| / (|a| |$|)``, in ``[0, 1]``.

Examples
--------
>>> import numpy as np
>>> from mobility.core.model import Joint, Mechanism
>>> from mobility.core.topology import decompose
>>> from mobility.core.joint_screws import joint_screws
>>> from mobility.core.screw_systems import evaluate
>>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
>>> arm = Mechanism("RR arm", "g", "hand", (R("A", "g", "upper", (0, 0, 0)), R("B", "upper", "hand", (1, 0, 0))))
>>> s, node = joint_screws(arm), decompose(arm).root
>>> twists = s.twists[None]
>>> w = input_wrenches(node, evaluate(node, twists, s.offsets), twists, s.offsets, 0, s.reference[None])
>>> w.has.tolist(), round(float(w.transmission[0]), 6)
([True], 1.0)
"""

from __future__ import annotations

from typing import NamedTuple, Sequence, cast

import numpy as np

from ..core.linalg import left_svds
from ..core.screw_systems import Systems, evaluate, span
from ..core.screws import SWAP_ROWS
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, decide_ranks
from ..core.topology import JointNode, Node, Series

__all__ = ["InputWrenches", "input_wrenches", "shift"]


class InputWrenches(NamedTuple):
    """The actuation wrench of one input at each pose of a stack.

    Attributes
    ----------
    wrench : ndarray, shape (N, 6)
        Unit wrench (normalised coordinates), zero where there is none.
    rate : ndarray, shape (N,)
        ``a o $`` (1.0 where there is no wrench).
    transmission : ndarray, shape (N,)
        ``|a o $| / (|a| |$|)`` (0.0 where there is no wrench).
    has : ndarray of bool, shape (N,)
        Whether the input has a wrench of its own at that pose.
    """

    wrench: np.ndarray
    rate: np.ndarray
    transmission: np.ndarray
    has: np.ndarray


def shift(points: np.ndarray, screws: np.ndarray, sign: float) -> np.ndarray:
    """``[a; b] -> [a; b - sign * p x a]`` for stacks of screws ``(N, 6, k)`` and points ``(N, 3)``.

    Examples
    --------
    >>> import numpy as np
    >>> z_rotation = np.array([[[0.0], [0.0], [1.0], [0.0], [0.0], [0.0]]])
    >>> shift(np.array([[1.0, 0.0, 0.0]]), z_rotation, 1.0)[0, :, 0].tolist()
    [0.0, 0.0, 1.0, 0.0, 1.0, 0.0]
    """
    out = screws.copy()
    out[:, 3:] -= sign * np.cross(points[:, :, None], screws[:, :3], axis=1)
    return out


def _locked_limb(node: Node, twists: np.ndarray, offsets: Sequence[int], col: int, tol: Tolerance) -> Systems:
    """The limb's twist system with freedom ``col`` locked (its twist zero; in a series of joints, the column left out: the same span)."""
    if isinstance(node, Series) and all(type(c) is JointNode for c in node.children):
        joints = cast("tuple[JointNode, ...]", node.children)  # every child is a joint (tested above)
        columns = [c for child in joints for c in range(offsets[child.index], offsets[child.index + 1]) if c != col]
        basis, wrenches, rank = span(twists[:, :, columns], len(columns), tol)
        return Systems(basis, rank, wrenches, rank * 0)
    locked = twists.copy()
    locked[:, :, col] = 0.0
    return evaluate(node, locked, offsets, tol)


def input_wrenches(node: Node, limb: Systems, twists: np.ndarray, offsets: Sequence[int], col: int, attach: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> InputWrenches:
    """The actuation wrench, rate and transmission of freedom ``col`` of a limb at every pose.

    ``node`` is the limb in the decomposition, ``limb`` its screw systems at the poses
    (:func:`mobility.core.screw_systems.evaluate`), ``twists`` ``(N, 6, f)`` the joint
    twists (normalised; joint ``j``'s columns ``offsets[j]:offsets[j+1]``), ``attach``
    ``(N, 3)`` where the limb meets the end effector (normalised).
    """
    count = twists.shape[0]
    others = _locked_limb(node, twists, offsets, col, tol)
    w_other = shift(attach, others.wrenches, 1.0)
    if limb.wrenches.shape[2]:
        q, _ = np.linalg.qr(shift(attach, limb.wrenches, 1.0))
        q = q * (np.arange(q.shape[2]) < np.reshape(6 - limb.dim, (-1, 1)))[:, None, :]
        w_other = w_other - q @ (np.swapaxes(q, 1, 2) @ w_other)
    if w_other.shape[2] == 0:
        return InputWrenches(np.zeros((count, 6)), np.ones(count), np.zeros(count), np.zeros(count, dtype=bool))
    other_count = 6 - others.dim
    u, s, _ = left_svds(w_other)
    has = (other_count > 0) & (decide_ranks(s, tol, np.minimum(other_count, 6)).rank > 0)
    a = shift(attach, u[:, :, :1], -1.0)[:, :, 0]
    a /= np.linalg.norm(a, axis=1)[:, None]
    twist = twists[:, :, col].copy()
    wn = np.linalg.norm(twist[:, :3], axis=1)
    twist[wn > tol.rank] /= wn[wn > tol.rank, None]  # unit angular rate (R, H); P columns are already unit linear rate
    r = np.einsum("ni,ni->n", a[:, SWAP_ROWS], twist)
    a = np.where((r < 0)[:, None], -a, a)
    return InputWrenches(np.where(has[:, None], a, 0.0), np.where(has, np.abs(r), 1.0),
                         np.where(has, np.minimum(np.abs(r) / np.linalg.norm(twist, axis=1), 1.0), 0.0), has)
