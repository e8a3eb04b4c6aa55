"""Screw systems of a decomposed mechanism at a stack of poses: the series/parallel route (README, "How it works").

Each node of the :mod:`~mobility.core.topology` tree gets, pose by pose, the
twist system between its two end links and its *idle* count (inner motions
that leave them still; mobility = dimension + idle):

* joint: the span of its twists, idle 0;
* series: the span of the children's twists; idle = children's + (stacked - dimension);
* parallel: the reciprocal of the union of the children's constraint wrenches;
  idle = children's;
* bridge: loop closure on the reduced network (one vector equation per
  connection, one per coupling: :func:`mobility.core.couplings.coupling_rows`);
  its system the target twists of the solutions, idle = children's +
  solutions that leave the target still.

All in normalised coordinates (:mod:`mobility.core.joint_screws`), every rank
by :func:`~mobility.core.tolerance.decide_ranks` with its margin kept; a rank
that varies over the stack pads with zero columns (docs/sweeps.md, "How it is
fast").  Nodes go level by level from the leaves (no recursion), one level's
same-shape matrices to LAPACK as one stack.
"""

from __future__ import annotations

from typing import Iterator, NamedTuple, Sequence, Union, cast

import numpy as np

from .couplings import coupling_rows
from .joint_screws import per_object_cache
from .linalg import left_svds, singular_values
from .screws import SWAP_ROWS, pattern_of
from .tolerance import DEFAULT_TOLERANCE, ROW_BY_ROW, Tolerance, decide_few, decide_ranks
from .topology import Bridge, JointNode, Node, Parallel, Topology, _children

__all__ = ["PerPose", "Systems", "Margins", "evaluate", "subtree_values", "span", "direction_ranks", "per_pose", "at_pose", "PoseAnswers", "analyse_poses"]


PerPose = Union[int, np.ndarray]
"""A count at each pose of a stack: an int when it is the same at every pose, else an array of one per pose."""


class Systems(NamedTuple):
    """Twist system of a node at ``N`` poses (normalised coordinates of each pose).

    ``basis`` (N, 6, k) and ``wrenches`` (N, 6, k') are orthonormal bases of
    the twist and constraint systems, zero beyond ``dim`` and ``6 - dim``
    columns; ``dim`` and ``idle`` are :data:`PerPose` counts; ``children`` the
    values of the composite children (every child of a parallel node).

    Examples
    --------
    >>> Systems(np.zeros((1, 6, 0)), 0, np.eye(6)[None], 2).mobility
    2
    """

    basis: np.ndarray
    dim: PerPose
    wrenches: np.ndarray
    idle: PerPose
    children: tuple["Systems", ...] = ()

    @property
    def mobility(self) -> PerPose:
        """Mobility of the network with one end link fixed."""
        return self.dim + self.idle


class Margins:
    """The worst margins over the rank decisions of each pose (as :class:`mobility.core.result.Margin` has them).

    Examples
    --------
    >>> m = Margins(2)
    >>> m.add(np.array([0.5, 1.0, 0.9, 0.2]), np.array([1e-16, 0.0, 1e-13, 0.0]))
    >>> m.smallest_kept.tolist(), m.largest_dropped.tolist()
    ([0.5, 0.2], [1e-13, 0.0])
    """

    def __init__(self, count: int) -> None:
        self.count = count
        self._kept: list[np.ndarray | Sequence[float]] = []
        self._dropped: list[np.ndarray | Sequence[float]] = []

    def add(self, kept: np.ndarray | Sequence[float], dropped: np.ndarray | Sequence[float]) -> None:
        """Take decisions into account, by their smallest kept and largest dropped values: one per pose, or several stacks of one per pose, stack after stack."""
        self._kept.append(kept)
        self._dropped.append(dropped)

    @property
    def smallest_kept(self) -> np.ndarray:
        """The smallest kept singular value (relative) of each pose, 1.0 where none was kept."""
        if not self._kept:
            return np.ones(self.count)
        if self.count == 1:  # one pose: the least of a few numbers, in Python (less overhead than joining arrays)
            return np.array([min([min(_numbers(k)) for k in self._kept])])
        return np.concatenate(self._kept).reshape(-1, self.count).min(axis=0)

    @property
    def largest_dropped(self) -> np.ndarray:
        """The largest dropped singular value (relative) of each pose, 0.0 where none was dropped."""
        if not self._dropped:
            return np.zeros(self.count)
        if self.count == 1:
            return np.array([max([max(_numbers(d)) for d in self._dropped])])
        return np.concatenate(self._dropped).reshape(-1, self.count).max(axis=0)


