"""Screw algebra in Plücker ray coordinates.

Conventions (stated once, pinned by ``tests/test_screws.py``):

* a twist is ``[w; v]`` with ``v = p x w + h w`` (angular part first);
* a wrench is ``[f; m]`` with ``m = p x f + h f``;
* the reciprocal product is ``a o b = a_w . b_v + a_v . b_w``, i.e.
  ``a @ SWAP @ b`` with ``SWAP = [[0, I], [I, 0]]``; a wrench does no work on a
  twist exactly when their reciprocal product is zero;
* a frame at origin ``t`` with rotation ``R`` maps both twists and wrenches by
  the same 6x6 adjoint ``[[R, 0], [skew(t) R, R]]``.

A *screw system* is kept as a 6 x r orthonormal basis; one SVD gives the
span and its reciprocal, since the reciprocal of ``span(T)`` is
``SWAP @ (span(T))^perp``.

Examples
--------
>>> import numpy as np
>>> rz = revolute_twist(axis=[0, 0, 1], point=[1, 0, 0])
>>> rz.tolist()
[0.0, 0.0, 1.0, 0.0, -1.0, 0.0]
>>> sys = span_and_reciprocal(rz[:, None])
>>> sys.basis.shape[1], sys.reciprocal.shape[1]
(1, 5)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .linalg import left_svd, rank, singular_values, svd
from .tolerance import DEFAULT_TOLERANCE, SIGN_TIE, RankDecision, Tolerance, decide_rank
from .transforms import skew

__all__ = ["SWAP", "SWAP_ROWS", "revolute_twist", "prismatic_twist", "helical_twist", "reciprocal_product", "adjoint",
           "ScrewSpan", "span_and_reciprocal", "reciprocal_system", "intersection", "same_subspace", "free_vector_subspace",
           "pattern_of", "motion_pattern"]

SWAP = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])
"""The 6x6 matrix of the reciprocal product: ``a o b = a @ SWAP @ b``."""

SWAP_ROWS = np.array([3, 4, 5, 0, 1, 2])
"""Row order with ``SWAP @ x == x[SWAP_ROWS]`` (cheaper than the product)."""


def revolute_twist(axis: npt.ArrayLike, point: npt.ArrayLike) -> np.ndarray:
    """Unit twist of a rotation about the line through ``point`` along ``axis``: ``[s; p x s]``."""
    s = np.asarray(axis, dtype=float)
    return np.concatenate([s, np.cross(np.asarray(point, dtype=float), s)])


def prismatic_twist(axis: npt.ArrayLike) -> np.ndarray:
    """Unit twist of a translation along ``axis``: ``[0; s]``."""
    return np.concatenate([np.zeros(3), np.asarray(axis, dtype=float)])


def helical_twist(axis: npt.ArrayLike, point: npt.ArrayLike, pitch: float) -> np.ndarray:
    """Unit twist of a screw motion: ``[s; p x s + h s]`` (pitch ``h`` in length per radian)."""
    s = np.asarray(axis, dtype=float)
    return np.concatenate([s, np.cross(np.asarray(point, dtype=float), s) + pitch * s])


def reciprocal_product(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Reciprocal product ``a_w . b_v + a_v . b_w`` of screws stored as columns.

    One screw ``(6,)`` pairs with every column of a ``(6, n)``; two ``(6, n)``
    pair column by column (further axes broadcast).

    Examples
    --------
    >>> force_x_through_origin = np.array([1.0, 0, 0, 0, 0, 0])
    >>> float(reciprocal_product(force_x_through_origin, prismatic_twist([1.0, 0, 0])))
    1.0
    >>> reciprocal_product(force_x_through_origin, np.eye(6)[:, 3:]).tolist()
    [1.0, 0.0, 0.0]
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    if a.ndim == 1 and b.ndim > 1:
        a = a.reshape((6,) + (1,) * (b.ndim - 1))
    elif b.ndim == 1 and a.ndim > 1:
        b = b.reshape((6,) + (1,) * (a.ndim - 1))
    return np.sum(a[:3] * b[3:], axis=0) + np.sum(a[3:] * b[:3], axis=0)


def adjoint(rotation: np.ndarray, translation: np.ndarray) -> np.ndarray:
    """The 6x6 matrix ``[[R, 0], [skew(t) R, R]]`` moving twists or wrenches to a parent frame.

    Examples
    --------
    >>> local = revolute_twist([0, 0, 1], [0, 0, 0])
    >>> moved = adjoint(np.eye(3), np.array([1.0, 0, 0])) @ local
    >>> bool(np.allclose(moved, revolute_twist([0, 0, 1], [1, 0, 0])))
    True
    """
    R = np.asarray(rotation, dtype=float)
    out = np.zeros((6, 6))
    out[:3, :3] = R
    out[3:, 3:] = R
    out[3:, :3] = skew(translation) @ R
    return out


@dataclass(frozen=True)
class ScrewSpan:
    """A screw system and its reciprocal, from one SVD.

    ``basis`` (6, r) is orthonormal, ``reciprocal`` (6, 6 - r) orthonormal up
    to the swap; ``decision`` the rank decision with its margin (see
    :func:`span_and_reciprocal`).
    """

    basis: np.ndarray
    reciprocal: np.ndarray
    decision: RankDecision

    @property
    def dim(self) -> int:
        """Dimension of the span."""
        return self.decision.rank


def span_and_reciprocal(screws: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> ScrewSpan:
    """Span of the columns of ``screws`` and the reciprocal system, by one SVD.

    ``screws`` are columns (6, n), ``n`` may be 0.  Each basis column is
    signed so that its first largest component is positive, so a
    one-dimensional system comes out the same from every SVD routine.

    Examples
    --------
    >>> span_and_reciprocal(np.eye(6)[:, [2, 2]]).dim
    1
    """
    m = screws if isinstance(screws, np.ndarray) and screws.ndim == 2 else np.asarray(screws, dtype=float).reshape(6, -1)
    if m.shape[1] == 0:
        return ScrewSpan(np.zeros((6, 0)), np.eye(6), RankDecision(0))
    u, s = left_svd(m)
    d = decide_rank(s, tol)
    u = u * np.where(u[np.argmax(np.abs(u) > np.abs(u).max(axis=0) - SIGN_TIE, axis=0), np.arange(u.shape[1])] < 0.0, -1.0, 1.0)
    return ScrewSpan(u[:, : d.rank], u[SWAP_ROWS, d.rank :], d)


def reciprocal_system(screws: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> np.ndarray:
    """Basis of the screws reciprocal to every column of ``screws``.

    Examples
    --------
    >>> planar = np.stack([prismatic_twist([1, 0, 0]), prismatic_twist([0, 1, 0]),
    ...                    revolute_twist([0, 0, 1], [0, 0, 0])], axis=1)
    >>> w = reciprocal_system(planar)
    >>> w.shape[1], bool(np.allclose(reciprocal_product(w, planar[:, [0]]), 0))
    (3, True)
    """
    return span_and_reciprocal(screws, tol).reciprocal


def intersection(a: np.ndarray, b: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> np.ndarray:
    """Basis of ``span(a) ∩ span(b)``: the reciprocal of the union of their reciprocals."""
    union = np.hstack([reciprocal_system(a, tol), reciprocal_system(b, tol)])
    return reciprocal_system(union, tol)


def same_subspace(a: np.ndarray, b: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> bool:
    """True when the columns of ``a`` and ``b`` span the same subspace.

    Equal ranks, and stacking them adds none; any row count (screws, 3-vectors).

    Examples
    --------
    >>> same_subspace(np.array([[1.0, 0], [0, 1], [0, 0]]), np.array([[1.0], [1.0], [0.0]]))
    False
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    if a.shape[0] != b.shape[0]:
        return False
    return rank(a, tol) == rank(b, tol) == rank(np.hstack([a, b]), tol)


