"""One continuation step of many poses: Newton at their driven values, and its retries.

A driven joint's variable is fixed; a pose coordinate is one more equation
(:class:`Drive`); the other variables are solved by the package's one Newton
(:func:`mobility.core.kinematics.newton`). A pose is *assembled* when every
residual component is at most ``Tolerance.closure``. A failed step is retried
(:func:`_advance`): a wider move, sub-steps, off a fold.

Examples
--------
>>> import numpy as np
>>> import mobility
>>> from mobility.core.kinematics import kinematics
>>> from mobility.sweeps.grid import plan_grid
>>> m = mobility.load("mechanisms/parallelogram.yaml")
>>> plan, kin = plan_grid(m, ["O1=10:10:1"]), kinematics(m)
>>> drive = Drive.of(plan.axes, kin.variable_count)
>>> q, residual, assembled = newton(kin, drive, np.zeros((1, kin.variable_count)), plan.axes[0].internal[None, :])
>>> bool(assembled[0]), float(residuals(kin, drive, q, plan.axes[0].internal[None, :])[0]) < 1e-12
(True, True)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.kinematics import MAX_ITERATIONS, Equations, Evaluation, Kinematics, min_norm_steps
from ..core.kinematics import newton as close_stack
from ..core.kinematics import polish as polish_stack
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, decide_ranks
from .grid import SweepAxis

__all__ = ["Drive", "newton", "polish", "residuals", "walk_between"]


@dataclass(frozen=True)
class Drive:
    """How the driven coordinates enter the equations.

    Attributes
    ----------
    joints, variables : ndarray of int
        Axis positions that drive a joint variable, and the variable each drives.
    pose, components : ndarray of int
        Axis positions that are pose coordinates, and the component (0..5) each fixes.
    free : ndarray of bool, shape (n,)
        The variables solved for.
    """

    joints: np.ndarray
    variables: np.ndarray
    pose: np.ndarray
    components: np.ndarray
    free: np.ndarray

    @classmethod
    def of(cls, axes: tuple[SweepAxis, ...], variable_count: int) -> "Drive":
        """The drive of a grid's axes."""
        joints = [i for i, a in enumerate(axes) if a.kind == "joint"]
        pose = [i for i, a in enumerate(axes) if a.kind == "pose"]
        free = np.ones(variable_count, dtype=bool)
        variables = np.array([axes[i].variable for i in joints], dtype=int)
        free[variables] = False
        return cls(np.array(joints, dtype=int), variables, np.array(pose, dtype=int), np.array([axes[i].variable for i in pose], dtype=int), free)

    @property
    def equations(self) -> Equations:
        """The equations of Newton's method: the free variables and the fixed pose coordinates (whose goals are ``targets[:, pose]``)."""
        return Equations(self.free, self.components)

    def apply(self, q: np.ndarray, targets: np.ndarray) -> np.ndarray:
        """``q`` with the driven joint variables set to their targets."""
        q = np.array(q, dtype=float)
        if self.joints.size:
            q[:, self.variables] = targets[:, self.joints]
        return q


def _evaluate(bk: Kinematics, drive: Drive, q: np.ndarray, targets: np.ndarray) -> tuple[np.ndarray, Evaluation]:
    """The loops' and pose equations' residual ``(m, N)``, and the evaluation that gives their Jacobian."""
    return drive.equations.values(bk, q, targets[:, drive.pose])


