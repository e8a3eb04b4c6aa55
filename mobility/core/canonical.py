"""Canonical, readable bases of screw systems: free vectors and principal screws.

A twist system splits into free vectors (pure translations ``[0; v]``) and
screws with independent directions; a wrench system into couples and force
screws.  The canonical form:

1. **free part**: an orthonormal basis as close to the coordinate axes as the
   subspace allows (``z`` comes out as ``[0, 0, 1]``);
2. **screw part**: one screw per remaining direction, with the free part
   removed at the *reference point* (the centroid of the end effector's joint
   points, so the form follows the mechanism under rigid motion and scaling).
   Directions orthogonal to every free vector have an intrinsic pitch
   ``h(w) = w . v / |w|^2``, a quadratic form whose eigenvectors are Hunt's
   **principal screws**; every other direction is given pitch 0 by a free
   vector.  Ties go to axes close to the coordinate axes; each axis passes
   through its point nearest the reference point, whose offset is the
   parasitic motion there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .linalg import svd
from .screws import free_vector_subspace
from .transforms import cross
from .tolerance import COMPONENT_TIE, DEFAULT_TOLERANCE, NORM_TIE, RankDecision, Tolerance

__all__ = ["PrincipalScrew", "CanonicalForm", "canonical_form", "readable_basis"]


@dataclass(frozen=True)
class PrincipalScrew:
    """A screw axis: unit ``axis``, a ``point`` on it, and its ``pitch`` (length per radian)."""

    axis: np.ndarray
    point: np.ndarray
    pitch: float

    def screw(self) -> np.ndarray:
        """The unit screw ``[s; p x s + h s]``."""
        return np.concatenate([self.axis, cross(self.point, self.axis) + self.pitch * self.axis])


@dataclass(frozen=True)
class CanonicalForm:
    """Free vectors (3 x k, orthonormal columns) and principal screws of a screw system."""

    free: np.ndarray
    screws: tuple[PrincipalScrew, ...]
    decision: RankDecision


def _dominant(v: np.ndarray) -> int:
    """Index of the first component of (nearly) largest magnitude."""
    mags = [abs(x) for x in v.tolist()]
    top = max(mags) - COMPONENT_TIE
    return next(i for i, m in enumerate(mags) if m > top)


def _signed(v: np.ndarray) -> np.ndarray:
    """Flip ``v`` so that its first component of largest magnitude is positive."""
    return -v if v[_dominant(v)] < 0 else v


def readable_basis(q: np.ndarray) -> np.ndarray:
    """An orthonormal basis of ``span(q)`` made of the projections of coordinate axes.

    ``q`` has orthonormal columns.  Greedy Gram-Schmidt of the projected axes,
    largest first, each with its largest component positive, ordered by that
    component's index.

    Examples
    --------
    >>> c = np.sqrt(0.5)
    >>> (readable_basis(np.array([[c, c], [c, -c], [0, 0]])).round(12) + 0.0).tolist()
    [[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]
    """
    n, m = q.shape
    if m == 0:
        return q
    resid = q @ q.T  # the projections of the coordinate axes
    basis: list[np.ndarray] = []
    for _ in range(m):
        norms = np.sqrt(np.einsum("ij,ij->j", resid, resid)).tolist()
        top = max(norms) - NORM_TIE
        k = next(i for i, x in enumerate(norms) if x > top)
        b = _signed(resid[:, k] / norms[k])
        basis.append(b)
        resid = resid - np.outer(b, b @ resid)
    basis.sort(key=_dominant)
    return np.stack(basis, axis=1)


def canonical_form(basis: np.ndarray, reference: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> CanonicalForm:
    """Free vectors and principal screws of the system spanned by ``basis``.

    ``basis`` (6, d) is orthonormal; each axis point is the one nearest
    ``reference`` (same coordinates), pitches in ``basis``'s length unit;
    ``tol`` also groups equal pitches.

    Examples
    --------
    >>> from mobility.core.screws import revolute_twist, prismatic_twist, span_and_reciprocal
    >>> cyl = np.stack([revolute_twist([0, 0, 1], [1, 0, 0]), prismatic_twist([0, 0, 1])], axis=1)
    >>> form = canonical_form(span_and_reciprocal(cyl).basis, np.zeros(3))
    >>> form.free.T.round(12).tolist()
    [[0.0, 0.0, 1.0]]
    >>> [(a.axis.round(12).tolist(), a.point.round(12).tolist(), round(a.pitch, 12)) for a in form.screws]
    [([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], 0.0)]
    """
    free, coef, decision = free_vector_subspace(basis, tol)
    free = readable_basis(free)
    r = coef.shape[1]
    if r == 0:
        return CanonicalForm(free, (), decision)
    screws = basis @ coef
    bw = screws[:3]
    bv = screws[3:] - cross(reference[:, None], bw)
    if free.shape[1]:
        bv = bv - free @ (free.T @ bv)
    u, s, vt = svd(bw)
    qw = u[:, :r]
    a = (bv @ vt.T[:, :r]) / s[:r]  # v = a @ (qw.T w) for w in span(qw)
    if free.shape[1]:
        # Directions orthogonal to every free vector: null space of free.T @ qw.
        _, gs, gvt = svd(free.T @ qw)
        k = int(np.count_nonzero(gs > tol.rank))
        perp, rest = gvt[k:].T, gvt[:k].T
    else:
        perp, rest = np.eye(r), np.zeros((r, 0))
    out: list[PrincipalScrew] = []
    m = perp.T @ qw.T @ a @ perp  # pitch form on W ∩ F⊥
    pitches, vecs = np.linalg.eigh(0.5 * (m + m.T))
    start = 0
    while start < len(pitches):
        stop = start + 1
        while stop < len(pitches) and abs(pitches[stop] - pitches[start]) <= tol.near_singular * max(1.0, abs(pitches[start])):
            stop += 1
        cluster = qw @ perp @ vecs[:, start:stop]
        directions = readable_basis(cluster) if stop - start > 1 else np.stack([_signed(cluster[:, 0])], axis=1)
        for w in directions.T:
            v = a @ (qw.T @ w)
            out.append(PrincipalScrew(w, reference + cross(w, v), float(w @ v)))
        start = stop
    for w in readable_basis(qw @ rest).T:
        v = a @ (qw.T @ w)
        along = free @ (free.T @ w)
        v = v - (w @ v) / (along @ along) * along  # a free vector cancels the pitch
        out.append(PrincipalScrew(w, reference + cross(w, v), 0.0))
    out.sort(key=lambda p: (abs(p.pitch) > tol.rank, _dominant(p.axis)))
    return CanonicalForm(free, tuple(out), decision)
