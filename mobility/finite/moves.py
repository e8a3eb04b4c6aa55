"""Probing moves: try to move a mechanism from a pose along a direction, re-closing every loop.

For a direction ``d`` and each step ``h`` of a :class:`MovePlan`: predict
``q = q0 + h d`` and re-close every loop by Newton with the progress fixed,
``d . q = d . q0 + h`` (docs/finite.md, "How it decides", step 4).  The
direction *moves* when the loops close at every step; a motion that does not
exist leaves a residual of order ``h^2``.  At the pose reached with the probe
step the first-order motions are examined again, which tells branches apart.

Examples
--------
>>> import numpy as np
>>> from mobility.core.kinematics import kinematics
>>> from mobility.core.model import Joint, Mechanism
>>> m = Mechanism("slide", "g", "s", (Joint("p", "P", ("g", "s"), axis=(1, 0, 0)),))
>>> plan = MovePlan.at_given_pose(kinematics(m), (1e-3, 1e-2, 5e-2))
>>> p = probe(plan, np.zeros(1), "basis", np.ones(1))
>>> p.moved, p.steps, p.mobility
(True, (0.001, 0.01, 0.05), 1)
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Sequence

import numpy as np

from ..core.kinematics import Kinematics
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance
from .orders import first_orders
from .parameters import INEXACT_ALLOWANCE, MAX_MOVE, NEARBY_NEAR_SINGULAR, NEARBY_RANK
from .results import Probe

__all__ = ["MovePlan", "probe", "probes", "probe_directions"]


@dataclass(frozen=True)
class MovePlan:
    """How the moves of one run are made.

    Attributes
    ----------
    kinematics : Kinematics
        The finite model of the mechanism at its given pose (``q = 0``).
    steps : tuple of float
        Increasing step sizes (dimensionless).
    probe_step : float
        The step at which the pose reached is kept and examined.
    tol : Tolerance
        The policy: its ``closure`` is the residual accepted as closed.
    nearby_tol : Tolerance
        The rank policy at the poses reached (see
        :data:`~mobility.finite.parameters.NEARBY_RANK`).
    inexact : float
        The largest singular value the rank decision at the given pose dropped
        (relative): geometry special only to this is treated as exact.
    """

    kinematics: Kinematics
    steps: tuple[float, ...]
    probe_step: float
    tol: Tolerance
    nearby_tol: Tolerance
    inexact: float = 0.0

    @classmethod
    def at_given_pose(cls, kin: Kinematics, steps: tuple[float, ...], tol: Tolerance = DEFAULT_TOLERANCE, inexact: float = 0.0) -> "MovePlan":
        """The plan of the moves from the given pose: the probe step is the middle step (or the only one)."""
        probe_step = steps[len(steps) // 2]
        nearby = replace(tol, rank=max(tol.rank, NEARBY_RANK * probe_step), near_singular=max(tol.near_singular, NEARBY_NEAR_SINGULAR * probe_step))
        return cls(kin, steps, probe_step, tol, nearby, inexact)

    def local(self) -> "MovePlan":
        """The plan of the moves from a nearby pose: the smallest step and half the probe step (the probe step)."""
        steps = (self.steps[0], self.probe_step / 2.0) if len(self.steps) > 1 else self.steps
        return replace(self, steps=steps, probe_step=steps[-1])

    def closure_tolerance(self, distance: float) -> Tolerance:
        """The policy with the residual accepted as closed at ``distance`` (joint space) from the given pose.

        Round-off, or the first-order residual ``~ inexact * distance`` that geometry
        special only to ``inexact`` leaves (treated as exact, as the rank decision did).
        """
        return replace(self.tol, closure=max(self.tol.closure, INEXACT_ALLOWANCE * self.inexact * distance))


def probe(plan: MovePlan, q0: np.ndarray, source: str, d: np.ndarray, *, examine: bool = True) -> Probe:
    """Move from ``q0`` along the unit joint-rate direction ``d`` with each step of ``plan`` (smallest first).

    ``source`` says how ``d`` was chosen; ``examine``: examine the first-order
    motions at the pose reached with the probe step.
    """
    return probes(plan, q0, [(source, d)], examine=examine)[0]


def probes(plan: MovePlan, q0: np.ndarray, candidates: Sequence[tuple[str, np.ndarray]], *, examine: bool = True) -> tuple[Probe, ...]:
    """:func:`probe` along each ``(source, direction)`` of ``candidates``, every direction and step re-closed in one Newton solve.

    Each step of each direction is its own solve (from ``q0``, not from the step before), so one
    Newton on the stack gives each what :func:`probe` alone makes of it (steps after the first
    failure dropped), at about the cost of one move.

    Examples
    --------
    >>> import numpy as np
    >>> from mobility.core.kinematics import kinematics
    >>> from mobility.core.model import Joint, Mechanism
    >>> m = Mechanism("slide", "g", "s", (Joint("p", "P", ("g", "s"), axis=(1, 0, 0)),))
    >>> plan = MovePlan.at_given_pose(kinematics(m), (1e-3, 1e-2))
    >>> [(p.source, p.moved, p.steps) for p in probes(plan, np.zeros(1), [("basis", np.ones(1)), ("basis", -np.ones(1))])]
    [('basis', True, (0.001, 0.01)), ('basis', True, (0.001, 0.01))]
    """
    if not candidates:
        return ()
    kin = plan.kinematics
    n, steps = kin.variable_count, plan.steps
    offset = float(np.linalg.norm(q0))  # distance of the start from the given pose
    limits = [plan.closure_tolerance(offset + h).closure for h in steps]  # each step's, the same for every direction
    starts, rows, targets = [], [], []
    for _, d in candidates:
        along = float(d @ q0)
        for h in steps:
            starts.append(q0 + h * d)
            rows.append(d)
            targets.append(along + h)
    closures = kin.close_each(np.array(starts).reshape(-1, n), constraints=(np.array(rows).reshape(-1, 1, n), np.array(targets).reshape(-1, 1)),
                              closure=np.tile(limits, len(candidates)), max_move=np.tile([MAX_MOVE * h for h in steps], len(candidates)))
    out: list[Probe] = []
    arrived = []  # (index in out, pose reached with the probe step) of the moves that moved
    for index, (source, d) in enumerate(candidates):
        residuals, iterations, done = [], [], []
        achieved = None
        reached = None
        for h, closure in zip(steps, closures[index * len(steps) : (index + 1) * len(steps)]):
            residuals.append(closure.residual)
            iterations.append(closure.iterations)
            done.append(h)
            if not closure.converged:
                break
            chord = closure.q - q0
            if achieved is None:
                achieved = chord / np.linalg.norm(chord)
            if h == plan.probe_step:
                reached = closure.q
        moved = len(residuals) == len(steps) and residuals[-1] <= limits[-1]
        out.append(Probe(source, d, tuple(done), tuple(residuals), tuple(iterations), moved, achieved, reached if moved else None))
        if moved and examine and reached is not None:
            arrived.append((len(out) - 1, reached))
    # the first-order motions where the moves arrived, examined together
    for (index, reached), there in zip(arrived, first_orders(kin, np.array([q for _, q in arrived]).reshape(-1, n), plan.nearby_tol)):
        out[index] = replace(out[index], mobility=there.mobility, dof=there.dof, margin=there.smallest_kept, tangent=there.tangent)
    return tuple(out)


def probe_directions(basis: np.ndarray, rng: np.random.Generator, *, randoms: int, pairs: bool) -> list[tuple[str, np.ndarray]]:
    """Probe directions in the span of ``basis``: ``(source, direction)`` for +-basis, sums of pairs, random combinations.

    Examples
    --------
    >>> import numpy as np
    >>> [s for s, _ in probe_directions(np.eye(3)[:, :2], np.random.default_rng(0), randoms=1, pairs=True)]
    ['basis', 'basis', 'basis', 'basis', 'pair', 'pair', 'random']
    """
    k = basis.shape[1]
    out = [("basis", sign * basis[:, i]) for i in range(k) for sign in (1.0, -1.0)]
    if pairs:
        out += [("pair", (basis[:, i] + s * basis[:, j]) / np.sqrt(2.0)) for i in range(k) for j in range(i + 1, k) for s in (1.0, -1.0)]
    for _ in range(randoms):
        u = rng.standard_normal(k)
        out.append(("random", basis @ (u / np.linalg.norm(u))))
    return out
