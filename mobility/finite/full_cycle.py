"""Instantaneous or full-cycle: does the freedom found at a pose survive a finite motion?

The screw route (:func:`mobility.analyze`) counts first-order motions.  At a
singular pose some of them are infinitesimal only (a planar four-bar stretched
flat), or the pose is where branches of motion meet (a parallelogram four-bar
folded flat).  :func:`finite_mobility` decides it numerically, on the finite
kinematics of :mod:`mobility.core.kinematics`:

1. **First order.**  The loop-closure Jacobian at the given pose ``q = 0``
   gives the instantaneous mobility ``k`` and the tangent space ``N`` (joint
   rates that close every loop to first order).
2. **Second order.**  Along a first-order motion ``d = N u`` the residual grows
   like ``t^2/2 B(d, d)``; its part outside the Jacobian's range (the
   *cokernel*) cannot be corrected, so a finite motion exists in the direction
   ``u`` only if the quadratic forms ``u @ M_k @ u`` of
   :meth:`~mobility.core.kinematics.Kinematics.second_order_forms` all vanish.
   When no unit ``u`` makes them vanish, the pose cannot move at all (a
   certificate independent of the numerical moves below); the directions that
   do make them vanish are tried first.
3. **Moves.**  For each direction ``d`` (the basis of ``N`` and its negatives,
   sums of pairs, seeded random combinations, the second-order directions)
   and each step ``h`` of ``steps``: predict ``q = h d`` and re-close every
   loop by Newton with the progress fixed, ``d . q = h``.  A direction *moves*
   when the loops close (residual below
   :data:`~mobility.core.kinematics.CLOSURE_TOLERANCE`) at every step.  A motion
   that does not exist leaves a residual of order ``h^2`` that Newton cannot
   remove.
4. **Nearby poses.**  At the pose reached with the middle step, the loop
   Jacobian again gives the first-order mobility ``m1`` and tangent space
   ``N1`` (rank threshold ``1e-3`` times the step: Newton pins a freedom that
   is infinitesimal everywhere only to ``sqrt(residual)``, leaving spurious
   singular values far below the step).  Poses whose tangent spaces agree
   belong to the same branch; poses that are still as singular as the given
   one (``m1 = k``, e.g. moved along a singular surface) do not tell branches
   apart and are set aside when others exist.
5. **Branch dimension.**  From one pose of each branch, the same moves are
   made again along ``N1``: the number of independent directions that really
   move is the branch's finite mobility (it can be below ``m1`` where a
   freedom is infinitesimal everywhere).  The branch's end-effector DOF and
   pattern come from :func:`mobility.analyze` at that nearby pose (the screw
   route, so two routes meet); when the moves are fewer than ``m1``, from the
   branch's exact tangent at the given pose, the common null space of the
   second-order forms (approximated from the moves if the forms do not
   single it out, with a warning).
6. **Verdict.**  ``full-cycle`` (one branch with every instantaneous freedom;
   also a pose with no instantaneous freedom, nothing to follow),
   ``instantaneous-only`` (one branch, of lower dimension or end-effector DOF),
   ``cannot-move`` (no direction moves), ``bifurcation`` (two or more branches
   meet: a change point).

Every number is dimensionless: rotations in radians, translations over the
mechanism's characteristic length ``L``; residuals likewise.  The steps are
therefore the same for a file scaled by 1000 or moved rigidly, and so is the
verdict.

Examples
--------
>>> from mobility.core.model import Joint, Mechanism
>>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
>>> flat = Mechanism("flat four-bar", "ground", "coupler", (
...     R("A", "ground", "crank", (0, 0, 0)), R("B", "crank", "coupler", (1, 0, 0)),
...     R("C", "coupler", "rocker", (3, 0, 0)), R("D", "rocker", "ground", (6, 0, 0))))
>>> f = finite_mobility(flat)
>>> f.instantaneous_dof, f.verdict, f.full_cycle_dof, f.second_order.obstructed
(2, 'cannot-move', 0, True)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.linalg import qr

from ..core.analysis import analyze
from ..core.kinematics import CLOSURE_TOLERANCE, Kinematics, kinematics
from ..core.model import Mechanism
from ..core.result import Margin, Result, pattern_of
from ..core.screws import free_vector_subspace, span_and_reciprocal
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance

__all__ = [
    "VERDICTS",
    "DEFAULT_STEPS",
    "Probe",
    "Branch",
    "SecondOrder",
    "FiniteMobility",
    "finite_mobility",
    "finite_report",
]

VERDICTS = ("full-cycle", "instantaneous-only", "cannot-move", "bifurcation")
"""The possible verdicts of :func:`finite_mobility`."""

DEFAULT_STEPS = (1e-3, 1e-2, 5e-2)
"""Step sizes (joint-space distance: radians, lengths over ``L``)."""

_SAME_SUBSPACE = 0.95
"""Two tangent spaces of nearby poses belong to one branch when every principal
angle between them is below acos(0.95) (18 degrees): they differ by O(step)."""

_MOVING_RANK = 0.2
"""A direction counts among the independent moves when its singular value,
relative to the largest, exceeds this (moves are unit chords, exact to O(step))."""

_SECOND_ORDER_ZERO = 1e-8
"""A second-order form counts as zero below this, relative to the whole second-order term."""


@dataclass(frozen=True, eq=False)
class Probe:
    """One attempt to move from a pose along a direction.

    Attributes
    ----------
    source : str
        How the direction was chosen: ``"basis"``, ``"pair"``, ``"random"``,
        ``"second-order"``, or ``"local"`` (from a nearby pose).
    direction : ndarray, shape (n,)
        Unit joint-rate direction requested.
    steps : tuple of float
        Steps attempted (smallest first; stops at the first failure).
    residuals : tuple of float
        Residual left by Newton at each step (dimensionless).
    iterations : tuple of int
        Newton steps taken at each step size.
    moved : bool
        Closed at every step of the list.
    achieved : ndarray, shape (n,)
        Unit direction of the motion reached at the smallest step (the
        requested one slides onto the nearest branch).
    q : ndarray or None
        Joint variables reached with the probe step (the middle step), when closed.
    mobility : int or None
        First-order mobility of the whole mechanism there.
    dof : int or None
        First-order end-effector DOF there.
    margin : float or None
        Smallest kept singular value of the loop Jacobian there (relative).
    tangent : ndarray or None
        Orthonormal basis of the first-order motions there.
    """

    source: str
    direction: np.ndarray
    steps: tuple[float, ...]
    residuals: tuple[float, ...]
    iterations: tuple[int, ...]
    moved: bool
    achieved: np.ndarray | None = None
    q: np.ndarray | None = None
    mobility: int | None = None
    dof: int | None = None
    margin: float | None = None
    tangent: np.ndarray | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON form (without the joint-variable vectors)."""
        return {
            "source": self.source,
            "steps": list(self.steps),
            "residuals": list(self.residuals),
            "iterations": list(self.iterations),
            "moved": self.moved,
            "mobility_nearby": self.mobility,
            "dof_nearby": self.dof,
            "margin_nearby": self.margin,
        }


