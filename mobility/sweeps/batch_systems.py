"""The series/parallel route of :mod:`mobility.core.screw_systems`, on many poses at once.

Every node of the (structural, computed once) decomposition gets, for all
``N`` poses together, its twist system, its constraint wrench system and its
idle count, by stacked SVDs (``numpy.linalg.svd`` on ``(N, 6, k)`` arrays).
A screw system of rank ``r`` (different at each pose) is kept as a
fixed-shape ``(N, 6, k)`` array whose columns beyond each pose's rank are
zero: zero columns change no span and no non-zero singular value, so series
steps (stack the twists) and parallel steps (stack the wrenches) keep a fixed
shape.  Each rank decision is the one policy,
:func:`mobility.core.tolerance.decide_ranks` (= :func:`~mobility.core.tolerance.decide_rank`
row by row), on singular values of the same matrices as
:func:`mobility.analyze` forms, with the padding columns left out of the
count, so the counts equal those of ``analyze`` on each pose, and the margins
equal them up to round-off.

Examples
--------
>>> import numpy as np
>>> import mobility
>>> from mobility.sweeps.batch_kinematics import BatchKinematics
>>> from mobility.sweeps.posed_screws import posed_screws
>>> m = mobility.load("mechanisms/3prs.yaml")
>>> answer = analyse_poses(m, posed_screws(BatchKinematics(m), np.zeros((2, 15))))
>>> answer.dof.tolist(), answer.pattern.tolist(), answer.mobility.tolist()
([3, 3], ['1T2R', '1T2R'], [3, 3])
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.model import Mechanism
from ..core.screws import SWAP_ROWS, pattern_of
from ..core.tolerance import DEFAULT_TOLERANCE, RankDecisions, Tolerance, decide_ranks
from ..core.topology import Bridge, JointNode, Node, Parallel, Series, decompose
from ..errors import AnalysisError
from .posed_screws import PosedScrews

__all__ = ["BatchValue", "MarginCollector", "stacked_svd", "span_batch", "evaluate_batch", "PoseAnswers", "analyse_poses"]


@dataclass(frozen=True, eq=False)
class BatchValue:
    """Twist system of a node at ``N`` poses (normalised coordinates of each pose).

    Attributes
    ----------
    basis : ndarray, shape (N, 6, k)
        Orthonormal basis of the twist system, columns beyond ``dim`` zero.
    dim : ndarray of int, shape (N,)
    wrenches : ndarray, shape (N, 6, k')
        Basis of the constraint wrenches (``6 - dim`` columns, then zeros).
    idle : ndarray of int, shape (N,)
    children : tuple of BatchValue
        As :class:`mobility.core.screw_systems.SystemValue` keeps them.
    """

    basis: np.ndarray
    dim: np.ndarray
    wrenches: np.ndarray
    idle: np.ndarray
    children: tuple["BatchValue", ...] = ()

    @property
    def mobility(self) -> np.ndarray:
        """Mobility of the network with one end link fixed."""
        return self.dim + self.idle


class MarginCollector:
    """Worst margins over the rank decisions of each pose (as :class:`mobility.core.result.Margin`)."""

    def __init__(self, count: int) -> None:
        self.smallest_kept = np.ones(count)
        self.largest_dropped = np.zeros(count)

    def add(self, d: RankDecisions) -> None:
        """Take one more decision of every pose into account."""
        np.minimum(self.smallest_kept, d.smallest_kept, out=self.smallest_kept)
        np.maximum(self.largest_dropped, d.largest_dropped, out=self.largest_dropped)


def stacked_svd(m: np.ndarray, *, full_v: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """``u`` (square), singular values and (if asked) ``vt`` (square) of every matrix of a stack ``(N, r, c)``.

    Raises
    ------
    AnalysisError
        When LAPACK does not converge on some matrix.
    """
    count, rows, cols = m.shape
    try:
        if cols == 0 or rows == 0:
            return np.broadcast_to(np.eye(rows), (count, rows, rows)), np.zeros((count, 0)), np.broadcast_to(np.eye(cols), (count, cols, cols))
        if full_v:
            u, s, vt = np.linalg.svd(m, full_matrices=True)
            return u, s, vt
        if cols <= rows:  # the transposed problem is the cheaper one for LAPACK here
            _, s, vt = np.linalg.svd(np.swapaxes(m, 1, 2), full_matrices=True)
            return np.swapaxes(vt, 1, 2), s, None
        u, s, _ = np.linalg.svd(m, full_matrices=False)
        return u, s, None
    except np.linalg.LinAlgError:
        raise AnalysisError(f"the singular value decomposition of a stack of {rows}x{cols} matrices did not converge") from None


def span_batch(m: np.ndarray, counts: np.ndarray, tol: Tolerance, margin: MarginCollector | None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Span of the columns of each ``m[i]`` and its reciprocal system, by one stacked SVD.

    Parameters
    ----------
    m : ndarray, shape (N, 6, k)
    counts : ndarray of int, shape (N,)
        The number of columns each matrix has without its zero padding.

    Returns
    -------
    span : ndarray, shape (N, 6, max rank)
        Orthonormal basis, columns beyond each rank zero.
    reciprocal : ndarray, shape (N, 6, 6 - min rank)
        Basis of the reciprocal system (``6 - rank`` columns, then zeros).
    rank : ndarray of int, shape (N,)
    """
    u, s, _ = stacked_svd(m)
    d = decide_ranks(s, tol, np.minimum(counts, 6))
    if margin is not None:
        margin.add(d)
    rank = d.rank
    if len(rank) == 0:
        return np.zeros((0, 6, 0)), np.zeros((0, 6, 0)), rank
    top = int(rank.max())
    span = u[:, :, :top] * (np.arange(top) < rank[:, None])[:, None, :]
    width = 6 - int(rank.min())
    index = rank[:, None] + np.arange(width)
    swapped = u[:, SWAP_ROWS, :]
    reciprocal = np.take_along_axis(swapped, np.minimum(index, 5)[:, None, :], axis=2) * (index < 6)[:, None, :]
    return span, reciprocal, rank


class _Screws:
    """Joint twist columns of every pose (possibly with some columns set to zero)."""

    def __init__(self, twists: np.ndarray, offsets: tuple[int, ...]) -> None:
        self.twists = twists
        self.offsets = offsets

    def of_joint(self, index: int) -> np.ndarray:
        return self.twists[:, :, self.offsets[index] : self.offsets[index + 1]]

    def dof(self, index: int) -> int:
        return self.offsets[index + 1] - self.offsets[index]


def evaluate_batch(node: Node, twists: np.ndarray, offsets: tuple[int, ...], tol: Tolerance = DEFAULT_TOLERANCE, margin: MarginCollector | None = None) -> BatchValue:
    """:func:`mobility.core.screw_systems.evaluate_node` of ``node`` at every pose.

    Parameters
    ----------
    node : Node
        A node of :func:`mobility.core.topology.decompose`.
    twists : ndarray, shape (N, 6, f)
        Unit joint twists of each pose, in its normalised coordinates.
    offsets : tuple of int
        Columns of joint ``j``: ``offsets[j]:offsets[j+1]``.
    margin : MarginCollector, optional
        Collects the margin of every decision.
    """
    return _evaluate(node, _Screws(twists, offsets), tol, margin)


def _evaluate(node: Node, screws: _Screws, tol: Tolerance, margin: MarginCollector | None) -> BatchValue:
    """Every node below ``node``, children before parents, with an explicit stack (trees thousands of levels deep)."""
    values: dict[int, BatchValue] = {}
    stack: list[tuple[Node, bool]] = [(node, False)]
    while stack:
        current, ready = stack.pop()
        if id(current) in values:
            continue
        inner = _inner_children(current)
        if not ready and inner:
            stack.append((current, True))
            stack.extend((child, False) for child in reversed(inner))
            continue
        values[id(current)] = _evaluate_one(current, screws, tol, margin, values)
    return values[id(node)]


def _inner_children(node: Node) -> list[Node]:
    """The children of ``node`` that are evaluated as nodes of their own (a series takes its joints' columns directly)."""
    if isinstance(node, JointNode):
        return []
    if isinstance(node, Series):
        return [c for c in node.children if type(c) is not JointNode]
    if isinstance(node, Parallel):
        return list(node.children)
    return [child for _, _, child in node.edges if not isinstance(child, JointNode)]


def _evaluate_one(node: Node, screws: _Screws, tol: Tolerance, margin: MarginCollector | None, done: dict[int, BatchValue]) -> BatchValue:
    """One node, its inner children's values already in ``done`` (the decisions in the order of the recursive form)."""
    count = screws.twists.shape[0]
    if isinstance(node, JointNode):
        f = screws.dof(node.index)
        basis, wrenches, rank = span_batch(screws.of_joint(node.index), np.full(count, f), tol, margin)
        return BatchValue(basis, rank, wrenches, np.zeros(count, dtype=int))
    if isinstance(node, Series):
        columns, counts, idle, values = [], np.zeros(count, dtype=int), np.zeros(count, dtype=int), []
        for child in node.children:
            if type(child) is JointNode:
                columns.append(screws.of_joint(child.index))
                counts = counts + screws.dof(child.index)
            else:
                v = done[id(child)]
                values.append(v)
                columns.append(v.basis)
                counts = counts + v.dim
                idle = idle + v.idle
        basis, wrenches, rank = span_batch(np.concatenate(columns, axis=2), counts, tol, margin)
        return BatchValue(basis, rank, wrenches, idle + counts - rank, tuple(values))
    if isinstance(node, Parallel):
        values = [done[id(child)] for child in node.children]
        counts = sum((6 - v.dim for v in values), np.zeros(count, dtype=int))
        wrenches, basis, rank = span_batch(np.concatenate([v.wrenches for v in values], axis=2), counts, tol, margin)
        return BatchValue(basis, 6 - rank, wrenches, sum((v.idle for v in values), np.zeros(count, dtype=int)), tuple(values))
    return _bridge(node, screws, tol, margin, done)


def _bridge(node: Bridge, screws: _Screws, tol: Tolerance, margin: MarginCollector | None, done: dict[int, BatchValue]) -> BatchValue:
    """Loop closure of a network that does not reduce, as :mod:`mobility.core.screw_systems` solves it."""
    count = screws.twists.shape[0]
    values, bases, real = [], [], []
    for _, _, child in node.edges:
        if isinstance(child, JointNode):
            bases.append(screws.of_joint(child.index))
            real.append(np.full(count, screws.dof(child.index)))
        else:
            value = done[id(child)]
            values.append(value)
            bases.append(value.basis)
            real.append(value.dim)
    inner = [x for x in node.links if x != node.source]
    col_of = {x: 6 * i for i, x in enumerate(inner)}
    n_link = 6 * len(inner)
    width = sum(b.shape[2] for b in bases)
    a = np.zeros((count, 6 * len(node.edges), n_link + width))
    c = n_link
    for row, ((u, v, _), b) in enumerate(zip(node.edges, bases)):
        r = slice(6 * row, 6 * row + 6)
        if v != node.source:
            a[:, r, col_of[v] : col_of[v] + 6] += np.eye(6)
        if u != node.source:
            a[:, r, col_of[u] : col_of[u] + 6] -= np.eye(6)
        a[:, r, c : c + b.shape[2]] = -b
        c += b.shape[2]
    real_cols = n_link + sum(real, np.zeros(count, dtype=int))
    _, s, vt = stacked_svd(a, full_v=True)
    assert vt is not None  # asked for (full_v)
    d = decide_ranks(s, tol, np.minimum(real_cols, a.shape[1]))
    if margin is not None:
        margin.add(d)
    # every null vector, padding columns' included: those move no link, so the target's span is the same
    solutions = np.swapaxes(vt, 1, 2) * (np.arange(vt.shape[1]) >= d.rank[:, None])[:, None, :]
    target = solutions[:, col_of[node.target] : col_of[node.target] + 6]
    real_solutions = real_cols - d.rank
    basis, wrenches, rank = span_batch(target, real_solutions, tol, margin)
    idle = sum((v.idle for v in values), np.zeros(count, dtype=int)) + real_solutions - rank
    return BatchValue(basis, rank, wrenches, idle, tuple(values))


def _direction_ranks(basis: np.ndarray, dim: np.ndarray, tol: Tolerance) -> RankDecisions:
    """The rank decision of :func:`mobility.core.screws.free_vector_subspace` (``coefficients=False``) at every pose."""
    count = len(dim)
    if basis.shape[2] == 0:
        return RankDecisions(np.zeros(count, dtype=int), np.ones(count), np.zeros(count))
    try:
        s = np.linalg.svd(basis[:, :3], compute_uv=False)
    except np.linalg.LinAlgError:
        raise AnalysisError("the singular value decomposition of a stack of direction parts did not converge") from None
    d = decide_ranks(np.concatenate([np.ones((count, 1)), s], axis=1), tol, 1 + np.minimum(dim, 3))  # 1.0 pins the scale
    r = d.rank - 1
    return RankDecisions(r, np.where(r > 0, d.smallest_kept, 1.0), d.largest_dropped)


@dataclass(frozen=True, eq=False)
class PoseAnswers:
    """The answers of :func:`mobility.analyze` at every pose (arrays of length ``N``).

    Attributes
    ----------
    dof, mobility, rotations : ndarray of int
        End-effector DOF, mobility of the whole mechanism, rotational freedoms.
    pattern : ndarray of str
    smallest_kept, largest_dropped : ndarray of float
        The margin over every rank decision of the pose.
    near_singular, inexact : ndarray of bool
    root : BatchValue
        The twist system of the ground-to-end-effector network (for actuation).
    """

    dof: np.ndarray
    pattern: np.ndarray
    mobility: np.ndarray
    rotations: np.ndarray
    smallest_kept: np.ndarray
    largest_dropped: np.ndarray
    near_singular: np.ndarray
    inexact: np.ndarray
    root: BatchValue


def analyse_poses(mechanism: Mechanism, posed: PosedScrews, tol: Tolerance = DEFAULT_TOLERANCE) -> PoseAnswers:
    """The counts and margins of :func:`mobility.analyze` at every pose of ``posed``."""
    topology = decompose(mechanism)
    count = posed.twists.shape[0]
    margin = MarginCollector(count)
    root = evaluate_batch(topology.root, posed.twists, posed.offsets, tol, margin)
    detached = sum((evaluate_batch(n, posed.twists, posed.offsets, tol, margin).mobility for n in topology.detached), np.zeros(count, dtype=int))
    rotational = _direction_ranks(root.basis, root.dim, tol)
    margin.add(rotational)
    dof = root.dim
    rot = rotational.rank
    names = np.array([pattern_of(t, r) for t in range(7) for r in range(7)], dtype=object)  # every (nT, nR) of a screw system
    pattern = names[(dof - rot) * 7 + rot]
    return PoseAnswers(
        dof=dof,
        pattern=pattern,
        mobility=root.mobility + detached,
        rotations=rot,
        smallest_kept=margin.smallest_kept,
        largest_dropped=margin.largest_dropped,
        near_singular=margin.smallest_kept < tol.near_singular,
        inexact=margin.largest_dropped > tol.inexact,
        root=root,
    )