def _numbers(values: np.ndarray | Sequence[float]) -> Sequence[float]:
    return values.tolist() if isinstance(values, np.ndarray) else values


def _decided(s: np.ndarray, tol: Tolerance, counts: PerPose | Sequence[int], margins: Margins | None) -> tuple[PerPose, int, int]:
    """The ranks of a stack from its singular values ``s`` (an int when every matrix has the same), the least and the greatest; the margins go to ``margins`` if given.

    A few matrices are decided in Python (:func:`~mobility.core.tolerance.decide_few`):
    at one pose no array is built for numbers read one by one.
    """
    if len(s) <= ROW_BY_ROW:
        ranks, kept, dropped = decide_few(s, tol, counts)
        if margins is not None:
            margins.add(kept, dropped)
        low, high = min(ranks), max(ranks)
        return (low if low == high else np.array(ranks)), low, high
    d = decide_ranks(s, tol, counts)
    if margins is not None:
        margins.add(d.smallest_kept, d.largest_dropped)
    low, high = _extremes(d.rank)
    return (low if low == high else d.rank), low, high


def _extremes(rank: np.ndarray) -> tuple[int, int]:
    """The least and the greatest rank of a stack (of a few, in Python: less overhead)."""
    if len(rank) > ROW_BY_ROW:
        return int(rank.min()), int(rank.max())
    ranks = rank.tolist()
    return min(ranks), max(ranks)


def _swapped(u: np.ndarray, low: int = 0) -> np.ndarray:
    """``u[:, SWAP_ROWS, low:]``, the reciprocal of a stack's span from its left singular vectors, the cheaper way for ``u``'s memory order.

    A C-ordered stack (of a few matrices) takes its rows whole, then views the
    columns: a third of the overhead of fancy indexing; the transposed
    problem's ``u`` of a large stack (:func:`~mobility.core.linalg.left_svds`)
    is a strided view, which fancy indexing gathers faster than ``take``.
    """
    strides = u.strides
    if strides[1] > strides[2]:  # rows apart, columns side by side: C order
        return u.take(SWAP_ROWS, axis=1)[:, :, low:]
    return u[:, SWAP_ROWS, low:]


def _split(u: np.ndarray, swapped: np.ndarray, rank: np.ndarray, low: int, high: int) -> tuple[np.ndarray, np.ndarray]:
    """The span (first ``rank`` left singular vectors ``u``) and its reciprocal (the rest of ``swapped``, ``u`` with rows swapped) of each matrix of a stack, ranks from ``low`` to ``high``."""
    if low == high:
        return u[:, :, :low], swapped[:, :, low:]
    span_ = u[:, :, :high] * (np.arange(high) < rank[:, None])[:, None, :]
    index = rank[:, None] + np.arange(6 - low)
    reciprocal = np.take_along_axis(swapped, np.minimum(index, 5)[:, None, :], axis=2) * (index < 6)[:, None, :]
    return span_, reciprocal