@dataclass(frozen=True, eq=False)
class Branch:
    """A branch of finite motion through the given pose.

    Attributes
    ----------
    dimension : int
        Its finite mobility (independent directions that move from a pose on it).
    dof : int
        End-effector DOF along it.
    pattern : str
        End-effector motion pattern along it (``{nT}T{nR}R``).
    mobility_nearby : int
        First-order mobility at the pose examined (above ``dimension`` when
        some freedom there is infinitesimal only).
    analysis : Result
        :func:`mobility.analyze` of the mechanism at that nearby pose.
    tangent : ndarray, shape (n, dimension)
        Orthonormal joint-rate basis of the branch at the nearby pose.
    q : ndarray, shape (n,)
        Joint variables of the nearby pose.
    distance : float
        Its distance from the given pose (joint space).
    probes : tuple of int
        Indices (in :attr:`FiniteMobility.probes`) of the moves that reached it.
    local : tuple of Probe
        The moves made from the nearby pose.
    source : str
        Where ``dof``, ``pattern`` and ``tangent`` come from: ``"nearby pose"``
        (the screw route at a regular pose of the branch), ``"second-order forms"``
        (the common null space of the second-order forms at the given pose,
        for a branch along which a freedom is infinitesimal everywhere), or
        ``"moves (approximate)"``.
    """

    dimension: int
    dof: int
    pattern: str
    mobility_nearby: int
    analysis: Result
    tangent: np.ndarray
    q: np.ndarray
    distance: float
    probes: tuple[int, ...]
    local: tuple[Probe, ...]
    source: str = "nearby pose"

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {
            "source": self.source,
            "dimension": self.dimension,
            "dof": self.dof,
            "pattern": self.pattern,
            "mobility_nearby": self.mobility_nearby,
            "dof_nearby": self.analysis.dof,
            "pattern_nearby": self.analysis.pattern,
            "margin_nearby": self.analysis.margin.smallest_kept,
            "distance": self.distance,
            "probes": list(self.probes),
            "local_moves": [p.to_dict() for p in self.local],
        }


