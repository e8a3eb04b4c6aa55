"""First and second order: which motions the loop equations allow at a pose, to first and to second order.

* :func:`first_order`: the rank of the loop Jacobian at a pose (the tolerance
  policy), its null space (the tangent space: joint rates that close every
  loop to first order) and the end-effector DOF along it.
* :func:`second_order`: along a first-order motion ``d = N u`` the residual's
  part ``t^2/2 B(d, d)`` outside the Jacobian's range (the *cokernel*) cannot
  be corrected, so ``u`` extends only where the quadratic forms ``u @ M_k @ u``
  all vanish; when no unit ``u`` does, the pose cannot move at all.
* :func:`canonical_basis`: a basis of the tangent space that depends only on
  the subspace, so the moves tried do not depend on how the SVD chose it.

Examples
--------
>>> import numpy as np
>>> from mobility.core.kinematics import kinematics
>>> from mobility.core.model import Joint, Mechanism
>>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
>>> flat = Mechanism("flat four-bar", "g", "c", (R("A", "g", "k", (0, 0, 0)), R("B", "k", "c", (1, 0, 0)),
...                                               R("C", "c", "r", (3, 0, 0)), R("D", "r", "g", (6, 0, 0))))
>>> kin = kinematics(flat)
>>> here = first_order(kin, np.zeros(4))
>>> here.mobility, here.dof
(2, 2)
>>> second_order(kin, canonical_basis(here.tangent), np.random.default_rng(0), here.largest_dropped).obstructed
True
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..core.kinematics import CLOSE_STALLED as STALLED
from ..core.kinematics import ROUND_OFF
from ..core.kinematics import Kinematics
from ..core.screws import motion_pattern, span_and_reciprocal
from ..core.tolerance import DEFAULT_TOLERANCE, SOLVER_STOP, Tolerance
from .parameters import DISTINCT_LINES, INEXACT_ALLOWANCE
from .results import SecondOrder

__all__ = ["FirstOrder", "first_order", "first_orders", "second_order", "canonical_basis", "end_effector_pattern"]


class FirstOrder(NamedTuple):
    """The first-order motions at a pose.

    Attributes
    ----------
    mobility : int
        Dimension of the tangent space.
    tangent : ndarray, shape (n, mobility)
        Orthonormal basis of the joint rates that close every loop to first order.
    smallest_kept, largest_dropped : float
        The margin of the loop Jacobian's rank decision (relative).
    dof : int
        End-effector DOF along the tangent space.
    """

    mobility: int
    tangent: np.ndarray
    smallest_kept: float
    largest_dropped: float
    dof: int


def end_effector_pattern(twists: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> tuple[int, str]:
    """DOF and motion pattern of end-effector twists (columns, normalised coordinates), scaled to at most 1.

    Examples
    --------
    >>> import numpy as np
    >>> end_effector_pattern(np.array([[0, 0, 0, 2.0, 0, 0], [0, 0, 1.0, 0, 0, 0]]).T)
    (2, '1T1R')
    """
    span = span_and_reciprocal(_scaled(twists), tol)
    return span.dim, motion_pattern(span.basis, tol)


def first_order(kin: Kinematics, q: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> FirstOrder:
    """Mobility, tangent space, margin and end-effector DOF at the pose ``q``."""
    return first_orders(kin, np.asarray(q, dtype=float).reshape(1, -1), tol)[0]


def first_orders(kin: Kinematics, q: np.ndarray, tol: Tolerance = DEFAULT_TOLERANCE) -> tuple[FirstOrder, ...]:
    """:func:`first_order` at each pose of a stack ``q`` ``(N, n)`` (its Jacobians and SVDs each in one call)."""
    if len(q) == 0:
        return ()
    decisions = kin.rank_decisions(q, tol)
    twists = kin.end_effector_jacobian(q).reshape(len(q), 6, -1)
    out = []
    for (decision, null), ee in zip(decisions, twists):
        dof = span_and_reciprocal(_scaled(ee @ null), tol).dim if null.shape[1] else 0
        out.append(FirstOrder(null.shape[1], null, decision.smallest_kept, decision.largest_dropped, dof))
    return tuple(out)


def _scaled(twists: np.ndarray) -> np.ndarray:
    """Twists divided by their largest entry when it exceeds 1 (the rank policy's scale)."""
    return twists / max(1.0, float(np.abs(twists).max(initial=0.0)))


def canonical_basis(null: np.ndarray) -> np.ndarray:
    """An orthonormal basis of ``span(null)`` that depends only on the subspace.

    A column-pivoted QR of the projector, each column's largest entry made
    positive, with ties (to :data:`TIE` relative) going to the lowest joint
    variable instead of to round-off (a symmetric mechanism has exact ties,
    which a file moved rigidly would otherwise break another way).  So the
    first moves tried are the motions nearest to turning or sliding one joint.

    Examples
    --------
    >>> import numpy as np
    >>> c = np.sqrt(0.5)
    >>> a = canonical_basis(np.array([[c], [-c], [0.0]]))
    >>> a.round(3).tolist(), bool(np.allclose(a, canonical_basis(-a)))
    ([[0.707], [-0.707], [0.0]], True)
    >>> b = canonical_basis(np.linalg.qr(np.array([[1.0, 1.0], [2.0, 0.0], [0.0, 1.0]]))[0])
    >>> bool(np.allclose(b, canonical_basis(b @ np.array([[0.6, -0.8], [0.8, 0.6]]))))   # any basis of the plane
    True
    """
    k = null.shape[1]
    if k == 0:
        return null
    rest = null @ null.T  # the projector on what is left of the subspace
    basis = np.empty((len(rest), k))
    for i in range(k):
        lengths = np.einsum("ij,ij->j", rest, rest)  # of each joint's unit rate projected
        j = int(np.flatnonzero(lengths >= (1.0 - TIE) * lengths.max())[0])
        basis[:, i] = rest[:, j] / np.sqrt(lengths[j])
        rest = rest - np.outer(basis[:, i], basis[:, i] @ rest)
    magnitudes = np.abs(basis)
    largest = np.argmax(magnitudes >= (1.0 - TIE) * magnitudes.max(axis=0, initial=0.0), axis=0)
    return basis * np.sign(basis[largest, np.arange(k)])


TIE = 1e-9
"""Two lengths within this fraction of each other are a tie in :func:`canonical_basis` (round-off is ~1e-15)."""


def second_order(kin: Kinematics, tangent: np.ndarray, rng: np.random.Generator, inexact: float, tol: Tolerance = DEFAULT_TOLERANCE) -> SecondOrder:
    """Second-order test of the first-order motions ``tangent`` at ``q = 0``.

    The forms projected on the cokernel are measured against the whole
    second-order term, so "zero" (the policy's rank threshold; more for geometry
    special only to ``inexact``) means small compared with how fast the loops
    open in general.  When the whole term is itself at round-off (the Sarrus
    linkage) every motion passes: round-off is not measured against round-off.
    The passing directions are searched by :func:`_unit_zero` from the basis
    directions and ``k + 2`` random starts drawn from ``rng``.
    """
    jac = kin.jacobian(np.zeros(kin.variable_count))
    n = kin.variable_count
    k = tangent.shape[1]
    u, _, _ = np.linalg.svd(jac / np.linalg.norm(kin.twists, axis=0), full_matrices=True)
    cokernel = u[:, n - k :]
    whole = np.einsum("ia,cij,jb->cab", tangent, kin.second_order_forms(np.eye(6 * kin.loop_count)), tangent)
    scale = float(np.abs(whole).max(initial=0.0))
    zero = max(tol.rank, INEXACT_ALLOWANCE * inexact)
    forms = kin.second_order_forms(cokernel) if cokernel.shape[1] else np.zeros((0, n, n))
    reduced = np.einsum("ia,cij,jb->cab", tangent, forms, tangent) / max(scale, 1e-300)
    if scale <= tol.rank or float(np.abs(reduced).max(initial=0.0)) <= zero:  # every first-order motion passes
        return SecondOrder(cokernel.shape[1], False, 0.0, np.zeros((n, 0)), tangent, np.zeros((0, k, k)), zero)
    starts = list(np.eye(k)) + list(rng.standard_normal((k + 2, k)))
    found: list[np.ndarray] = []
    least = np.inf
    for x0 in starts:
        x, value = _unit_zero(reduced, x0 / np.linalg.norm(x0), SECOND_ORDER_STEPS * k)
        least = min(least, value)
        if value <= zero and all(abs(float(x @ y)) < DISTINCT_LINES for y in found):
            found.append(x)
    directions = tangent @ np.array(found).T if found else np.zeros((n, 0))
    return SecondOrder(cokernel.shape[1], not found, 0.0 if found else least, directions, tangent, reduced, zero)


SECOND_ORDER_STEPS = 100
"""Gauss–Newton steps at most, per first-order freedom, of one search of :func:`_unit_zero`."""


def _unit_zero(forms: np.ndarray, x: np.ndarray, steps: int) -> tuple[np.ndarray, float]:
    """A unit ``x`` where the quadratic forms ``x @ forms[c] @ x`` vanish, by Gauss–Newton from the unit ``x``.

    The equations are the forms and ``|x|^2 = 1``, each step their minimum-norm
    least-squares linearised solution.  Returned: the unit iterate with the
    smallest largest form, and that value.  It stops at round-off, after
    :data:`~mobility.core.kinematics.CLOSE_STALLED` steps in a row that did not
    halve the smallest value (no zero near), or after ``steps`` steps.

    Examples
    --------
    >>> import numpy as np
    >>> x, value = _unit_zero(np.array([[[1.0, 0.0], [0.0, -1.0]]]), np.array([0.8, 0.6]), 100)   # x0^2 - x1^2 = 0
    >>> bool(abs(abs(x[0]) - abs(x[1])) < 1e-12), value < 1e-15
    (True, True)
    """
    def violation(u: np.ndarray) -> np.ndarray:
        return np.einsum("a,cab,b->c", u, forms, u)

    best, least = x, float(np.abs(violation(x)).max(initial=0.0))
    stalled = 0
    for _ in range(steps):
        residual = np.append(violation(x), x @ x - 1.0)
        jac = np.vstack([2.0 * np.einsum("cab,b->ca", forms, x), 2.0 * x])
        step = np.linalg.lstsq(jac, -residual, rcond=None)[0]
        x = x + step
        unit = x / np.linalg.norm(x)
        value = float(np.abs(violation(unit)).max(initial=0.0))
        stalled = 0 if value < 0.5 * least else stalled + 1
        if value < least:
            best, least = unit, value
        if not np.isfinite(value) or value <= ROUND_OFF or stalled >= STALLED or np.linalg.norm(step) <= SOLVER_STOP * np.linalg.norm(x):
            break
    return best, least
