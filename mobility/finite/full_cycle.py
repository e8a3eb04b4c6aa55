"""Instantaneous or full-cycle: does the freedom found at a pose survive a finite motion?  The entry point.

The screw route (:func:`mobility.analyze`) counts first-order motions.  At a
singular pose some of them are infinitesimal only (a planar four-bar stretched
flat), or the pose is where branches of motion meet (a parallelogram four-bar
folded flat).  :func:`finite_mobility` decides it numerically, on the finite
kinematics of :mod:`mobility.core.kinematics`: first and second order at the
given pose, moves along the first-order directions re-closed by Newton, the
poses reached grouped into branches and measured, and the verdict
(docs/finite.md, "How it decides").  Every number is dimensionless (radians;
lengths over the characteristic length), so the verdict is the same for a file
scaled by 1000 or moved rigidly.

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

import itertools
from typing import Any, Iterable

import numpy as np

from ..core.analysis import analyze
from ..core.couplings import require_no_couplings
from ..core.kinematics import kinematics
from ..core.model import Mechanism, require_mechanism
from ..core.validation import require_integer
from ..core.poses import MAX_STEP, require_seed, require_step
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, require_tolerance
from ..errors import RequestError, counted, shown_argument
from .branches import examine_branch, group_by_tangent
from .moves import MovePlan, probe_directions, probes
from .orders import canonical_basis, first_order, second_order
from .parameters import DEFAULT_STEPS, MAX_RANDOMS, MAX_STEP_COUNT
from .results import FiniteMobility, Probe, SecondOrder
from .verdict import judge, no_motion

__all__ = ["finite_mobility"]


def finite_mobility(mechanism: Mechanism, *, steps: Iterable[float] = DEFAULT_STEPS, randoms: int | None = None, seed: int = 0,
                    tol: Tolerance = DEFAULT_TOLERANCE) -> FiniteMobility:
    """Decide whether the instantaneous freedom of ``mechanism`` survives a finite motion.

    Parameters
    ----------
    steps : sequence of float
        Step sizes, dimensionless (radians; lengths over the characteristic
        length), sorted here: 1 to :data:`~mobility.finite.parameters.MAX_STEP_COUNT`
        (10) numbers, each in ``(0, 1]`` (:data:`mobility.core.poses.MAX_STEP`).
        The middle one (or the only one) is the *probe step*: nearby poses are
        examined there.
    randoms : int, optional
        Random combinations of the tangent basis to try, an integer from 0 to
        :data:`~mobility.finite.parameters.MAX_RANDOMS` (1,000) (default
        ``2 k + 2``, at most 14, for ``k`` instantaneous freedoms).
    seed : int
        Seed of the random directions, a non-negative integer: results are
        reproducible (None, fresh randomness, is refused, as by
        :func:`~mobility.core.poses.sample_poses`).
    tol : Tolerance
        Rank policy, as for :func:`mobility.analyze`, and the closure threshold.

    Raises
    ------
    RequestError
        When ``steps`` is not 1 to 10 numbers in ``(0, 1]``, ``randoms`` not
        an integer in ``[0, 1000]``, or ``seed`` not a non-negative integer;
        for a mechanism with couplings (:attr:`Mechanism.couplings`), whose
        joints the moves would not keep coupled.

    Examples
    --------
    The four-bar keeps its freedom; the parallelogram at its change point has
    two instantaneous freedoms, two branches of one freedom each:

    >>> import mobility
    >>> f = finite_mobility(mobility.load("mechanisms/four_bar.yaml"))
    >>> f.verdict, f.full_cycle_dof, f.full_cycle_pattern
    ('full-cycle', 1, '1R')
    >>> f = finite_mobility(mobility.load("mechanisms/parallelogram_change_point.yaml"))
    >>> f.verdict, f.instantaneous_dof, f.full_cycle_dof, f.full_cycle_pattern
    ('bifurcation', 2, 1, '1T | 1R')
    """
    mechanism = require_mechanism(mechanism, "finite_mobility")
    require_no_couplings(mechanism.couplings, mechanism.name, "finite_mobility", "the full-cycle moves")
    tol = require_tolerance(tol, "finite_mobility")
    checked = _checked_steps(steps)
    if randoms is not None:
        randoms = require_integer(randoms, f"a non-negative integer of at most {MAX_RANDOMS:,} (random directions to try)",
                                  caller="finite_mobility", argument="randoms", low=0, high=MAX_RANDOMS)
    rng = np.random.default_rng(require_seed(seed, "finite_mobility: seed"))  # one stream, drawn in a fixed order: second order, moves, branches
    instant = analyze(mechanism, tol=tol)
    kin = kinematics(mechanism)
    here = first_order(kin, np.zeros(kin.variable_count), tol)
    warnings = [] if here.mobility == instant.mobility else [f"the loop-closure route finds mobility {here.mobility}, the screw route "
                                                             f"{instant.mobility}: the pose is close to a rank decision"]
    if here.mobility == 0:
        return no_motion(instant, checked, warnings)
    plan = MovePlan.at_given_pose(kin, checked, tol, here.largest_dropped)
    basis = canonical_basis(here.tangent)
    second = second_order(kin, basis, rng, here.largest_dropped, tol) if kin.loop_count else None
    probes = _moves_from_given_pose(plan, basis, second, rng, randoms)
    groups, set_aside = group_by_tangent(probes, here.mobility)
    if set_aside:
        warnings.append(f"{counted(set_aside, 'move')} reached poses as singular as the given one "
                        f"(mobility {here.mobility}: a singular locus through the pose); they are not counted as a branch")
    branches = []
    for group in groups:
        branch, warning = examine_branch(plan, group, probes, second, rng)
        branches.append(branch)
        if warning:
            warnings.append(warning)
    return judge(instant, here.mobility, branches, probes, second, checked, warnings, tol)


def _checked_steps(steps: Any) -> tuple[float, ...]:
    """The steps sorted, or a :class:`~mobility.errors.RequestError`: 1 to ``MAX_STEP_COUNT`` numbers (not a string's characters nor a bytes' codes), each in ``(0, MAX_STEP]``.

    Examples
    --------
    >>> _checked_steps(np.array([0.05, 0.001]))
    (0.001, 0.05)
    >>> _checked_steps(b"abc")
    Traceback (most recent call last):
    mobility.errors.RequestError: finite_mobility: steps: expected positive numbers, each at most 1 (joint-space distances), 1 to 10 of them, got b'abc'
    """
    try:
        given = None if isinstance(steps, (str, bytes, bytearray, memoryview)) else list(itertools.islice(steps, MAX_STEP_COUNT + 1))
    except TypeError:  # not iterable
        given = None
    try:
        if given and len(given) <= MAX_STEP_COUNT:
            return tuple(sorted(require_step(h) for h in given))
    except RequestError:
        pass
    raise RequestError(f"finite_mobility: steps: expected positive numbers, each at most {MAX_STEP:g} (joint-space distances), "
                       f"1 to {MAX_STEP_COUNT} of them, got {shown_argument(steps)}")


def _moves_from_given_pose(plan: MovePlan, basis: np.ndarray, second: SecondOrder | None, rng: np.random.Generator, randoms: int | None) -> tuple[Probe, ...]:
    """The moves from the given pose: the basis directions, pairs (up to 3 freedoms), random ones, the second-order ones."""
    k = basis.shape[1]
    count = min(2 * k + 2, 14) if randoms is None else randoms
    candidates = probe_directions(basis, rng, randoms=count, pairs=k <= 3)
    if second is not None:
        for d in second.directions.T[:k]:
            candidates += [("second-order", d), ("second-order", -d)]
    return probes(plan, np.zeros(plan.kinematics.variable_count), candidates)