@dataclass(frozen=True, eq=False)
class SecondOrder:
    """The second-order test at the given pose.

    Attributes
    ----------
    cokernel : int
        Loop equations that are dependent at first order (``6 * loops - rank``),
        whose second-order part cannot be corrected.
    obstructed : bool
        No unit first-order motion makes every second-order form vanish: the
        pose cannot move (to any order).
    least_violation : float
        Over unit first-order motions ``u``, the smallest value of the largest
        ``|u @ M_k @ u|``, relative to the whole second-order term (0 when some
        direction passes).
    directions : ndarray, shape (n, c)
        Unit joint-rate directions that pass (one per line found); empty when
        every form vanishes identically (every first-order motion passes).
    basis : ndarray, shape (n, k)
        The orthonormal basis of the first-order motions the forms are written in.
    forms : ndarray, shape (cokernel, k, k)
        The forms ``u @ forms[c] @ u`` in that basis, relative to the whole
        second-order term.
    zero : float
        Below this a form's value counts as zero.
    """

    cokernel: int
    obstructed: bool
    least_violation: float
    directions: np.ndarray
    basis: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    forms: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 0)))
    zero: float = _SECOND_ORDER_ZERO

    def isotropic_kernel(self) -> np.ndarray:
        """Joint-rate basis of the first-order motions on which every form vanishes with all its polarisations.

        The common null space of the forms: where the forms are semidefinite
        (a freedom infinitesimal along a whole branch, ``x^2 = 0``), it is the
        tangent space of the branch, exactly.
        """
        k = self.basis.shape[1]
        if self.forms.shape[0] == 0:
            return self.basis
        stacked = self.forms.reshape(-1, k)
        _, s, vt = np.linalg.svd(stacked, full_matrices=True)
        rank = int(np.count_nonzero(s > self.zero * max(1.0, float(s[0]) if s.size else 1.0)))
        return self.basis @ vt[rank:].T

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {
            "cokernel": self.cokernel,
            "obstructed": self.obstructed,
            "least_violation": self.least_violation,
            "directions_found": int(self.directions.shape[1]),
        }


@dataclass(frozen=True, eq=False)
class FiniteMobility:
    """Instantaneous and full-cycle mobility of a mechanism at its pose.

    Attributes
    ----------
    name : str
    verdict : str
        One of :data:`VERDICTS`.
    explanation : str
        One paragraph with the numbers behind the verdict.
    instantaneous_dof, instantaneous_pattern, instantaneous_mobility
        From :func:`mobility.analyze` at the given pose.
    full_cycle_dof, full_cycle_pattern, full_cycle_mobility
        Along the finite motion: the largest over the branches (patterns of
        branches of equal DOF joined by ``" | "``); 0, ``"0"`` and 0 when it
        cannot move.
    margin : Margin
        Singular-value margin of the instantaneous analysis.
    branches : tuple of Branch
    probes : tuple of Probe
        The moves from the given pose.
    steps : tuple of float
        Step sizes used (dimensionless).
    second_order : SecondOrder or None
        ``None`` when there is no first-order motion or no loop.
    warnings : tuple of str
    """

    name: str
    verdict: str
    explanation: str
    instantaneous_dof: int
    instantaneous_pattern: str
    instantaneous_mobility: int
    full_cycle_dof: int
    full_cycle_pattern: str
    full_cycle_mobility: int
    margin: Margin
    branches: tuple[Branch, ...]
    probes: tuple[Probe, ...]
    steps: tuple[float, ...]
    second_order: SecondOrder | None
    warnings: tuple[str, ...] = field(default=())

    @property
    def moved(self) -> int:
        """Number of directions from the given pose that moved."""
        return sum(p.moved for p in self.probes)

    @property
    def instantaneous_only_dof(self) -> int:
        """End-effector DOF found by the screw route that no finite motion has (``instantaneous - full-cycle``, at least 0)."""
        return max(0, self.instantaneous_dof - self.full_cycle_dof)

    @property
    def instantaneous_only_mobility(self) -> int:
        """Freedoms of the whole mechanism that are infinitesimal only (``instantaneous - full-cycle`` mobility)."""
        return max(0, self.instantaneous_mobility - self.full_cycle_mobility)

    def expected_values(self) -> dict[str, Any]:
        """The values that an ``expected`` block's finite keys are compared with.

        Examples
        --------
        >>> from mobility.core.model import Joint, Mechanism
        >>> m = Mechanism("slide", "g", "s", (Joint("p", "P", ("g", "s"), axis=(1, 0, 0)),))
        >>> finite_mobility(m).expected_values()
        {'full_cycle_dof': 1, 'full_cycle_mobility': 1, 'finite_verdict': 'full-cycle'}
        """
        return {"full_cycle_dof": self.full_cycle_dof, "full_cycle_mobility": self.full_cycle_mobility, "finite_verdict": self.verdict}

    def to_dict(self) -> dict[str, Any]:
        """JSON form (the ``finite`` object of ``mobility analyze --finite --json``)."""
        return {
            "verdict": self.verdict,
            "explanation": self.explanation,
            "instantaneous": {"dof": self.instantaneous_dof, "pattern": self.instantaneous_pattern, "mobility": self.instantaneous_mobility},
            "full_cycle": {"dof": self.full_cycle_dof, "pattern": self.full_cycle_pattern, "mobility": self.full_cycle_mobility},
            "instantaneous_only": {"dof": self.instantaneous_only_dof, "mobility": self.instantaneous_only_mobility},
            "margin": self.margin.to_dict(),
            "steps": list(self.steps),
            "directions_tried": len(self.probes),
            "directions_moved": self.moved,
            "second_order": None if self.second_order is None else self.second_order.to_dict(),
            "branches": [b.to_dict() for b in self.branches],
            "probes": [p.to_dict() for p in self.probes],
            "warnings": list(self.warnings),
        }