def free_vector_subspace(basis: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE, *, coefficients: bool = True):
    """Split an orthonormal screw basis into its free-vector part and the rest.

    The free vectors are a twist system's pure translations ``[0; v]``, a
    wrench system's pure couples.  Returns ``free`` (3, k), an orthonormal
    basis of their ``v`` parts; ``coefficients`` (d, d - k), orthonormal, with
    ``basis @ coefficients`` screws of independent directions; and the rank
    decision on the direction part (rank ``d - k``, threshold absolute: the
    basis is orthonormal), alone when ``coefficients`` is false.

    Examples
    --------
    >>> cyl = np.stack([revolute_twist([0, 0, 1], [1, 0, 0]), prismatic_twist([0, 0, 1])], axis=1)
    >>> free_vector_subspace(span_and_reciprocal(cyl).basis, coefficients=False).rank
    1
    """
    d = basis.shape[1]
    if not coefficients:
        if d == 0:
            return RankDecision(0)
        return decide_rank(singular_values(basis[:3]), tol)  # at most 1 (orthonormal basis), up to round-off: the threshold is absolute
    if d == 0:
        return np.zeros((3, 0)), np.zeros((0, 0)), RankDecision(0)
    _, s, vt = svd(basis[:3])
    decision = decide_rank(s, tol)
    r = decision.rank
    null = vt[r:].T  # coefficients of the pure free vectors
    if null.shape[1]:
        fu, _, _ = svd(basis[3:] @ null)
        free = fu[:, : null.shape[1]]
    else:
        free = np.zeros((3, 0))
    return free, vt[:r].T, decision


def pattern_of(translations: int, rotations: int) -> str:
    """The motion pattern ``{nT}T{nR}R``, a zero part dropped; ``"0"`` for no motion.

    Examples
    --------
    >>> pattern_of(1, 2), pattern_of(3, 0), pattern_of(0, 0)
    ('1T2R', '3T', '0')
    """
    text = (f"{translations}T" if translations else "") + (f"{rotations}R" if rotations else "")
    return text or "0"


def motion_pattern(basis: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> str:
    """The motion pattern of an orthonormal twist basis: pure translations, then rotational freedoms.

    ``nT`` is the dimension of the pure translations, ``nR`` the rest: the one rule of every feature.

    Examples
    --------
    >>> cyl = np.stack([revolute_twist([0, 0, 1], [1, 0, 0]), prismatic_twist([0, 0, 1])], axis=1)
    >>> motion_pattern(span_and_reciprocal(cyl).basis)
    '1T1R'
    """
    rotations = free_vector_subspace(basis, tol, coefficients=False).rank
    return pattern_of(basis.shape[1] - rotations, rotations)
