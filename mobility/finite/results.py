"""What :func:`~mobility.finite.full_cycle.finite_mobility` finds: frozen results.

:class:`FiniteMobility` is the answer (the verdict, the instantaneous and
full-cycle DOF, with the numbers behind them); :class:`Branch`,
:class:`Probe` and :class:`SecondOrder` record how it was reached.  Each has a
``to_dict`` JSON form (the ``finite`` object of ``mobility analyze --finite
--json``); the text is formatted by :mod:`mobility.report.finite`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core.frozen import ReadOnlyArrays
from ..core.result import Margin, Result
from ..core.tolerance import DEFAULT_TOLERANCE

__all__ = ["VERDICTS", "Probe", "Branch", "SecondOrder", "FiniteMobility"]

VERDICTS = ("full-cycle", "instantaneous-only", "cannot-move", "bifurcation")
"""The possible verdicts of :func:`~mobility.finite.full_cycle.finite_mobility`."""


@dataclass(frozen=True, eq=False)
class Probe(ReadOnlyArrays):
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
        return {"source": self.source, "steps": list(self.steps), "residuals": list(self.residuals), "iterations": list(self.iterations),
                "moved": self.moved, "mobility_nearby": self.mobility, "dof_nearby": self.dof, "margin_nearby": self.margin}


@dataclass(frozen=True, eq=False)
class Branch(ReadOnlyArrays):
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

    def describe(self) -> str:
        """The branch in words, with the numbers behind it (used in explanations and reports)."""
        text = f"dimension {self.dimension}, end-effector DOF {self.dof} ({self.pattern})"
        if self.source == "nearby pose":
            return text + (f"; at a pose {self.distance:.3g} away on it, first-order mobility {self.mobility_nearby} "
                           f"and DOF {self.analysis.dof} ({self.analysis.pattern})")
        text += f", from the {self.source} at the given pose" if self.source == "second-order forms" else f", from the {self.source}"
        if self.mobility_nearby > self.dimension:
            text += f"; at a pose {self.distance:.3g} away on it the first-order mobility is still {self.mobility_nearby} (a freedom infinitesimal all along)"
        return text

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {"source": self.source, "dimension": self.dimension, "dof": self.dof, "pattern": self.pattern,
                "mobility_nearby": self.mobility_nearby, "dof_nearby": self.analysis.dof, "pattern_nearby": self.analysis.pattern,
                "margin_nearby": self.analysis.margin.smallest_kept, "distance": self.distance, "probes": list(self.probes),
                "local_moves": [p.to_dict() for p in self.local]}


@dataclass(frozen=True, eq=False)
class SecondOrder(ReadOnlyArrays):
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
        Below this a form's value counts as zero: the policy's rank threshold,
        or more for geometry special only to within it
        (:data:`~mobility.finite.parameters.INEXACT_ALLOWANCE`).
    """

    cokernel: int
    obstructed: bool
    least_violation: float
    directions: np.ndarray
    basis: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    forms: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 0)))
    zero: float = DEFAULT_TOLERANCE.rank

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
        rank = int(np.count_nonzero(s > self.zero * max(1.0, float(s[0]) if s.size else 1.0)))  # decide_rank's rule, threshold zero
        return self.basis @ vt[rank:].T

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {"cokernel": self.cokernel, "obstructed": self.obstructed, "least_violation": self.least_violation,
                "directions_found": int(self.directions.shape[1])}


@dataclass(frozen=True, eq=False)
class FiniteMobility(ReadOnlyArrays):
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
        >>> from mobility.finite import finite_mobility
        >>> m = Mechanism("slide", "g", "s", (Joint("p", "P", ("g", "s"), axis=(1, 0, 0)),))
        >>> finite_mobility(m).expected_values()
        {'full_cycle_dof': 1, 'full_cycle_mobility': 1, 'finite_verdict': 'full-cycle'}
        """
        return {"full_cycle_dof": self.full_cycle_dof, "full_cycle_mobility": self.full_cycle_mobility, "finite_verdict": self.verdict}

    def to_dict(self) -> dict[str, Any]:
        """JSON form (the ``finite`` object of ``mobility analyze --finite --json``)."""
        return {
            "verdict": self.verdict, "explanation": self.explanation,
            "instantaneous": {"dof": self.instantaneous_dof, "pattern": self.instantaneous_pattern, "mobility": self.instantaneous_mobility},
            "full_cycle": {"dof": self.full_cycle_dof, "pattern": self.full_cycle_pattern, "mobility": self.full_cycle_mobility},
            "instantaneous_only": {"dof": self.instantaneous_only_dof, "mobility": self.instantaneous_only_mobility},
            "margin": self.margin.to_dict(), "steps": list(self.steps), "directions_tried": len(self.probes), "directions_moved": self.moved,
            "second_order": None if self.second_order is None else self.second_order.to_dict(),
            "branches": [b.to_dict() for b in self.branches], "probes": [p.to_dict() for p in self.probes], "warnings": list(self.warnings),
        }