# ---------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------


def _canonical_basis(null: np.ndarray) -> np.ndarray:
    """An orthonormal basis of ``span(null)`` that depends only on the subspace.

    Pivoted QR of the projector (frame- and scale-free, since joint variables
    are), each column's largest entry made positive.
    """
    k = null.shape[1]
    if k == 0:
        return null
    proj = null @ null.T
    qmat, _, _ = qr(proj, pivoting=True)
    basis = qmat[:, :k]
    signs = np.sign(basis[np.argmax(np.abs(basis), axis=0), np.arange(k)])
    return basis * signs


def _directions(basis: np.ndarray, rng: np.random.Generator, *, randoms: int, pairs: bool) -> list[tuple[str, np.ndarray]]:
    """Probe directions in the span of ``basis``: +-basis, sums of pairs, random combinations."""
    k = basis.shape[1]
    out: list[tuple[str, np.ndarray]] = []
    for i in range(k):
        out.append(("basis", basis[:, i]))
        out.append(("basis", -basis[:, i]))
    if pairs:
        for i in range(k):
            for j in range(i + 1, k):
                for s in (1.0, -1.0):
                    out.append(("pair", (basis[:, i] + s * basis[:, j]) / np.sqrt(2.0)))
    for _ in range(randoms):
        u = rng.standard_normal(k)
        out.append(("random", basis @ (u / np.linalg.norm(u))))
    return out


def _first_order(kin: Kinematics, q: np.ndarray, tol: Tolerance) -> tuple[int, np.ndarray, float, int, float]:
    """Mobility, tangent basis, smallest kept and largest dropped singular values, end-effector DOF at ``q``."""
    decision, null = kin.rank_decision(q, tol)
    ee = kin.end_effector_jacobian(q) @ null
    dof = span_and_reciprocal(ee / max(1.0, float(np.abs(ee).max(initial=0.0))), tol).dim if null.shape[1] else 0
    return null.shape[1], null, decision.smallest_kept, dof, decision.largest_dropped


def _closure_tolerance(distance: float, inexact: float) -> float:
    """Residual accepted as closed at ``distance`` (joint space) from the given pose.

    Round-off, or, when the given geometry is special only to ``inexact``
    (the largest singular value the rank decision dropped, relative), the
    first-order residual ``~ inexact * distance`` that such geometry leaves:
    the finite test then treats the geometry as exact, as the rank decision
    did.  A motion that does not exist leaves a residual of order ``h^2``.
    """
    return max(CLOSURE_TOLERANCE, 10.0 * inexact * distance)