def newton(bk: Kinematics, drive: Drive, start: np.ndarray, targets: np.ndarray, *, tol: Tolerance = DEFAULT_TOLERANCE,
           max_move: np.ndarray | float = np.inf, max_iter: int = MAX_ITERATIONS) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Close every loop of many poses at their driven values ``targets`` ``(N, axes)``: the best iterates, their residuals, whether assembled."""
    out = close_stack(bk, drive.apply(start, targets), targets[:, drive.pose], drive.equations, tol=tol, max_move=max_move, max_iter=max_iter)
    return out.q, out.residual, out.converged


def polish(bk: Kinematics, drive: Drive, q: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """Closed poses ``q`` at their driven values refined in extended precision (:func:`mobility.core.kinematics.polish`)."""
    return polish_stack(bk, q, targets[:, drive.pose], drive.equations)


def _advance(bk: Kinematics, drive: Drive, base_q: np.ndarray, base_t: np.ndarray, predicted: np.ndarray, targets: np.ndarray,
             tol: Tolerance, retry: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One continuation step from ``base_q`` (at ``base_t``) to ``targets``; a failure retried wider, in sub-steps, off a fold.

    A solve moves at most ``10 span + 0.05`` (``span``: the predicted move plus
    the drive's change): farther, it would reach another assembly.
    """
    with np.errstate(over="ignore", invalid="ignore"):  # an infinite span (a target beyond any size) allows any move
        span = np.linalg.norm(predicted - base_q, axis=1) + np.linalg.norm(targets - base_t, axis=1)
    q, err, ok = newton(bk, drive, predicted, targets, tol=tol, max_move=10.0 * span + 0.05)
    if not retry:
        return q, err, ok
    failed = np.flatnonzero(~ok)
    linear = np.zeros(len(q))
    if failed.size:
        linear[failed] = _linear_step_lengths(bk, drive, base_q[failed], targets[failed], tol)
        wider = failed[linear[failed] > np.linalg.norm(predicted[failed] - base_q[failed], axis=1)]
        if wider.size:  # the same step, allowed as far as the linearised step reaches
            _keep_better(q, err, ok, wider, *newton(bk, drive, predicted[wider], targets[wider], tol=tol, max_move=10.0 * (span[wider] + linear[wider]) + 0.05))
    failed = np.flatnonzero(~ok)
    if failed.size:
        _keep_better(q, err, ok, failed, *_substeps(bk, drive, base_q[failed], base_t[failed], predicted[failed], targets[failed], linear[failed], tol))
    failed = np.flatnonzero(~ok)
    if failed.size:
        _keep_better(q, err, ok, failed, *_off_a_fold(bk, drive, base_q[failed], base_t[failed], targets[failed], tol))
    return q, err, ok


def _keep_better(q: np.ndarray, err: np.ndarray, ok: np.ndarray, rows: np.ndarray, new_q: np.ndarray, new_err: np.ndarray, new_ok: np.ndarray) -> None:
    """In place: each of ``rows`` (not assembled) takes the new attempt if it assembles, or if it lowers the residual."""
    take = new_ok | (new_err < err[rows])
    q[rows[take]], err[rows[take]] = new_q[take], new_err[take]
    ok[rows[new_ok]] = True


SUBSTEP_HALVINGS = 4
"""A failed step walked in sub-steps (:func:`_substeps`) gives up at its ``SUBSTEP_HALVINGS + 1``-th failed sub-step; each
failure halves the next sub-step, so the shortest tried is ``2**-(SUBSTEP_HALVINGS + 1)`` of the step (1/32)."""


