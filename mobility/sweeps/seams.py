"""Seams: where the walk round a full turn comes back on another assembly.

A full turn walked round the circle need not come back to the pose it left:
free joints drift (a planar 5R with one crank driven), or the mechanism changes
assembly on the way.  :func:`find_seams` walks on from the last stop of each
such line to its anchor's drive values and compares the joint twists reached
with the anchor's (so a link spinning idly is the same pose): a seam where they
differ by more than :data:`~mobility.core.tolerance.SEAM_GAP`.

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

    ``q`` ``(size, n)`` and ``assembled`` ``(size,)``: every grid point's (flat, C order).
    Returns the flat indices ``(k, 2)`` of each seam's two points.
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
    """The largest difference between the joint twists of two sets of poses (unit columns, normalised coordinates), per pose."""
    with np.errstate(invalid="ignore", over="ignore"):
        a, b = posed_screws(bk, q).twists, posed_screws(bk, other).twists
        gap = np.abs(a - b).max(axis=(1, 2)) if a.shape[2] else np.zeros(len(q))
    return np.where(np.isfinite(gap), gap, np.inf)