def _probe(
    kin: Kinematics,
    q0: np.ndarray,
    source: str,
    d: np.ndarray,
    steps: tuple[float, ...],
    probe_step: float,
    tol: Tolerance,
    *,
    inexact: float = 0.0,
    first_order: bool = True,
    nearby_tol: Tolerance | None = None,
) -> Probe:
    """Move from ``q0`` along ``d`` with each step (smallest first), re-closing the loops."""
    offset = float(np.linalg.norm(q0))  # distance of the start from the given pose
    residuals, iterations, done = [], [], []
    achieved = None
    reached = None
    for h in steps:
        target = float(d @ q0) + h
        closure = kin.close(q0 + h * d, constraints=(d[None, :], np.array([target])), tol=_closure_tolerance(offset + h, inexact), max_move=10.0 * h)
        residuals.append(closure.residual)
        iterations.append(closure.iterations)
        done.append(h)
        if not closure.converged:
            break
        chord = closure.q - q0
        if achieved is None:
            achieved = chord / np.linalg.norm(chord)
        if h == probe_step:
            reached = closure.q
    moved = len(residuals) == len(steps) and residuals[-1] <= _closure_tolerance(offset + steps[-1], inexact)
    if not moved:
        return Probe(source, d, tuple(done), tuple(residuals), tuple(iterations), False, achieved)
    mobility = dof = margin = tangent = None
    if first_order and reached is not None:
        mobility, tangent, margin, dof, _ = _first_order(kin, reached, nearby_tol or tol)
    return Probe(source, d, tuple(done), tuple(residuals), tuple(iterations), True, achieved, reached, mobility, dof, margin, tangent)


def _second_order(kin: Kinematics, tangent: np.ndarray, rng: np.random.Generator, inexact: float) -> SecondOrder:
    """Second-order test of the first-order motions ``tangent`` at ``q = 0``.

    The forms projected on the cokernel are measured against the whole
    second-order term (every residual component), so "zero" means small
    compared with how fast the loops open in general; geometry that is special
    only to ``inexact`` is allowed forms of that relative size.
    """
    from scipy.optimize import least_squares  # slow to import; needed only here

    jac = kin.jacobian(np.zeros(kin.variable_count))
    n = kin.variable_count
    k = tangent.shape[1]
    u, _, _ = np.linalg.svd(jac / np.linalg.norm(kin.twists, axis=0), full_matrices=True)
    cokernel = u[:, n - k :]
    whole = np.einsum("ia,cij,jb->cab", tangent, kin.second_order_forms(np.eye(6 * kin.loop_count)), tangent)
    scale = float(np.abs(whole).max(initial=0.0))
    zero = max(_SECOND_ORDER_ZERO, 10.0 * inexact)
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
    for x0 in starts:
        sol = least_squares(residuals, x0 / np.linalg.norm(x0), jac=jacobian, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=100 * k)
        x = sol.x / np.linalg.norm(sol.x)
        value = float(np.max(np.abs(violation(x))))
        least = min(least, value)
        if value <= zero and all(abs(float(x @ y)) < 0.999 for y in found):
            found.append(x)
    directions = tangent @ np.array(found).T if found else np.zeros((n, 0))
    return SecondOrder(cokernel.shape[1], not found, 0.0 if found else least, directions, tangent, reduced, zero)


def _same_subspace(a: np.ndarray, b: np.ndarray) -> bool:
    if a.shape[1] != b.shape[1]:
        return False
    if a.shape[1] == 0:
        return True
    return float(np.linalg.svd(a.T @ b, compute_uv=False).min()) >= _SAME_SUBSPACE


def _rank_of_moves(chords: list[np.ndarray]) -> tuple[int, np.ndarray]:
    """Independent directions among unit chords, and an orthonormal basis of them."""
    if not chords:
        return 0, np.zeros((0, 0))
    m = np.array(chords).T
    u, s, _ = np.linalg.svd(m, full_matrices=False)
    r = int(np.count_nonzero(s > _MOVING_RANK * s[0]))
    return r, u[:, :r]


def _tangent_from_second_order(second: SecondOrder | None, chords: list[np.ndarray], dim: int) -> tuple[np.ndarray | None, str]:
    """The exact tangent of a branch at the given pose, if the second-order forms single it out.

    It is the common null space of the forms when that has the branch's
    dimension and holds the moves that reached the branch (to their O(step)).
    """
    if second is None or second.forms.shape[0] == 0:
        return None, ""
    kernel = second.isotropic_kernel()
    if kernel.shape[1] != dim or not chords:
        return None, ""
    off = max(float(np.linalg.norm(c - kernel @ (kernel.T @ c))) for c in chords)
    return (kernel, "second-order forms") if off < _MOVING_RANK else (None, "")


