"""Closing every pose of a grid: the lines of continuation, then the poses they missed.

:func:`close_grid` runs in this process the stages :func:`mobility.sweeps.sweep`
runs in chunks. :func:`fill` tries each missing pose from its assembled
neighbours on every axis (the ends of a full turn are neighbours), and a pose
congruent modulo a turn to an assembled one takes its pose.

Examples
--------
>>> import mobility
>>> from mobility.core.kinematics import kinematics
>>> from mobility.sweeps.grid import plan_grid
>>> m = mobility.load("mechanisms/four_bar.yaml")  # the crank reaches -160.8 .. +34.0 deg from the file's pose
>>> closure = close_grid(kinematics(m), plan_grid(m, ["A=0:360:13"]))
>>> closure.assembled.tolist()  # 0, 30; then 210 .. 360, the same poses as -150 .. 0
[True, True, False, False, False, False, False, True, True, True, True, True, True]
"""

from __future__ import annotations

import numpy as np

from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance
from ..core.kinematics import Kinematics
from .continuation import GridClosure, anchors, close_lines, line_layout, retarget, seed_grid, targets_of
from .steps import Drive, _advance
from .grid import GridPlan, whole_turns
from .walks import AxisWalk, axis_walk, plan_walks

__all__ = ["close_grid", "fill"]


def close_grid(bk: Kinematics, plan: GridPlan, *, tol: Tolerance = DEFAULT_TOLERANCE) -> GridClosure:
    """Close every pose of the grid by continuation (the lines of the last axis in one batch), then :func:`fill` what is missing."""
    seeds = seed_grid(bk, plan, tol=tol)
    shape = plan.shape
    last = len(shape) - 1
    layout = line_layout(shape, last)
    anchor = anchors(plan)[last]
    starts = layout[:, anchor]
    q, err, ok = seeds.q.copy(), seeds.residual.copy(), seeds.assembled.copy()
    drive = Drive.of(plan.axes, bk.variable_count)
    lq, lerr, lok = close_lines(bk, drive, q[starts], ok[starts], targets_of(plan, layout), anchor, walk=axis_walk(plan.axes[last], last), tol=tol)
    q[layout], err[layout], ok[layout] = lq, lerr, lok
    return fill(bk, plan, GridClosure(q, err, ok), tol=tol)


def fill(bk: Kinematics, plan: GridPlan, closure: GridClosure, *, tol: Tolerance = DEFAULT_TOLERANCE, max_passes: int | None = None) -> GridClosure:
    """Try the missing poses again from any assembled neighbour not yet tried, in batched passes while they assemble new poses.

    The arrays of ``closure`` are updated in place (a sweep's grid can be
    large: no copy is made) and returned in a new :class:`GridClosure`.
    """
    q, err, ok = closure.q, closure.residual, closure.assembled
    shape = plan.shape
    drive = Drive.of(plan.axes, bk.variable_count)
    walks = plan_walks(plan)
    grid_index = np.arange(plan.size).reshape(shape)
    tried: set[tuple[int, int]] = set()
    passes = max_passes if max_passes is not None else sum(shape)
    q, err, ok = _congruent(bk, drive, plan, walks, q, err, ok, tol)
    for _ in range(passes):
        missing = ~ok
        if not missing.any():
            break
        pairs = []  # (pose, neighbour, neighbour's neighbour or -1)
        for axis in range(len(shape)):
            around = walks[axis].closed
            for direction in (1, -1):
                src = np.roll(grid_index, direction, axis=axis)  # the neighbour at index - direction
                valid = np.ones(shape, dtype=bool)
                edge: list[slice | int] = [slice(None)] * len(shape)
                edge[axis] = 0 if direction > 0 else -1
                if not around:
                    valid[tuple(edge)] = False
                src2 = np.roll(grid_index, 2 * direction, axis=axis)
                valid2 = valid.copy()
                edge2: list[slice | int] = [slice(None)] * len(shape)
                edge2[axis] = 1 if direction > 0 else -2
                if shape[axis] > 1 and not around:
                    valid2[tuple(edge2)] = False
                sel = valid & missing.reshape(shape) & ok[src].reshape(shape)
                for pose, nb, nb2, v2 in zip(grid_index[sel], src[sel], src2[sel], valid2[sel]):
                    if (pose, nb) not in tried:
                        pairs.append((pose, nb, nb2 if v2 and ok[nb2] and nb2 != pose else -1))
        if not pairs:
            break
        pairs_a = np.array(pairs, dtype=int)
        tried.update((int(a), int(b)) for a, b, _ in pairs)
        poses, nbs, nbs2 = pairs_a[:, 0], pairs_a[:, 1], pairs_a[:, 2]
        goal = targets_of(plan, poses)
        base_q, base_t = _turned_towards(plan, q[nbs], targets_of(plan, nbs), goal)
        second_q, _ = _turned_towards(plan, q[np.maximum(nbs2, 0)], targets_of(plan, np.maximum(nbs2, 0)), base_t)
        predicted = np.where((nbs2 >= 0)[:, None], 2.0 * base_q - second_q, base_q)
        nq, nerr, nok = _advance(bk, drive, base_q, base_t, predicted, goal, tol, retry=True)
        found = False
        for k in np.argsort(nerr):  # the best attempt at each pose
            pose = poses[k]
            if ok[pose]:
                continue
            if nok[k]:
                q[pose], err[pose], ok[pose] = nq[k], nerr[k], True
                found = True
            elif nerr[k] < err[pose]:
                q[pose], err[pose] = nq[k], nerr[k]
        if not found:
            break
        q, err, ok = _congruent(bk, drive, plan, walks, q, err, ok, tol)
    return GridClosure(q, err, ok)


def _turned_towards(plan: GridPlan, q: np.ndarray, targets: np.ndarray, goal: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Poses and their driven values, each angle that wraps turned by whole turns to within half a turn of ``goal``."""
    q, targets = q.copy(), targets.copy()
    for k, axis in enumerate(plan.axes):
        if axis.period:
            turn = whole_turns(goal[:, k] - targets[:, k], axis.period * axis.scale)
            targets[:, k] += turn
            q[:, axis.variable] += turn
    return q, targets


def _congruent(bk: Kinematics, drive: Drive, plan: GridPlan, walks: tuple[AxisWalk, ...], q: np.ndarray, err: np.ndarray, ok: np.ndarray,
               tol: Tolerance) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Missing poses whose driven angle is congruent (modulo a turn) to an assembled pose's on the same line take its pose (in place)."""
    sources, places = [], []
    for axis, walk in enumerate(walks):
        if walk.stops.size == walk.stop_of.size:
            continue
        layout = line_layout(plan.shape, axis)
        members = np.argsort(walk.stop_of, kind="stable")
        bounds = np.flatnonzero(np.diff(walk.stop_of[members])) + 1
        for group in np.split(members, bounds):
            if group.size < 2:
                continue
            index = layout[:, group]  # (lines, members)
            present = ok[index]
            need = present.any(axis=1)[:, None] & ~present
            rows, cols = np.nonzero(need)
            sources.append(index[rows, np.argmax(present[rows], axis=1)])
            places.append(index[rows, cols])
    if not sources or not sum(p.size for p in places):
        return q, err, ok
    src, dst = np.concatenate(sources), np.concatenate(places)
    dst, first = np.unique(dst, return_index=True)
    src = src[first]
    nq, nerr, nok = retarget(bk, drive, q[src], err[src], ok[src], targets_of(plan, dst), tol=tol)
    q[dst[nok]], err[dst[nok]], ok[dst[nok]] = nq[nok], nerr[nok], True
    return q, err, ok