def span(m: np.ndarray, counts: PerPose, tol: Tolerance = DEFAULT_TOLERANCE, margins: Margins | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Span of the columns of each ``m[i]`` and its reciprocal system, by one stacked SVD.

    ``m`` is (N, 6, k), ``counts`` its columns without zero padding.  Returns
    the span (N, 6, max rank) and reciprocal (N, 6, 6 - min rank) bases, zero
    beyond each pose's count, and the ranks (N,).

    Examples
    --------
    >>> z = np.zeros((1, 6, 2)); z[0, 2, 0] = z[0, 2, 1] = 1.0   # one rotation about z, twice
    >>> basis, reciprocal, rank = span(z, np.array([2]))
    >>> rank.tolist(), basis.shape, reciprocal.shape
    ([1], (1, 6, 1), (1, 6, 5))
    """
    if len(m) == 0:
        return np.zeros((0, 6, 0)), np.zeros((0, 6, 0)), np.zeros(0, dtype=int)
    u, s, _ = left_svds(m)
    rank, low, high = _decided(s, tol, counts, margins)
    ranks = per_pose(rank, len(m))
    return (*_split(u, _swapped(u), ranks, low, high), ranks)


def evaluate(node: Node, twists: np.ndarray, offsets: Sequence[int], tol: Tolerance = DEFAULT_TOLERANCE, margins: Margins | None = None) -> Systems:
    """Twist system, wrench system and idle count of ``node`` at every pose of a stack.

    ``twists`` (N, 6, f) are the unit joint twists of each pose in its
    normalised coordinates (a locked freedom a zero column), joint ``j``'s
    columns ``offsets[j]:offsets[j+1]``; ``margins`` collects every decision's.

    Examples
    --------
    >>> import mobility
    >>> from mobility.core.topology import decompose
    >>> from mobility.core.joint_screws import joint_screws
    >>> m = mobility.load("mechanisms/four_bar.yaml")
    >>> s = joint_screws(m)
    >>> v = evaluate(decompose(m).root, s.twists[None], s.offsets)
    >>> v.dim, v.idle, v.basis.shape
    (1, 0, (1, 6, 1))
    """
    count = twists.shape[0]
    if margins is None:
        margins = Margins(count)
    values: dict[int, Systems] = {}  # by id of the node
    for level in _plan(node, tuple(offsets)):
        same_shape: dict[int, list[tuple[Step, list[Systems], np.ndarray, PerPose]]] = {}
        for step in level:
            kids = [values[id(c)] for c in step.children]
            if isinstance(step.node, Bridge):
                values[id(step.node)] = _bridge(step.node, kids, twists, offsets, tol, margins)
            else:
                m, counts = _matrix(step, kids, twists)
                same_shape.setdefault(m.shape[2], []).append((step, kids, m, counts))
        for members in same_shape.values():
            stack, stack_counts = _stacked(members, count)
            u, s, _ = left_svds(stack)
            rank, low, high = _decided(s, tol, stack_counts, margins)
            if low == high:  # one rank at every pose: the spans of the whole stack at once, the rank an int
                span_, reciprocal = u[:, :, :low], _swapped(u, low)
                if len(members) == 1:
                    values[id(members[0][0].node)] = _value(members[0][0].node, members[0][1], span_, reciprocal, low, members[0][3])
                    continue
            for i, (step, kids, m, c) in enumerate(members):
                rows = slice(i * count, (i + 1) * count)
                if low == high:
                    values[id(step.node)] = _value(step.node, kids, span_[rows], reciprocal[rows], low, c)
                else:  # each node as wide as its own greatest rank
                    own = cast(np.ndarray, rank)[rows]
                    values[id(step.node)] = _value(step.node, kids, *_split(u[rows], _swapped(u[rows]), own, *_extremes(own)), own, c)
    return values[id(node)]


def _stacked(members: list[tuple[Step, list[Systems], np.ndarray, PerPose]], count: int) -> tuple[np.ndarray, PerPose | list[int]]:
    """The matrices of same-shape nodes as one stack (node after node, each its ``count`` poses), and their column counts."""
    if len(members) == 1:
        return members[0][2], members[0][3]
    stack = np.concatenate([m for *_, m, _ in members])
    listed = [c for *_, c in members]
    if all(type(c) is int for c in listed):
        return stack, cast("list[int]", listed) if count == 1 else np.repeat(np.array(listed), count)
    return stack, np.concatenate([per_pose(c, count) for c in listed])


class Step(NamedTuple):
    """One node of the tree as :func:`evaluate` takes it: its composite children, and where its matrix's joint columns are.

    ``parts`` lists the blocks of a joint or series node's matrix: a ``slice``
    of joint twist columns (consecutive joints merged), or the index of a
    composite child in ``children``.
    """

    node: Node
    children: tuple[Node, ...]
    parts: tuple[slice | int, ...]
    joint_columns: int


def _plan(node: Node, offsets: tuple[int, ...]) -> list[list[Step]]:
    """The steps of the tree below ``node`` grouped by height, leaves first (what depends on the graph only, computed once per node)."""
    plans = per_object_cache(node, "screw_system_plan", dict)
    if offsets not in plans:
        plans[offsets] = [[_step(n, children, offsets) for n, children in level] for level in _levels(node)]
    return plans[offsets]


def _step(node: Node, children: list[Node], offsets: tuple[int, ...]) -> Step:
    if isinstance(node, (Parallel, Bridge)):
        return Step(node, tuple(children), (), 0)
    parts: list[slice | int] = []
    composite = 0
    for c in (node,) if type(node) is JointNode else node.children:
        if type(c) is JointNode:
            lo, hi = offsets[c.index], offsets[c.index + 1]
            if parts and isinstance(parts[-1], slice) and parts[-1].stop == lo:  # consecutive joints: one block
                parts[-1] = slice(parts[-1].start, hi)
            else:
                parts.append(slice(lo, hi))
        else:
            parts.append(composite)
            composite += 1
    return Step(node, tuple(children), tuple(parts), sum(p.stop - p.start for p in parts if isinstance(p, slice)))


def _levels(node: Node) -> list[list[tuple[Node, list[Node]]]]:
    """The nodes of the tree that get a value, with their children that do, grouped by height (leaves first)."""
    levels: list[list[tuple[Node, list[Node]]]] = []
    height: dict[int, int] = {}
    stack: list[tuple[Node, bool]] = [(node, False)]
    while stack:
        n, ready = stack.pop()
        children = [c for c in _children(n) if isinstance(n, Parallel) or type(c) is not JointNode]  # with a value: composite, or of a parallel node
        if children and not ready:
            stack.append((n, True))
            stack.extend((c, False) for c in reversed(children))
            continue
        h = 1 + max(height[id(c)] for c in children) if children else 0
        height[id(n)] = h
        if h == len(levels):
            levels.append([])
        levels[h].append((n, children))
    return levels


def _matrix(step: Step, values: list[Systems], twists: np.ndarray) -> tuple[np.ndarray, int | np.ndarray]:
    """The stack whose span a joint, series or parallel node is (twists, or for a parallel node constraint wrenches), and its real column counts (an int when the same at every pose)."""
    if isinstance(step.node, Parallel):
        return np.concatenate([v.wrenches for v in values], axis=2), 6 * len(values) - sum(v.dim for v in values)
    blocks = [twists[:, :, p] if type(p) is slice else values[p].basis for p in step.parts]
    m = blocks[0] if len(blocks) == 1 else np.concatenate(blocks, axis=2)
    return m, step.joint_columns + sum(v.dim for v in values) if values else step.joint_columns


def _value(node: Node, values: list[Systems], span_: np.ndarray, reciprocal: np.ndarray, rank: int | np.ndarray, counts: int | np.ndarray) -> Systems:
    """The value of a joint, series or parallel node from the span of its matrix, its reciprocal, its rank and its column count."""
    if isinstance(node, Parallel):  # the span of the constraint wrenches; its reciprocal is the twist system
        return Systems(reciprocal, 6 - rank, span_, sum(v.idle for v in values), tuple(values))
    if type(node) is JointNode:  # its twists are independent: no idle motion
        return Systems(span_, rank, reciprocal, 0)
    return Systems(span_, rank, reciprocal, counts - rank + sum(v.idle for v in values), tuple(values))


def _bridge(node: Bridge, values: list[Systems], twists: np.ndarray, offsets: Sequence[int], tol: Tolerance, margins: Margins) -> Systems:
    """Loop closure of a network that does not reduce (incidence form), from the values of its composite connections."""
    count = twists.shape[0]
    composite = iter(values)
    bases: list[np.ndarray] = []
    real: list[PerPose] = []
    for _, _, child in node.edges:
        if type(child) is JointNode:
            bases.append(twists[:, :, offsets[child.index] : offsets[child.index + 1]])
            real.append(offsets[child.index + 1] - offsets[child.index])
        else:
            value = next(composite)
            bases.append(value.basis)
            real.append(value.dim)
    inner = [x for x in node.links if x != node.source]
    col_of = {x: 6 * i for i, x in enumerate(inner)}
    n_link = 6 * len(inner)
    a = np.zeros((count, 6 * len(node.edges) + len(node.couplings), n_link + sum(b.shape[2] for b in bases)))
    c = n_link
    column_of = []  # of each edge's first coordinate: a coupled joint has one
    for row, ((u, v, _), b) in enumerate(zip(node.edges, bases)):
        column_of.append(c)
        r = slice(6 * row, 6 * row + 6)
        if v != node.source:
            a[:, r, col_of[v] : col_of[v] + 6] += np.eye(6)
        if u != node.source:
            a[:, r, col_of[u] : col_of[u] + 6] -= np.eye(6)
        a[:, r, c : c + b.shape[2]] = -b
        c += b.shape[2]
    for row, (slides, terms) in enumerate(node.couplings, start=6 * len(node.edges)):
        joints = [node.edges[e][2].index for e, _ in terms]  # type: ignore[union-attr]  # a coupled joint is an edge of its own
        a[:, row, [column_of[e] for e, _ in terms]] = coupling_rows(twists, [offsets[j] for j in joints], [x for _, x in terms], slides)
    real_cols = n_link + sum(real, np.zeros(count, dtype=int))
    _, s, vt = left_svds(a, full_v=True)
    assert vt is not None  # asked for (full_v)
    rank, low, high = _decided(s, tol, real_cols, margins)
    # the null vectors; a padding column's own (it moves no link) leaves the target's span as it is
    solutions = np.swapaxes(vt[:, low:], 1, 2)
    if high != low:
        solutions = solutions * (np.arange(low, vt.shape[1]) >= cast(np.ndarray, rank)[:, None])[:, None, :]
    target = solutions[:, col_of[node.target] : col_of[node.target] + 6]
    real_solutions = real_cols - rank
    basis, wrenches, rank = span(target, real_solutions, tol, margins)
    idle = sum((v.idle for v in values), np.zeros(count, dtype=int)) + real_solutions - rank
    return Systems(basis, rank, wrenches, idle, tuple(values))


def subtree_values(node: Node, value: Systems) -> Iterator[tuple[Node, Systems | None]]:
    """Every node of the subtree of ``node`` (parents first) with its value from :func:`evaluate`.

    A joint inside a series or a bridge has no value of its own: ``None``.

    Examples
    --------
    >>> from mobility.core.model import Joint, Mechanism
    >>> from mobility.core.topology import decompose, describe
    >>> from mobility.core.joint_screws import joint_screws
    >>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
    >>> m = Mechanism("two limbs", "g", "e", (R("A1", "g", "x", (0, 0, 0)), R("A2", "x", "e", (1, 0, 0)),
    ...                                      R("B1", "g", "y", (0, 1, 0)), R("B2", "y", "e", (1, 1, 0))))
    >>> root, s = decompose(m).root, joint_screws(m)
    >>> [(describe(n), None if v is None else v.dim) for n, v in subtree_values(root, evaluate(root, s.twists[None], s.offsets))]
    [('parallel(series(A1,A2), series(B1,B2))', 1), ('series(A1,A2)', 2), ('A1', None), ('A2', None), ('series(B1,B2)', 2), ('B1', None), ('B2', None)]
    """
    stack: list[tuple[Node, Systems | None]] = [(node, value)]
    while stack:
        n, v = stack.pop()
        yield n, v
        if isinstance(n, JointNode):
            continue
        assert v is not None  # only a joint inside a series or a bridge has no value
        values = iter(v.children)
        every = isinstance(n, Parallel)  # a parallel node keeps every child's value, others their composite children's only
        stack.extend(reversed([(c, next(values) if every or not isinstance(c, JointNode) else None) for c in _children(n)]))


def direction_ranks(basis: np.ndarray, dim: PerPose, tol: Tolerance = DEFAULT_TOLERANCE, margins: Margins | None = None) -> np.ndarray:
    """How many independent directions (rotations, for a twist system) each orthonormal screw basis of a stack holds.

    The rank of the direction parts ``basis[:, :3]`` (singular values at most
    1: the threshold is absolute), as :func:`mobility.core.screws.free_vector_subspace`
    decides it; the margin, which ``margins`` collects, says how near a screw is to a free vector.

    Examples
    --------
    >>> cylindrical = np.zeros((1, 6, 2)); cylindrical[0, 2, 0] = cylindrical[0, 5, 1] = 1.0
    >>> direction_ranks(cylindrical, np.array([2])).tolist()
    [1]
    """
    count = basis.shape[0]
    if basis.shape[2] == 0:  # no screw: nothing decided
        return np.zeros(count, dtype=int)
    rank, _, _ = _decided(singular_values(basis[:, :3]), tol, dim, margins)
    return per_pose(rank, count)


def per_pose(value: PerPose, count: int) -> np.ndarray:
    """``value`` (an int when the same at every pose, or an array) as an array of ``count`` values.

    Examples
    --------
    >>> per_pose(3, 2).tolist(), per_pose(np.array([1, 2]), 2).tolist()
    ([3, 3], [1, 2])
    """
    return value if isinstance(value, np.ndarray) else np.full(count, value)


def at_pose(value: PerPose, index: int = 0) -> int:
    """The count of pose ``index`` of a :data:`~mobility.core.screw_systems.PerPose`.

    Examples
    --------
    >>> at_pose(3), at_pose(np.array([1, 2]), 1)
    (3, 2)
    """
    return value if isinstance(value, int) else int(value[index])


_PATTERNS = np.array([[pattern_of(d - r, r) if r <= d else "" for r in range(7)] for d in range(7)], dtype=object)  # by (DOF, rotations)


class PoseAnswers(NamedTuple):
    """The counts and margins of :func:`mobility.analyze` at every pose of a stack (arrays of length ``N``).

    ``root`` is the ground-to-end-effector network's :class:`Systems`,
    ``detached`` those of networks off that path; ``rotations`` the end
    effector's rotational freedoms; the margin over every decision of a pose
    and the ``tol`` that decided.  ``dof``, ``mobility``, ``pattern``,
    ``near_singular`` and ``inexact`` follow (see :func:`analyse_poses`).
    """

    root: Systems
    detached: tuple[Systems, ...]
    rotations: np.ndarray
    smallest_kept: np.ndarray
    largest_dropped: np.ndarray
    tol: Tolerance

    @property
    def dof(self) -> np.ndarray:
        return per_pose(self.root.dim, len(self.rotations))

    @property
    def mobility(self) -> np.ndarray:
        return per_pose(sum((v.mobility for v in self.detached), self.root.mobility), len(self.rotations))

    @property
    def pattern(self) -> np.ndarray:
        return _PATTERNS[self.root.dim, self.rotations]

    @property
    def near_singular(self) -> np.ndarray:
        return self.smallest_kept < self.tol.near_singular

    @property
    def inexact(self) -> np.ndarray:
        return self.largest_dropped > self.tol.inexact


def analyse_poses(topology: Topology, twists: np.ndarray, offsets: Sequence[int], tol: Tolerance = DEFAULT_TOLERANCE) -> PoseAnswers:
    """The counts and margins of :func:`mobility.analyze` at every pose of a stack of joint twists.

    Examples
    --------
    >>> import mobility
    >>> from mobility.core.topology import decompose
    >>> from mobility.core.joint_screws import joint_screws
    >>> m = mobility.load("mechanisms/3prs.yaml")
    >>> s = joint_screws(m)
    >>> answers = analyse_poses(decompose(m), s.twists[None], s.offsets)
    >>> answers.dof.tolist(), answers.pattern.tolist(), answers.mobility.tolist()
    ([3], ['1T2R'], [3])
    """
    count = twists.shape[0]
    margins = Margins(count)
    root = evaluate(topology.root, twists, offsets, tol, margins)
    detached = tuple(evaluate(n, twists, offsets, tol, margins) for n in topology.detached)
    rotations = direction_ranks(root.basis, root.dim, tol, margins)
    return PoseAnswers(root, detached, rotations, margins.smallest_kept, margins.largest_dropped, tol)