def _describe(b: Branch) -> str:
    """One branch in words, with the numbers behind it."""
    text = f"dimension {b.dimension}, end-effector DOF {b.dof} ({b.pattern})"
    if b.source == "nearby pose":
        return text + f"; at a pose {b.distance:.3g} away on it, first-order mobility {b.mobility_nearby} and DOF {b.analysis.dof} ({b.analysis.pattern})"
    text += f", from the {b.source} at the given pose" if b.source == "second-order forms" else f", from the {b.source}"
    if b.mobility_nearby > b.dimension:
        text += f"; at a pose {b.distance:.3g} away on it the first-order mobility is still {b.mobility_nearby} (a freedom infinitesimal all along)"
    return text


def _pattern(twists: np.ndarray, tol: Tolerance) -> tuple[int, str]:
    """DOF and pattern of a set of end-effector twists (normalised coordinates, columns)."""
    if twists.shape[1] == 0:
        return 0, "0"
    span = span_and_reciprocal(twists / max(1.0, float(np.abs(twists).max())), tol)
    free, _, _ = free_vector_subspace(span.basis, tol)
    return span.dim, pattern_of(free.shape[1], span.dim - free.shape[1])


# ---------------------------------------------------------------------------
# the decision
# ---------------------------------------------------------------------------


