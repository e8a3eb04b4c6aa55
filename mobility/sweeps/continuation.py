"""Closing every loop at every point of a grid: continuation along lines.

The grid is solved one axis at a time outwards from the *anchor* point (the
value nearest the file's pose on each axis), all lines of an axis advancing
together; each Newton solve (:mod:`mobility.sweeps.steps`) starts at a cubic
predictor, which keeps the branch through a change point.  docs/sweeps.md tells
it step by step; :mod:`mobility.sweeps.grid_closure` fills the points missed and
:mod:`mobility.sweeps.walks` walks an angle round a full turn.

Examples
--------
>>> import mobility
>>> from mobility.core.kinematics import kinematics
>>> from mobility.sweeps.grid import plan_grid
>>> m = mobility.load("mechanisms/parallelogram.yaml")
>>> plan, bk = plan_grid(m, ["O1=0:90:7"]), kinematics(m)
>>> line = targets_of(plan, line_layout(plan.shape, 0))
>>> q, residual, assembled = close_lines(bk, Drive.of(plan.axes, bk.variable_count), np.zeros((1, bk.variable_count)), np.array([True]), line, 0)
>>> bool(assembled.all()), float(residual.max()) < 1e-12
(True, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..core.kinematics import Kinematics
from ..core.tolerance import DEFAULT_TOLERANCE, SAME_GRID_VALUE, Tolerance
from .grid import GridPlan, whole_turns
from .steps import Drive, _advance, residuals
from .walks import AxisWalk, plan_walks

__all__ = ["GridClosure", "close_lines", "seed_grid", "line_layout", "anchors", "targets_of", "retarget"]

MAX_PIECES = 2000
"""Grid steps at most on the way from the file's pose to the grid's anchor point; a grid
farther away is approached in longer steps (and is not assembled if Newton cannot follow)."""

EXTRAPOLATION = ((1.0,), (2.0, -1.0), (3.0, -3.0, 1.0), (4.0, -6.0, 4.0, -1.0))
"""Predictor from the last 1, 2, 3 or 4 points of a line (polynomial extrapolation, error of order 1 to 4 in the step)."""

GIVE_UP = 2
"""A line stops after this many failures in a row (:func:`fill` takes over from the other axes)."""

HOMOTOPY_STEP = 0.1
"""Largest step (radians, lengths over the characteristic length) from the file's pose to a grid of one point."""


def close_lines(bk: Kinematics, drive: Drive, start_q: np.ndarray, start_ok: np.ndarray, line_targets: np.ndarray, anchor: int, *,
                walk: AxisWalk | None = None, tol: Tolerance = DEFAULT_TOLERANCE,
                on_step: Callable[[int], None] | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Continuation along many lines at once, from their anchor point outwards: ``q (B, c, n)``, ``residual`` and ``assembled`` ``(B, c)``.

    ``start_q`` ``(B, n)`` is each line's pose at point ``anchor`` (assembled
    where ``start_ok``), ``line_targets`` ``(B, c, axes)`` the driven values of
    every point; ``walk`` walks an angle that wraps (default: both ways along the
    lines); ``on_step(poses done)`` is called after each step.
    """
    lines, count = line_targets.shape[:2]
    plain = walk is None or walk.plain
    legs: tuple[tuple[np.ndarray, np.ndarray | None, bool], ...]
    if plain:
        width, start, stops = count, anchor, None
        legs = ((np.arange(anchor + 1, count), None, False), (np.arange(anchor - 1, -1, -1), None, False))
    else:
        assert walk is not None  # not plain
        width, start, stops = walk.stops.size, int(walk.stop_of[anchor]), walk.stops
        legs = walk.legs()
    q, err, ok = _unsolved((lines, width), bk.variable_count)
    q[:, start], ok[:, start] = start_q, start_ok
    start_t = line_targets[:, anchor]
    err[:, start] = np.where(start_ok, residuals(bk, drive, start_q, start_t), np.inf)  # the start's own residual, as every row's
    if on_step:
        on_step(lines)
    for at, values, halts in legs:
        targets = line_targets[:, at if stops is None else stops[at]]
        if values is not None:
            assert walk is not None  # values come from a walk's legs
            targets = targets.copy()
            targets[:, :, walk.position] = values
        halt = ok[:, at] if halts else None
        lq, lerr, lok = _leg(bk, drive, start_q, start_ok, start_t, targets, tol, halt, on_step)
        if halt is None:
            q[:, at], err[:, at], ok[:, at] = lq, lerr, lok
        else:  # keep what the other leg assembled
            take = lok | (~ok[:, at] & (lerr < err[:, at]))
            q[:, at] = np.where(take[:, :, None], lq, q[:, at])
            err[:, at] = np.where(take, lerr, err[:, at])
            ok[:, at] = ok[:, at] | lok
    if plain:
        return q, err, ok
    assert walk is not None  # not plain
    return _spread_stops(bk, drive, walk, q, err, ok, line_targets, tol)


def _spread_stops(bk: Kinematics, drive: Drive, walk: AxisWalk, q: np.ndarray, err: np.ndarray, ok: np.ndarray, line_targets: np.ndarray,
                  tol: Tolerance) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every point of the lines takes the pose of its stop, its driven angle turned by whole turns to its own value."""
    lines, count = line_targets.shape[:2]
    n = q.shape[2]
    gq, gerr, gok = q[:, walk.stop_of].reshape(-1, n), err[:, walk.stop_of].reshape(-1), ok[:, walk.stop_of].reshape(-1)
    gq, gerr, gok = retarget(bk, drive, gq, gerr, gok, line_targets.reshape(lines * count, -1), tol=tol)
    return gq.reshape(lines, count, n), gerr.reshape(lines, count), gok.reshape(lines, count)


