"""First and second order: which motions the loop equations allow at a pose, to first and to second order.

* :func:`first_order`: the rank of the loop Jacobian at a pose (the tolerance
  policy), its null space (the tangent space: joint rates that close every
  loop to first order) and the end-effector DOF along it.
* :func:`second_order`: along a first-order motion ``d = N u`` the residual
  grows like ``t^2/2 B(d, d)``; its part outside the Jacobian's range (the
  *cokernel*) cannot be corrected, so a finite motion exists in the direction
  ``u`` only if the quadratic forms ``u @ M_k @ u`` of
  :meth:`~mobility.core.kinematics.Kinematics.second_order_forms` all vanish.
  When no unit ``u`` makes them vanish, the pose cannot move at all.
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
from scipy.linalg import qr

from ..core.kinematics import Kinematics
from ..core.screws import motion_pattern, span_and_reciprocal
from ..core.tolerance import DEFAULT_TOLERANCE, SOLVER_STOP, Tolerance
from .parameters import DISTINCT_LINES, INEXACT_ALLOWANCE
from .results import SecondOrder

__all__ = ["FirstOrder", "first_order", "second_order", "canonical_basis", "end_effector_pattern"]


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
    decision, null = kin.rank_decision(q, tol)
    dof = span_and_reciprocal(_scaled(kin.end_effector_jacobian(q) @ null), tol).dim if null.shape[1] else 0
    return FirstOrder(null.shape[1], null, decision.smallest_kept, decision.largest_dropped, dof)


def _scaled(twists: np.ndarray) -> np.ndarray:
    """Twists divided by their largest entry when it exceeds 1 (the rank policy's scale)."""
    return twists / max(1.0, float(np.abs(twists).max(initial=0.0)))


def canonical_basis(null: np.ndarray) -> np.ndarray:
    """An orthonormal basis of ``span(null)`` that depends only on the subspace.

    Pivoted QR of the projector (frame- and scale-free, since joint variables
    are), each column's largest entry made positive.

    Examples
    --------
    >>> import numpy as np
    >>> c = np.sqrt(0.5)
    >>> a = canonical_basis(np.array([[c], [-c], [0.0]]))
    >>> bool(np.allclose(a, canonical_basis(-a)))
    True
    """
    k = null.shape[1]
    if k == 0:
        return null
    proj = null @ null.T
    qmat, _, _ = qr(proj, pivoting=True)
    basis = qmat[:, :k]
    signs = np.sign(basis[np.argmax(np.abs(basis), axis=0), np.arange(k)])
    return basis * signs


def second_order(kin: Kinematics, tangent: np.ndarray, rng: np.random.Generator, inexact: float, tol: Tolerance = DEFAULT_TOLERANCE) -> SecondOrder:
    """Second-order test of the first-order motions ``tangent`` at ``q = 0``.

    The forms projected on the cokernel are measured against the whole
    second-order term (every residual component), so "zero" (the policy's
    rank threshold) means small compared with how fast the loops open in
    general; geometry that is special only to ``inexact`` is allowed forms of
    that relative size.  The directions where every form vanishes are searched
    by Levenberg–Marquardt from the basis directions and ``k + 2`` random
    starts drawn from ``rng``.
    """
    from scipy.optimize import least_squares  # slow to import; needed only here

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
    if float(np.abs(reduced).max(initial=0.0)) <= zero:  # every first-order motion passes
        return SecondOrder(cokernel.shape[1], False, 0.0, np.zeros((n, 0)), tangent, np.zeros((0, k, k)), zero)
    c = reduced.shape[0]
    pad = max(0, k - c - 1)  # Levenberg-Marquardt wants as many residuals as unknowns

    def violation(x: np.ndarray) -> np.ndarray:
        return np.einsum("a,cab,b->c", x, reduced, x)

    def residuals(x: np.ndarray) -> np.ndarray:  # the forms, and |x| = 1
        return np.concatenate([violation(x), [x @ x - 1.0], np.zeros(pad)])

    def jacobian(x: np.ndarray) -> np.ndarray:
        return np.vstack([2.0 * np.einsum("cab,b->ca", reduced, x), 2.0 * x[None, :], np.zeros((pad, k))])

    starts = list(np.eye(k)) + list(rng.standard_normal((k + 2, k)))
    found: list[np.ndarray] = []
    least = np.inf
    precision = SOLVER_STOP
    for x0 in starts:
        sol = least_squares(residuals, x0 / np.linalg.norm(x0), jac=jacobian, method="lm", xtol=precision, ftol=precision, gtol=precision, max_nfev=100 * k)
        x = sol.x / np.linalg.norm(sol.x)
        value = float(np.max(np.abs(violation(x))))
        least = min(least, value)
        if value <= zero and all(abs(float(x @ y)) < DISTINCT_LINES for y in found):
            found.append(x)
    directions = tangent @ np.array(found).T if found else np.zeros((n, 0))
    return SecondOrder(cokernel.shape[1], not found, 0.0 if found else least, directions, tangent, reduced, zero)