def _substeps(bk: Kinematics, drive: Drive, base_q: np.ndarray, base_t: np.ndarray, predicted: np.ndarray, targets: np.ndarray,
              linear: np.ndarray, tol: Tolerance) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Failed steps walked towards their targets in sub-steps (half the step at most), halving a sub-step that fails.

    The drive moves monotonically, so a walk cannot pass a fold onto the other
    assembly branch. Returns the best attempt at each target (the base, residual infinite, where none reached it).
    """
    count = len(base_q)
    cur_q, cur_t = base_q.copy(), base_t.copy()
    tangent = predicted - base_q  # the move per whole step: the line's predictor, or (from one point) the walk's secant
    secant = ~np.any(tangent != 0.0, axis=1)
    done, size = np.zeros(count), np.full(count, 0.5)
    failures = np.zeros(count, dtype=int)
    q, err, ok = base_q.copy(), np.full(count, np.inf), np.zeros(count, dtype=bool)
    active = np.arange(count)
    while active.size:
        reach = np.minimum(done[active] + size[active], 1.0)
        part = reach - done[active]
        t = base_t[active] + (targets[active] - base_t[active]) * reach[:, None]
        guess = cur_q[active] + tangent[active] * part[:, None]
        with np.errstate(over="ignore", invalid="ignore"):
            move = np.linalg.norm(guess - cur_q[active], axis=1) + np.linalg.norm(t - cur_t[active], axis=1) + linear[active] * part
        nq, nerr, nok = newton(bk, drive, guess, t, tol=tol, max_move=10.0 * move + 0.05)
        final = reach >= 1.0
        at_target = active[final]
        _keep_better(q, err, ok, at_target, nq[final], nerr[final], nok[final])
        took = active[nok]
        along = nok & secant[active]
        with np.errstate(over="ignore", invalid="ignore"):
            tangent[active[along]] = (nq[along] - cur_q[active[along]]) / part[along, None]
        cur_q[took], cur_t[took], done[took] = nq[nok], t[nok], reach[nok]
        size[took] = np.minimum(2.0 * size[took], 0.5)
        missed = active[~nok]
        size[missed] *= 0.5
        failures[missed] += 1
        active = active[~(final & nok) & (failures[active] <= SUBSTEP_HALVINGS)]
    return q, err, ok


def _linear_step_lengths(bk: Kinematics, drive: Drive, base_q: np.ndarray, targets: np.ndarray, tol: Tolerance) -> np.ndarray:
    """Length of the first Newton step from each assembled ``base_q`` to ``targets`` (the linearised motion), 0 at a fold.

    Where the equations lose rank (a fold, or a driven coordinate the mechanism
    cannot change there) the damped step's length means nothing: 0.
    """
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        start = drive.apply(base_q, targets)
        r, evaluation = _evaluate(bk, drive, start, targets)
        lengths = np.zeros(len(base_q))
        if r.shape[0] == 0 or not drive.free.any():
            return lengths
        jac = drive.equations.jacobians(evaluation)
        full = np.zeros(len(base_q), dtype=bool)
        finite = np.all(np.isfinite(jac), axis=(1, 2)) & np.all(np.isfinite(r), axis=0)
        if jac.shape[1] <= jac.shape[2] and finite.any():  # no more equations than free variables, and none lost
            full[finite] = ~_folds(np.linalg.svd(jac[finite], compute_uv=False), tol)[1]
        if full.any():
            lengths[full] = np.linalg.norm(min_norm_steps(jac[full], r[:, full]), axis=1)
    return np.where(np.isfinite(lengths), lengths, 0.0)


FOLD_REACH = (0.3, 1.0, 3.0)
"""Distances tried along a singular direction when a step leaves a fold, in units of ``sqrt(step)``."""


def _off_a_fold(bk: Kinematics, drive: Drive, base_q: np.ndarray, base_t: np.ndarray, targets: np.ndarray,
                tol: Tolerance) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Steps that failed from a fold (the drive's Jacobian singular), tried from ``+-c sqrt(step)`` along each free direction.

    At a fold the nearby poses lie ``sqrt(step)`` away, where Newton's
    minimum-norm step never goes. The first start that closes and walks back to
    the base (:func:`_walks_back`) is kept; elsewhere the base, residual infinite.
    """
    count = len(base_q)
    q, err, ok = base_q.copy(), np.full(count, np.inf), np.zeros(count, dtype=bool)
    if not drive.free.any():
        return q, err, ok
    with np.errstate(over="ignore", invalid="ignore"):
        _, evaluation = _evaluate(bk, drive, base_q, base_t)
        _, sv, vt = np.linalg.svd(drive.equations.jacobians(evaluation), full_matrices=True)
        step = np.abs(targets - base_t).max(axis=1)
    free = int(drive.free.sum())
    # (N, free): the right singular vectors the rank decision drops, motions free to first order.  Only a base singular by the
    # policy's own rank decision (a file at a dead centre) is a fold to leave this way; from one merely near a fold (the last
    # grid point before a workspace boundary) a start across it would land on the other assembly branch and carry it into the grid
    rank, fold = _folds(sv, tol)
    singular = fold[:, None] & (np.arange(free)[None, :] >= rank[:, None]) & (np.isfinite(step) & (step > 0))[:, None]
    for reach in FOLD_REACH:
        rows, direction = np.nonzero(~ok[:, None] & singular)  # row-major: each row's directions in order
        if rows.size == 0:
            break
        rows, direction = np.repeat(rows, 2), np.repeat(direction, 2)
        sign = np.tile([1.0, -1.0], rows.size // 2)
        length = sign * reach * np.sqrt(step[rows])
        guess = base_q[rows].copy()
        guess[:, drive.free] += length[:, None] * vt[rows, direction]
        nq, nerr, nok = newton(bk, drive, guess, targets[rows], tol=tol, max_move=10.0 * np.abs(length) + 10.0 * step[rows] + 0.05)
        closed = np.flatnonzero(nok)
        if closed.size:
            nok[closed] = _walks_back(bk, drive, nq[closed], targets[rows[closed]], base_q[rows[closed]], base_t[rows[closed]], tol)
        for k in np.flatnonzero(nok):  # the first kept start of each row, in order
            if not ok[rows[k]]:
                q[rows[k]], err[rows[k]], ok[rows[k]] = nq[k], nerr[k], True
    return q, err, ok


def _folds(sv: np.ndarray, tol: Tolerance) -> tuple[np.ndarray, np.ndarray]:
    """The rank of each stacked closure Jacobian (singular values ``(N, min(m, free))``) and whether it is a fold (loses rank)."""
    rank = decide_ranks(sv, tol).rank if sv.shape[1] else np.zeros(len(sv), dtype=int)
    return rank, rank < sv.shape[1]


RETURN_STEPS = 4
"""Steps of the walk back from a pose found off a fold to the fold's drive values (:func:`_walks_back`)."""


def walk_between(bk: Kinematics, drive: Drive, q: np.ndarray, start: np.ndarray, goal: np.ndarray, *, tol: Tolerance = DEFAULT_TOLERANCE) -> np.ndarray:
    """The poses reached from ``q`` (closed at drive values ``start``) by :data:`RETURN_STEPS` Newton solves on the straight way to ``goal``."""
    cur = q
    for k in range(1, RETURN_STEPS + 1):
        cur, _, _ = newton(bk, drive, cur, start + (goal - start) * (k / RETURN_STEPS), tol=tol)
    return cur


def _walks_back(bk: Kinematics, drive: Drive, q: np.ndarray, targets: np.ndarray, base_q: np.ndarray, base_t: np.ndarray, tol: Tolerance) -> np.ndarray:
    """Whether each closed pose ``q`` (at ``targets``) lies on a branch through ``base_q``: walked back, it ends nearer the base than half its distance.

    A pose of another assembly walks back to a pose of its own branch.
    """
    cur = walk_between(bk, drive, q, targets, base_t, tol=tol)
    with np.errstate(over="ignore", invalid="ignore"):
        return np.linalg.norm(cur - base_q, axis=1) <= 0.5 * np.linalg.norm(q - base_q, axis=1)


def residuals(bk: Kinematics, drive: Drive, q: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """The largest residual component of each pose ``q`` ``(N, n)`` at its driven values ``targets`` (loops and pose equations); infinite where not finite."""
    out = np.empty(len(q))
    for start in range(0, len(q), EVALUATION_BLOCK):  # a line of a 1-D sweep may hold millions of poses
        rows = slice(start, start + EVALUATION_BLOCK)
        with np.errstate(over="ignore", invalid="ignore"):
            r, _ = _evaluate(bk, drive, q[rows], targets[rows])
            e = np.abs(r).max(axis=0) if r.shape[0] else np.zeros(len(q[rows]))
        out[rows] = np.where(np.isfinite(e), e, np.inf)
    return out


EVALUATION_BLOCK = 16384
"""Poses evaluated together by :func:`residuals` (its stacked arrays take about 1 kB per pose and joint variable)."""
