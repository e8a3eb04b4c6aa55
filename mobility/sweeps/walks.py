"""Angles that wrap: the order in which the continuation visits the values of one axis.

The angle of an ``R`` joint displaced by a whole turn is the same joint
state, and so is the angle of a ``C`` joint (its slide is free); not the
angle of an ``H`` joint (its slide goes with its angle), a slide or a pose
coordinate (:attr:`~mobility.sweeps.grid.SweepAxis.period`).

The continuation (:mod:`mobility.sweeps.continuation`) walks every axis from
its *anchor*, the value nearest the file's pose, both ways.  On an axis
whose values wrap:

* the anchor is the value nearest the file's pose round the circle (a
  displacement of 350 degrees is 10 degrees from it);
* values congruent modulo a turn (to within
  :data:`~mobility.core.tolerance.SAME_GRID_VALUE` of a step: ``0`` and
  ``360``, ``-180`` and ``180``, ``-350`` and ``10``) are one *stop* of the
  walk, solved once: every value of a stop takes its pose, the driven angle
  turned by whole turns;
* when the range covers a full turn (its span plus one step reaches a turn,
  so that no gap between the values round the circle is longer than a step)
  the walk is *closed*: its stops are ordered round the circle and the last
  is a neighbour of the first.  The walk goes up from the anchor all the
  way round (to the stop before the anchor), then down from the anchor
  until it meets a stop already assembled: a crank that turns fully is
  walked in one direction, so neighbouring stops are joined by motion
  everywhere but between the last stop and the anchor (where a full turn
  comes back to the file's pose, as it does unless the turn leads to
  another pose: a seam, :mod:`mobility.sweeps.seams`); a crank that cannot turn fully is walked up to its
  limit, and the down leg reaches the poses on the other side of the
  file's pose.  So ``0:360:361`` and ``-180:180:361`` assemble the same
  poses (the walk of both starts at 0 and goes up first).  Walking up half
  way and down the other half would meet in the middle, where the two
  halves can arrive on different branches: a four-bar whose file sits at a
  change point leaves it on one branch going up and on the other going
  down.

Inside a walk the driven angle is continuous (``values`` of a closed walk go
on past a turn), so the predictor and the step size of the continuation
never see a jump of 360 degrees.

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
        The value (index along the axis) solved at each stop of the walk, in
        walk order: round the circle for a closed walk, else the axis's own order.
    values : ndarray of float, shape (w,)
        The internal value driven at each stop, continuous from the first
        stop to the last (whole turns away from the stop's own value).
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

        A closed walk's up leg goes all the way round (one direction, so
        the stops it reaches are joined by motion); its down leg serves the
        stops the up leg could not reach.

        ``stops`` indexes :attr:`stops` in the order the leg visits them,
        ``values`` are the driven internal values there (continuous from the
        start's), ``halts``: the leg ends where it meets a stop already
        assembled (the down leg of a closed walk).
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
    step = axis.step
    period = axis.period
    if not axis.covers_turn:
        every = np.arange(count)
        return AxisWalk(position, variable, every, axis.internal, start, False, 0.0, every)
    tie = SAME_GRID_VALUE * step
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