def retarget(bk: Kinematics, drive: Drive, q: np.ndarray, residual: np.ndarray, assembled: np.ndarray, targets: np.ndarray, *,
             tol: Tolerance = DEFAULT_TOLERANCE) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Poses ``(N, n)`` with their driven joint variables set to ``targets`` ``(N, axes)`` (the same joint states whole turns away).

    The residual of every changed assembled pose is measured again; returns ``q, residual, assembled``.
    """
    moved = drive.apply(q, targets)
    changed = np.flatnonzero(np.any(moved != q, axis=1) & assembled)
    residual, assembled = residual.copy(), assembled.copy()
    residual[changed] = residuals(bk, drive, moved[changed], targets[changed])
    assembled[changed] = residual[changed] <= tol.closure
    return moved, residual, assembled


def _unsolved(shape: tuple[int, ...], n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Joint variables, residuals and ``assembled`` of points not solved yet: zeros, infinite, false."""
    return np.zeros(shape + (n,)), np.full(shape, np.inf), np.zeros(shape, dtype=bool)


def _leg(bk: Kinematics, drive: Drive, start_q: np.ndarray, start_ok: np.ndarray, start_t: np.ndarray, leg_targets: np.ndarray,
         tol: Tolerance, halt: np.ndarray | None = None, on_step: Callable[[int], None] | None = None, *,
         levels: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Continuation of many lines through ``leg_targets`` ``(B, s, axes)``; a line ends for good where ``halt`` ``(B, s)`` is true.

    A long leg of few lines with short steps is cut in two levels (unless
    ``levels=False``): every ``k``-th point first (steps at most
    :data:`COARSE_STEP`), then the pieces between, all together: about ``2 sqrt(s)`` batched steps instead of ``s``.
    """
    lines, count = leg_targets.shape[:2]
    n = bk.variable_count
    q, err, ok = _unsolved((lines, count), n)
    if levels and halt is not None and lines * TWO_LEVEL_LINES <= count:
        # a line ends for good at its first halting point: solve up to the last of those, then forget what lies past each line's own
        ends = np.where(halt.any(axis=1), np.argmax(halt, axis=1), count)
        reach = int(ends.max(initial=0))
        if reach:
            q[:, :reach], err[:, :reach], ok[:, :reach] = _leg(bk, drive, start_q, start_ok, start_t, leg_targets[:, :reach], tol, None, on_step)
        past = np.arange(count)[None, :] >= ends[:, None]
        err[past], ok[past] = np.inf, False
        if on_step and count > reach:
            on_step(lines * (count - reach))
        return q, err, ok
    k = _coarse_stride(leg_targets, start_t) if levels and halt is None and lines * TWO_LEVEL_LINES <= count else 1
    if k >= 2:
        pieces = count // k
        coarse = np.arange(1, pieces + 1) * k - 1  # the last point of each piece
        cq, cerr, cok = _leg(bk, drive, start_q, start_ok, start_t, leg_targets[:, coarse], tol, None, on_step, levels=False)
        axes = leg_targets.shape[2]
        q[:, coarse], err[:, coarse], ok[:, coarse] = cq, cerr, cok
        # piece j: the k - 1 points before coarse point j, from coarse point j - 1 (piece 0 from the leg's start)
        from_q = np.concatenate([start_q[:, None], cq[:, :-1]], axis=1).reshape(lines * pieces, n)
        from_ok = np.concatenate([start_ok[:, None], cok[:, :-1]], axis=1).reshape(lines * pieces)
        from_t = np.concatenate([start_t[:, None], leg_targets[:, coarse[:-1]]], axis=1).reshape(lines * pieces, axes)
        inner = (coarse[:, None] - k + 1 + np.arange(k - 1)[None, :])  # (pieces, k - 1)
        pq, perr, pok = _leg(bk, drive, from_q, from_ok, from_t, leg_targets[:, inner].reshape(lines * pieces, k - 1, axes), tol, None, on_step, levels=False)
        q[:, inner], err[:, inner], ok[:, inner] = pq.reshape(lines, pieces, k - 1, n), perr.reshape(lines, pieces, k - 1), pok.reshape(lines, pieces, k - 1)
        tail = np.arange(pieces * k, count)
        if tail.size:
            tq, terr, tok = _leg(bk, drive, cq[:, -1], cok[:, -1], leg_targets[:, coarse[-1]], leg_targets[:, tail], tol, None, on_step, levels=False)
            q[:, tail], err[:, tail], ok[:, tail] = tq, terr, tok
        return q, err, ok
    # one point after the other
    last_q, last_t = start_q.copy(), start_t.copy()  # the last assembled point of each line
    last_ok = start_ok.copy()  # is the previous point assembled
    # the points before the last one, most recent first, and whether each (and all after it) is assembled
    history = [start_q.copy() for _ in range(len(EXTRAPOLATION) - 1)]
    known = [np.zeros(lines, dtype=bool) for _ in history]
    misses = np.where(start_ok, 0, GIVE_UP)  # failures in a row since the last assembled point
    for i in range(count):
        if halt is not None:
            ended = halt[:, i]
            last_ok = last_ok & ~ended
            misses = np.where(ended, GIVE_UP, misses)
        targets = leg_targets[:, i]
        points = [last_q] + history
        available = [last_ok] + known
        predicted = last_q.copy()
        for order in range(1, len(EXTRAPOLATION)):  # the highest order the assembled points allow
            use = available[order]
            if use.any():
                predicted[use] = sum(c * p[use] for c, p in zip(EXTRAPOLATION[order], points))
        for retry, rows in ((True, np.flatnonzero(last_ok)), (False, np.flatnonzero(~last_ok & (misses < GIVE_UP)))):
            if rows.size:
                rq, rerr, rok = _advance(bk, drive, last_q[rows], last_t[rows], predicted[rows], targets[rows], tol, retry=retry)
                q[rows, i], err[rows, i], ok[rows, i] = rq, rerr, rok
        now = ok[:, i]
        history = [np.where(now[:, None], p, h) for p, h in zip(points[:-1], history)]
        known = [now & a for a in available[:-1]]
        last_q = np.where(now[:, None], q[:, i], last_q)
        last_t = np.where(now[:, None], targets, last_t)
        last_ok = now
        misses = np.where(now, 0, misses + 1)
        if on_step:
            on_step(lines)
    return q, err, ok


COARSE_STEP = 0.01
"""Longest step (radians, lengths over the characteristic length) of the first level of a two-level leg (:func:`_leg`):
about half a degree, finer than the steps the continuation takes through change points in the tests."""

TWO_LEVEL_LINES = 512
"""A leg is cut in two levels when it has at least this many points per line (and its steps allow it)."""


def _coarse_stride(leg_targets: np.ndarray, start_t: np.ndarray) -> int:
    """The stride ``k`` of a two-level leg: at most ``sqrt(s)``, and ``k`` steps no longer than :data:`COARSE_STEP`; 1 when not worth it."""
    count = leg_targets.shape[1]
    path = np.concatenate([start_t[:, None], leg_targets], axis=1)
    with np.errstate(over="ignore", invalid="ignore"):
        longest = float(np.max(np.abs(np.diff(path, axis=1)), initial=0.0))
    if not np.isfinite(longest):
        return 1
    k = int(math.isqrt(count))
    if longest > 0.0:
        k = min(k, int(COARSE_STEP / longest))
    return k if k >= 8 else 1


def line_layout(shape: tuple[int, ...], axis: int) -> np.ndarray:
    """Flat indices of the grid as lines along ``axis``: shape ``(lines, shape[axis])``.

    Examples
    --------
    >>> line_layout((2, 3), 1).tolist(), line_layout((2, 3), 0).tolist()
    ([[0, 1, 2], [3, 4, 5]], [[0, 3], [1, 4], [2, 5]])
    """
    flat = np.arange(int(np.prod(shape))).reshape(shape)
    return np.moveaxis(flat, axis, -1).reshape(-1, shape[axis])


def anchors(plan: GridPlan) -> tuple[int, ...]:
    """Index, on each axis, of the value nearest the file's pose (displacement 0, round the circle for an angle that wraps); the first of two as near.

    Examples
    --------
    >>> import mobility
    >>> from mobility.sweeps.grid import plan_grid
    >>> anchors(plan_grid(mobility.load("mechanisms/3prs.yaml"), ["P1=-11:11:4", "P2=5:20:4"]))
    (1, 0)
    """
    return tuple(a.anchor for a in plan.axes)


def targets_of(plan: GridPlan, flat: np.ndarray) -> np.ndarray:
    """Internal driven values of grid points, ``(..., axes)``."""
    index = np.unravel_index(np.asarray(flat), plan.shape)
    return np.stack([a.internal[i] for a, i in zip(plan.axes, index)], axis=-1)


@dataclass(frozen=True, eq=False)
class GridClosure:
    """The closed poses of a grid (flat, C order: the last axis varies fastest).

    Attributes
    ----------
    q : ndarray, shape (N, n)
        Joint variables of each pose (see :mod:`mobility.core.kinematics`).
    residual : ndarray, shape (N,)
        Largest loop-closure residual component (dimensionless).
    assembled : ndarray of bool, shape (N,)
    """

    q: np.ndarray
    residual: np.ndarray
    assembled: np.ndarray


def seed_grid(bk: Kinematics, plan: GridPlan, *, tol: Tolerance = DEFAULT_TOLERANCE) -> GridClosure:
    """Every point whose last coordinate is at its anchor, by continuation (the starts of the last axis's lines).

    The other points of the :class:`GridClosure` are not assembled, residual infinite.
    """
    drive = Drive.of(plan.axes, bk.variable_count)
    shape, size, n = plan.shape, plan.size, bk.variable_count
    q, err, ok = _unsolved((size,), n)
    walks = plan_walks(plan)
    anchor = anchors(plan)
    anchor_flat = int(np.ravel_multi_index(anchor, shape))
    # from the file's pose to the anchor point, in steps no longer than a grid step (an angle that wraps: the shorter way round)
    at = targets_of(plan, np.array([anchor_flat]))
    goal = at - np.array([[float(whole_turns(t, a.period * a.scale)) for t, a in zip(at[0], plan.axes)]])
    steps = [a.step * a.scale if a.count > 1 else HOMOTOPY_STEP for a in plan.axes]
    pieces = max([0] + [int(np.ceil(abs(g) / s - SAME_GRID_VALUE)) for g, s in zip(goal[0], steps) if s > 0])
    pieces = min(pieces, MAX_PIECES)  # farther than that: longer steps, which fail (not assembled) rather than run for ever
    # one line of continuation (its predictor keeps the file's branch up to a change point)
    path = goal[:, None, :] * (np.arange(pieces + 1) / max(pieces, 1))[None, :, None]
    pq, perr, pok = close_lines(bk, drive, np.zeros((1, n)), np.array([True]), path, 0, tol=tol)
    reached = bool(pok[0].all())  # a failure on the way is a failure, as before
    aq, aerr, aok = retarget(bk, drive, pq[0, -1:], perr[0, -1:], np.array([reached]), at, tol=tol)  # whole turns back to the grid's value
    q[anchor_flat], ok[anchor_flat], err[anchor_flat] = aq[0], aok[0], aerr[0] if aok[0] else np.inf
    for axis in range(len(shape) - 1):
        layout = line_layout(shape, axis)
        others = [i for i in range(len(shape)) if i != axis]
        index = np.unravel_index(layout[:, 0], shape)
        at_anchor = np.ones(len(layout), dtype=bool)
        for i in others[axis:]:  # later axes sit at their anchors
            at_anchor &= index[i] == anchor[i]
        lines = layout[at_anchor]
        start = lines[:, anchor[axis]]
        lq, lerr, lok = close_lines(bk, drive, q[start], ok[start], targets_of(plan, lines), anchor[axis], walk=walks[axis], tol=tol)
        q[lines], err[lines], ok[lines] = lq, lerr, lok
    return GridClosure(q, err, ok)
