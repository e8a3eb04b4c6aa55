"""Seams: where the walk round a full turn comes back on another assembly.

A range that covers a full turn of an ``R`` or ``C`` joint is walked round the
circle in one direction (:mod:`mobility.sweeps.walks`), so neighbouring
poses are joined by motion everywhere but between the last stop of the walk
and its anchor, where the turn closes.  There a full turn usually comes back
to the pose it left; it need not: the free joints of a mechanism driven by
fewer coordinates than its mobility drift along the turn (a planar 5R with
one crank driven), and a mechanism can leave one assembly for another on the
way (a crank that turns twice per turn of its output).  The table then holds
two poses a grid step apart that no small motion joins, which the answers
alone may not show.

:func:`find_seams` walks from the last stop of each closed line to its
anchor's drive values (:data:`~mobility.sweeps.steps.RETURN_STEPS` Newton steps,
:func:`~mobility.sweeps.steps.walk_between`) and compares the pose reached with the anchor's, joint by joint (their
unit twists in normalised coordinates, so that a link spinning idly is the
same pose): they differ by more than :data:`~mobility.core.tolerance.SEAM_GAP`
at a seam.  Only lines walked all the way round are looked at (a line with a
pose not assembled was joined to its anchor the other way).

Examples
--------
>>> import mobility
>>> r = mobility.sweep(mobility.load("mechanisms/planar_5r.yaml"), ["A1=0:360:361"])
>>> [(r.values[a].tolist(), r.values[b].tolist()) for a, b in r.seams]   # A2, left free, drifts round the turn
[([359.0], [0.0])]
>>> mobility.sweep(mobility.load("mechanisms/four_bar.yaml"), ["A=0:360:361"]).seams.shape   # a four-bar's crank comes back
(0, 2)
"""

from __future__ import annotations

import numpy as np

from ..core.tolerance import DEFAULT_TOLERANCE, SEAM_GAP, Tolerance
from ..core.kinematics import Kinematics
from .continuation import line_layout, targets_of
from .steps import Drive, walk_between
from .grid import GridPlan
from .posed_screws import posed_screws
from .walks import plan_walks

__all__ = ["find_seams"]


def find_seams(bk: Kinematics, plan: GridPlan, q: np.ndarray, assembled: np.ndarray, *, tol: Tolerance = DEFAULT_TOLERANCE) -> np.ndarray:
    """The pairs of grid points, ``(last stop, anchor)`` of a line round a full turn, that no small motion joins.

    Parameters
    ----------
    bk : Kinematics
    plan : GridPlan
    q : ndarray, shape (size, n)
        The joint variables of every grid point (flat, C order).
    assembled : ndarray of bool, shape (size,)
    tol : Tolerance

    Returns
    -------
    ndarray of int, shape (k, 2)
        Flat indices of the two grid points of each seam, in grid order of
        the lines (none when no axis covers a full turn).
    """
    out: list[tuple[int, int]] = []
    drive = Drive.of(plan.axes, bk.variable_count)
    for walk in plan_walks(plan):
        if not walk.closed or walk.stops.size < 2 or walk.variable < 0:
            continue
        w, s = walk.stops.size, walk.start
        layout = line_layout(plan.shape, walk.position)
        last, anchor = layout[:, walk.stops[(s - 1) % w]], layout[:, walk.stops[s]]
        # a line with a stop not assembled was not walked all the way round: its down leg joined the last stop to the anchor
        whole = assembled[layout[:, walk.stops]].all(axis=1)
        last, anchor = last[whole], anchor[whole]
        if last.size == 0:
            continue
        # the anchor's drive values, its driven angle continued from the last stop's (one step on, not a turn back)
        begin, goal = targets_of(plan, last), targets_of(plan, anchor)
        ahead = np.mod(goal[:, walk.position] - begin[:, walk.position], walk.period)
        start = goal.copy()
        start[:, walk.position] = q[last, walk.variable]
        goal[:, walk.position] = start[:, walk.position] + ahead
        gap = _pose_gap(bk, walk_between(bk, drive, q[last], start, goal, tol=tol), q[anchor])
        apart = ~(gap <= SEAM_GAP)  # a walk that diverged (not finite) is a seam too
        out.extend(zip(last[apart].tolist(), anchor[apart].tolist()))
    return np.array(sorted(out), dtype=int).reshape(-1, 2)


def _pose_gap(bk: Kinematics, q: np.ndarray, other: np.ndarray) -> np.ndarray:
    """The largest difference between the joint twists of two sets of poses (unit columns, normalised coordinates), per pose.

    The joints' lines, not the links' displacements: a link that spins idly
    between two spherical joints (a rod of a Delta) turns without moving any
    joint, and is the same pose.
    """
    with np.errstate(invalid="ignore", over="ignore"):
        a, b = posed_screws(bk, q).twists, posed_screws(bk, other).twists
        gap = np.abs(a - b).max(axis=(1, 2)) if a.shape[2] else np.zeros(len(q))
    return np.where(np.isfinite(gap), gap, np.inf)
