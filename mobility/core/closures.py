"""Advice on closures: which constraint rows of a closing joint the rest of the mechanism already imposes.

A simulator closes a loop with an equality constraint (MuJoCo's ``connect``,
three rows; ``weld``, six); rows the rest of the mechanism already imposes
make its constraint Jacobian singular (a planar four-bar closed by a point
constraint: the force along the plane's normal).  Each closing joint's rows
(the wrenches reciprocal to its twists, acting on its two links' twists in
the incidence form of loop closure) are projected off the other joints' row
space; the rank of what is left is the number of independent rows.  Ranks
are decided on orthonormal rows in normalised coordinates (absolute
threshold), independent of unit and frame.

Examples
--------
A planar four-bar closed at C by a spherical joint (a point constraint):

>>> from mobility.core.model import Joint, Mechanism
>>> z = (0, 0, 1)
>>> m = Mechanism("four-bar", "ground", "coupler", (
...     Joint("A", "R", ("ground", "crank"), axis=z, point=(0, 0, 0)),
...     Joint("B", "R", ("crank", "coupler"), axis=z, point=(1, 2, 0)),
...     Joint("D", "R", ("ground", "rocker"), axis=z, point=(5, 0, 0)),
...     Joint("C", "S", ("coupler", "rocker"), point=(4, 2.5, 0))))
>>> (c,) = closure_advice(m, ["C"])
>>> c.rows, c.independent, c.redundant
(3, 2, 1)
>>> c.to_dict()["redundant_forces"]
[{'axis': [0.0, 0.0, 1.0], 'point': [4.0, 2.5, 0.0], 'pitch': 0.0, 'kind': 'force'}]
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Iterable

import numpy as np

from ..errors import RequestError, shown_argument
from .analysis import screw_system_in_frame
from .joint_screws import joint_screws
from .linalg import svd
from .model import Mechanism, require_mechanism
from .result import ScrewAxis
from .screws import SWAP_ROWS, span_and_reciprocal
from .tolerance import Tolerance, clean_numbers, decide_rank, file_tolerance, require_tolerance

__all__ = ["ClosureAdvice", "closure_advice"]


@dataclass(frozen=True, eq=False)
class ClosureAdvice:
    """What one closing joint constrains that the rest of the mechanism does not.

    Attributes
    ----------
    joint : str
    rows : int
        Its constraint rows (6 minus its freedoms).
    independent : int
        How many of them the rest of the mechanism does not already impose.
    couples : ndarray, shape (k, 3)
        The redundant rows that are pure couples (unit axes).
    forces : tuple of ScrewAxis
        The other redundant rows, each on its line (global frame).
    wrenches : ndarray, shape (redundant, 6)
        A basis of the redundant rows ``[f; m]``, couples first.
    length_scale : float
        The mechanism's size (the round-off of numbers written).
    """

    joint: str
    rows: int
    independent: int
    couples: np.ndarray
    forces: tuple[ScrewAxis, ...]
    wrenches: np.ndarray
    length_scale: float = 1.0

    @property
    def redundant(self) -> int:
        """How many of the closure's rows depend on the others (``rows - independent``)."""
        return self.rows - self.independent

    def to_dict(self) -> dict[str, Any]:
        """The JSON form: name, counts and the redundant directions."""
        return {"joint": self.joint, "rows": self.rows, "independent": self.independent, "redundant": self.redundant,
                "redundant_couples": [clean_numbers(c) for c in self.couples], "redundant_forces": [f.to_dict(self.length_scale) for f in self.forces]}


def closure_advice(mechanism: Mechanism, joints: Iterable[str], *, tol: Tolerance | None = None) -> tuple[ClosureAdvice, ...]:
    """For each joint named, how many of its constraint rows are independent, and the redundant ones.

    ``joints`` may name any joints (one on no loop has every row
    independent); the advice comes in the order asked.  ``tol`` defaults to
    :func:`~mobility.analyze`'s (never finer than the file's precision).  A
    name that is not a joint raises :class:`~mobility.errors.RequestError`.

    Examples
    --------
    >>> import mobility
    >>> [c.redundant for c in closure_advice(mobility.load("mechanisms/four_bar.yaml"), ["D"])]
    [3]
    """
    mechanism = require_mechanism(mechanism, "closure_advice")
    tol = file_tolerance(mechanism.precision) if tol is None else require_tolerance(tol, "closure_advice")
    if isinstance(joints, (str, bytes)) or not isinstance(joints, Iterable):
        raise RequestError(f"joints must be a list of joint names, got {shown_argument(joints)}", caller="closure_advice")
    names = list(joints)
    index = {j.name: i for i, j in enumerate(mechanism.joints)}
    for name in names:
        if name not in index:
            raise RequestError(f"{shown_argument(name)} is not a joint of {mechanism.name!r}", caller="closure_advice")
    screws = joint_screws(mechanism)
    rows, wrenches = _constraint_rows(mechanism, screws, tol)
    return tuple(_advice(mechanism, screws, rows, wrenches, index[name], tol) for name in names)


def _constraint_rows(mechanism: Mechanism, screws: Any, tol: Tolerance) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Each joint's constraint rows on the twists of the links (ground left out), and its constraint wrenches."""
    links = [x for x in mechanism.links if x != mechanism.ground]
    column = {x: 6 * i for i, x in enumerate(links)}
    rows, wrenches = [], []
    for i, joint in enumerate(mechanism.joints):
        w = span_and_reciprocal(screws.of_joint(i), tol).reciprocal  # (6, 6 - f), orthonormal, [f; m]
        acting = w[SWAP_ROWS].T  # w . t = (swap w)^T t
        r = np.zeros((w.shape[1], 6 * len(links)))
        a, b = joint.links
        if b in column:
            r[:, column[b] : column[b] + 6] += acting
        if a in column:
            r[:, column[a] : column[a] + 6] -= acting
        rows.append(r)
        wrenches.append(w)
    return rows, wrenches


def _advice(mechanism: Mechanism, screws: Any, rows: list[np.ndarray], wrenches: list[np.ndarray], i: int, tol: Tolerance) -> ClosureAdvice:
    """The advice for joint ``i``: its rows projected off the others' row space."""
    own = rows[i]
    others = np.concatenate([r for k, r in enumerate(rows) if k != i] or [np.zeros((0, own.shape[1]))])
    if others.shape[0] and own.shape[0]:
        _, s, vt = svd(others)
        span = vt[: decide_rank(s, tol).rank]
        left = own - (own @ span.T) @ span
    else:
        left = own
    if own.shape[0]:
        u, s, _ = svd(left)
        independent = decide_rank(np.concatenate([[1.0], s]), tol).rank - 1  # orthonormal rows: an absolute threshold
        combination = u[:, independent:]  # combinations of the rows that vanish off the others' row space
    else:
        independent, combination = 0, np.zeros((0, 0))
    redundant = wrenches[i] @ combination  # (6, r), orthonormal, normalised coordinates
    couples, forces, basis = screw_system_in_frame(redundant, screws.normalisation, screws.reference, ("force", "wrench"), tol)
    return ClosureAdvice(mechanism.joints[i].name, own.shape[0], independent, couples, forces, basis, screws.normalisation.size)
