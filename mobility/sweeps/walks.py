"""Angles that wrap: the order in which the continuation visits the values of one axis.

An ``R`` or ``C`` angle displaced by a whole turn is the same joint state;
values congruent modulo a turn are one *stop*, solved once.  A range covering a
full turn is a *closed* walk: up from the anchor all the way round, then down
until it meets a stop already assembled, so a crank that turns fully is walked
in one direction (walking half way each way could meet on different branches),
and ``0:360:361`` and ``-180:180:361`` assemble the same poses.  The driven
angle stays continuous along a walk (no jump of 360 degrees for the predictor).

Examples
--------
>>> import mobility
>>> from mobility.sweeps.grid import plan_grid
>>> plan = plan_grid(mobility.load("mechanisms/four_bar.yaml"), ["A=0:360:5"])
>>> walk = axis_walk(plan.axes[0])
>>> walk.closed, walk.stops.tolist(), walk.stop_of.tolist()
(True, [0, 1, 2, 3], [0, 1, 2, 3, 0])
>>> [(walk.stops[at].tolist(), np.degrees(values).round(9).tolist(), halts) for at, values, halts in walk.legs()]
[([1, 2, 3], [90.0, 180.0, 270.0], False), ([3, 2, 1], [-90.0, -180.0, -270.0], True)]
>>> plan_grid(mobility.load("mechanisms/four_bar.yaml"), ["A=100:350:6"]).axes[0].anchor  # 350 is 10 from 0
5
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.tolerance import SAME_GRID_VALUE
from .grid import GridPlan, SweepAxis

__all__ = ["AxisWalk", "axis_walk", "plan_walks"]


@dataclass(frozen=True, eq=False)
class AxisWalk:
    """How the continuation visits the values of one axis (see the module docstring).

    Attributes
    ----------
    position : int
        The axis's place in the grid (the column of its driven values).
    variable : int
        The joint variable the axis drives (-1 for a pose coordinate).
    stops : ndarray of int, shape (w,)
        The value (index along the axis) solved at each stop, in walk order.
    values : ndarray of float, shape (w,)
        The internal value driven at each stop, continuous along the walk.
    start : int
        The stop of the anchor.
    closed : bool
        The last stop is a neighbour of the first.
    period : float
        A whole turn in internal units (2 pi), 0 when the values do not wrap.
    stop_of : ndarray of int, shape (count,)
        The stop each value of the axis takes its pose from.
    """

    position: int
    variable: int
    stops: np.ndarray
    values: np.ndarray
    start: int
    closed: bool
    period: float
    stop_of: np.ndarray

    @property
    def plain(self) -> bool:
        """Every value is its own stop, in the axis's order, and the ends are not neighbours."""
        return not self.closed

    def legs(self) -> tuple[tuple[np.ndarray, np.ndarray, bool], tuple[np.ndarray, np.ndarray, bool]]:
        """The two legs from the start, up then down: ``(stops, values, halts)`` each.

        ``stops`` indexes :attr:`stops` in visiting order, ``values`` are the driven internal
        values there; ``halts``: the leg ends at a stop already assembled (a closed walk's down leg).
        """
        w, s = self.stops.size, self.start
        if self.closed:
            up, down = np.arange(s + 1, s + w), np.arange(s - 1, s - w, -1)
        else:
            up, down = np.arange(s + 1, w), np.arange(s - 1, -1, -1)
        legs = []
        for at, halts in ((up, False), (down, self.closed)):
            index = np.mod(at, w)
            legs.append((index, self.values[index] + self.period * np.floor_divide(at, w), halts))
        return legs[0], legs[1]


def axis_walk(axis: SweepAxis, position: int = 0) -> AxisWalk:
    """The walk of one axis (the ``position``-th of its grid): closed, with congruent values merged, when the axis wraps and covers a full turn."""
    count, start = axis.count, axis.anchor
    variable = axis.variable if axis.kind == "joint" else -1
    period = axis.period
    if not axis.covers_turn:
        every = np.arange(count)
        return AxisWalk(position, variable, every, axis.internal, start, False, 0.0, every)
    tie = SAME_GRID_VALUE * axis.step
    values = axis.values
    residue = np.mod(values, period)
    order = np.argsort(residue, kind="stable")
    ordered = residue[order]
    label = np.concatenate([[0], np.cumsum(np.diff(ordered) > tie)])
    wrapped = bool(label[-1] > 0 and ordered[0] + period - ordered[-1] <= tie)
    if wrapped:  # values just below a turn are the values at 0
        label[label == label[-1]] = 0
    stop_of = np.empty(count, dtype=int)
    stop_of[order] = label
    w = int(label.max()) + 1
    stops = np.full(w, count)
    np.minimum.at(stops, stop_of, np.arange(count))
    stops[stop_of[start]] = start
    here = residue[stops]
    if wrapped and here[0] > 0.5 * period:
        here[0] -= period
    s = int(stop_of[start])
    unwrapped = axis.internal[start] / axis.scale + (here - here[s])  # from the anchor's value as the solver takes it (near the file's pose)
    return AxisWalk(position, variable, stops, unwrapped * axis.scale, s, True, period * axis.scale, stop_of)


def plan_walks(plan: GridPlan) -> tuple[AxisWalk, ...]:
    """The walk of every axis of a grid."""
    return tuple(axis_walk(a, k) for k, a in enumerate(plan.axes))