def finite_mobility(
    mechanism: Mechanism,
    *,
    steps: tuple[float, ...] = DEFAULT_STEPS,
    randoms: int | None = None,
    seed: int = 0,
    tol: Tolerance = DEFAULT_TOLERANCE,
) -> FiniteMobility:
    """Decide whether the instantaneous freedom of ``mechanism`` survives a finite motion.

    Parameters
    ----------
    mechanism : Mechanism
    steps : tuple of float
        Increasing step sizes, dimensionless (radians; lengths over the
        characteristic length).  The middle one (or the only one) is the
        *probe step*: nearby poses are examined there.
    randoms : int, optional
        Random combinations of the tangent basis to try (default ``2 k + 2``,
        at most 14, for ``k`` instantaneous freedoms).
    seed : int
        Seed of the random directions (results are reproducible).
    tol : Tolerance
        Rank policy, as for :func:`mobility.analyze`.

    Returns
    -------
    FiniteMobility
    """
    steps = tuple(sorted(float(h) for h in steps))
    if not steps or steps[0] <= 0.0:
        raise ValueError("steps must be positive")
    probe_step = steps[len(steps) // 2]
    rng = np.random.default_rng(seed)
    instant = analyze(mechanism, tol=tol)
    kin = kinematics(mechanism)
    n = kin.variable_count
    q0 = np.zeros(n)
    k, null, _, _, inexact = _first_order(kin, q0, tol)
    warnings: list[str] = []
    if k != instant.mobility:
        warnings.append(f"the loop-closure route finds mobility {k}, the screw route {instant.mobility}: the pose is close to a rank decision")
    common = dict(
        name=mechanism.name,
        instantaneous_dof=instant.dof,
        instantaneous_pattern=instant.pattern,
        instantaneous_mobility=instant.mobility,
        margin=instant.margin,
        steps=steps,
    )
    if k == 0:
        text = (
            "The pose has no first-order motion (mobility 0), so there is nothing to follow: "
            "the DOF 0 found by the screw route holds for finite motion too (a structure)."
        )
        return FiniteMobility(verdict="full-cycle", explanation=text, full_cycle_dof=0, full_cycle_pattern="0", full_cycle_mobility=0,
                              branches=(), probes=(), second_order=None, warnings=tuple(warnings), **common)

    basis = _canonical_basis(null)
    second = _second_order(kin, basis, rng, inexact) if kin.loop_count else None
    count = min(2 * k + 2, 14) if randoms is None else randoms
    candidates = _directions(basis, rng, randoms=count, pairs=k <= 3)
    if second is not None:
        for d in second.directions.T[:k]:
            candidates += [("second-order", d), ("second-order", -d)]
    # A pose reached by Newton is exact only to ~sqrt(residual) along a freedom that is infinitesimal
    # everywhere (x^2 = 0), which leaves singular values ~1e-7 that are not real; a pose a probe step
    # from a singular one has its smallest singular value ~ step.  Nearby poses are judged in between.
    nearby_tol = Tolerance(rank=max(tol.rank, 1e-3 * probe_step), near_singular=max(tol.near_singular, 1e-2 * probe_step), inexact=tol.inexact)
    probes = tuple(_probe(kin, q0, source, d, steps, probe_step, tol, inexact=inexact, nearby_tol=nearby_tol) for source, d in candidates)
    moved = [i for i, p in enumerate(probes) if p.moved]

    # group the nearby poses by their tangent spaces
    groups: list[dict[str, Any]] = []
    for i in sorted(moved, key=lambda i: (probes[i].mobility, -(probes[i].margin or 0.0))):
        p = probes[i]
        tangent = p.tangent
        for g in groups:
            if _same_subspace(g["tangent"], tangent):
                g["probes"].append(i)
                break
        else:
            groups.append({"tangent": tangent, "probes": [i], "mobility": p.mobility})
    still_singular = [g for g in groups if g["mobility"] >= k]
    regular = [g for g in groups if g["mobility"] < k]
    if regular and still_singular:
        warnings.append(
            f"{sum(len(g['probes']) for g in still_singular)} move(s) reached poses as singular as the given one "
            f"(mobility {k}: a singular locus through the pose); they are not counted as a branch"
        )
    kept = regular or still_singular

    branches = []
    local_steps = (steps[0], probe_step / 2.0) if len(steps) > 1 else steps
    for g in kept:
        rep = probes[g["probes"][0]]
        m1, n1 = rep.mobility, rep.tangent
        local = tuple(
            _probe(kin, rep.q, "local", d, local_steps, local_steps[-1], tol, inexact=inexact, first_order=False)
            for _, d in _directions(_canonical_basis(n1), rng, randoms=2, pairs=False)
        )
        dim, moves = _rank_of_moves([p.achieved for p in local if p.moved])
        moved_mechanism = kin.mechanism_at(rep.q)
        nearby = analyze(moved_mechanism, tol=tol)
        if dim == m1:
            # a regular point of its branch: the screw route there gives the branch's DOF and pattern
            tangent, source = n1, "nearby pose"
            dof, pattern = nearby.dof, nearby.pattern
        else:
            # fewer moves than first-order motions along the whole branch: its tangent at the given
            # pose is where the second-order forms vanish identically, when they single it out
            tangent, source = _tangent_from_second_order(second, [probes[i].achieved for i in g["probes"]], dim)
            if tangent is not None:
                dof, pattern = _pattern(kin.end_effector_jacobian(q0) @ tangent, tol)  # exact, at the given pose
            else:
                tangent, source = np.linalg.qr(n1 @ (n1.T @ moves))[0] if dim else np.zeros((n, 0)), "moves (approximate)"
                dof, pattern = _pattern(kin.end_effector_jacobian(rep.q) @ tangent, nearby_tol)
                warnings.append(f"the pattern of a branch of dimension {dim} comes from finite moves only (approximate)")
        branches.append(Branch(dim, dof, pattern, m1, nearby, tangent, rep.q, float(np.linalg.norm(rep.q)), tuple(sorted(g["probes"])), local, source))
    branches = [b for b in branches if b.dimension > 0]
    branches.sort(key=lambda b: (-b.dimension, -b.dof))
    tried = len(probes)
    worst = max((p.residuals[-1] for p in probes if p.moved), default=0.0)
    if not branches:
        smallest = min((p.residuals[0] for p in probes), default=float("nan"))
        if second is not None and second.obstructed:
            order2 = (
                f" The second-order test agrees: no first-order motion keeps the {second.cokernel} dependent loop equation(s) "
                f"closed to second order (least violation {second.least_violation:.2e} relative)."
            )
        elif second is not None:
            order2 = " Some directions pass the second-order test, yet no move along them closes: the obstruction is of higher order."
        else:
            order2 = ""
        text = (
            f"The screw route finds {k} first-order motion(s) (end-effector DOF {instant.dof}), but none is a finite motion: "
            f"in {tried} directions, Newton does not re-close the loops at every step {', '.join(f'{h:g}' for h in steps)} "
            f"(smallest residual left at step {steps[0]:g}: {smallest:.2e}; closed means below {CLOSURE_TOLERANCE:.0e}).{order2} "
            "The pose cannot move at all."
        )
        return FiniteMobility(verdict="cannot-move", explanation=text, full_cycle_dof=0, full_cycle_pattern="0", full_cycle_mobility=0,
                              branches=(), probes=probes, second_order=second, warnings=tuple(warnings), **common)

    top = branches[0]
    full_dof = max(b.dof for b in branches)
    patterns = list(dict.fromkeys(b.pattern for b in branches if b.dof == full_dof))
    summary = "; ".join(f"branch {i + 1}: {_describe(b)}" for i, b in enumerate(branches))
    numbers = (
        f"{len(moved)} of {tried} directions moved at steps {', '.join(f'{h:g}' for h in steps)} "
        f"(loops re-closed to {worst:.1e} or better)"
    )
    if len(branches) > 1:
        verdict = "bifurcation"
        text = (
            f"{len(branches)} branches of finite motion meet at this pose (a bifurcation, or change point): {summary}. "
            f"The {k} first-order motion(s) of the screw route are the union of their tangents; {numbers}. "
            f"No single motion has all {k} freedoms: each branch has at most {top.dimension}."
        )
    elif top.dimension == k and top.dof == instant.dof:
        verdict = "full-cycle"
        text = f"Every first-order motion is a finite one: {numbers}; {summary}. The instantaneous answer holds for finite motion."
    elif top.dimension == k and top.dof > instant.dof:
        verdict = "full-cycle"
        text = (
            f"Every first-order motion is a finite one ({numbers}; {summary}), and the end effector has more DOF at nearby "
            f"poses ({top.dof}) than at this one ({instant.dof}): the pose is singular for the end effector, not for the mechanism."
        )
    else:
        verdict = "instantaneous-only"
        text = (
            f"The finite motion has {top.dimension} of the {k} first-order freedom(s) and end-effector DOF {top.dof} "
            f"({top.pattern}) instead of {instant.dof} ({instant.pattern}): {numbers}; {summary}."
        )
        if second is not None and second.directions.shape[1]:
            text += f" Second order: {second.directions.shape[1]} direction line(s) pass."
    if verdict != "bifurcation" and len(patterns) > 1:
        warnings.append("branches of equal DOF with different patterns")
    return FiniteMobility(
        verdict=verdict,
        explanation=text,
        full_cycle_dof=full_dof,
        full_cycle_pattern=" | ".join(patterns),
        full_cycle_mobility=top.dimension,
        branches=tuple(branches),
        probes=probes,
        second_order=second,
        warnings=tuple(warnings),
        **common,
    )


def finite_report(f: FiniteMobility) -> str:
    """The text section printed by ``mobility analyze --finite``.

    Examples
    --------
    >>> from mobility.core.model import Joint, Mechanism
    >>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
    >>> m = Mechanism("four-bar", "g", "c", (R("A", "g", "k", (0, 0, 0)), R("B", "k", "c", (1, 2, 0)),
    ...                                        R("C", "c", "r", (4, 2.5, 0)), R("D", "r", "g", (5, 0, 0))))
    >>> print(finite_report(finite_mobility(m)).splitlines()[1])
      verdict: full-cycle
    """
    out = [
        "finite motion (instantaneous or full-cycle):",
        f"  verdict: {f.verdict}",
        f"  instantaneous: DOF {f.instantaneous_dof} ({f.instantaneous_pattern}), mobility {f.instantaneous_mobility}"
        f"   (margin: smallest kept singular value {f.margin.smallest_kept:.2e})",
        f"  full-cycle:    DOF {f.full_cycle_dof} ({f.full_cycle_pattern}), mobility {f.full_cycle_mobility}",
    ]
    if f.instantaneous_only_dof or f.instantaneous_only_mobility:
        out.append(f"  instantaneous only: {f.instantaneous_only_dof} end-effector DOF, {f.instantaneous_only_mobility} freedom(s) of the mechanism")
    if f.probes:
        out.append(
            f"  moves: {f.moved} of {len(f.probes)} directions re-closed at every step ({', '.join(f'{h:g}' for h in f.steps)}; "
            f"radians, lengths over the characteristic length)"
        )
    if f.second_order is not None:
        so = f.second_order
        if so.obstructed:
            text = f"obstructed (least violation {so.least_violation:.2e}, relative): no direction survives"
        elif so.directions.shape[1]:
            text = f"{so.directions.shape[1]} direction line(s) survive"
        else:
            text = "every first-order motion survives"
        out.append(f"  second order: {so.cokernel} dependent loop equation(s); {text}")
    for i, b in enumerate(f.branches):
        out.append(f"  branch {i + 1}: {_describe(b)}")
    out.append("  " + f.explanation)
    out += [f"  warning: {w}" for w in f.warnings]
    return "\n".join(out)
