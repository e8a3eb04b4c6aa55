"""Screw systems of a decomposed mechanism: the series/parallel route.

Each node of the :mod:`~mobility.core.topology` tree gets the twist system of the
relative motion of its two end links, and its *idle* count (motions of the
joints inside that leave those two links still):

* joint: the span of its twists, idle 0;
* series: the span of the children's twists (union of twists);
  idle = children's idle + (twists stacked - dimension);
* parallel: the reciprocal of the union of the children's constraint wrenches
  (so the intersection of their twist systems); idle = children's idle;
* bridge: loop closure on the reduced network (unknowns: the twists of its
  inner links and coordinates on each connection's twist system; one vector
  equation per connection), its twist system the set of target twists of the
  solutions; idle = children's idle + solutions that leave the target still.

The mobility of a network is ``dimension + idle``.  Everything is computed in
normalised coordinates (:mod:`mobility.core.joint_screws`); every rank decision goes
through the one tolerance policy and its margin is kept.

Examples
--------
>>> from mobility.core.model import Joint, Mechanism
>>> from mobility.core.topology import decompose
>>> from mobility.core.joint_screws import joint_screws
>>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
>>> m = Mechanism("four-bar", "g", "c", (R("A", "g", "k", (0, 0, 0)), R("B", "k", "c", (1, 2, 0)),
...                                        R("C", "c", "r", (4, 2.5, 0)), R("D", "r", "g", (5, 0, 0))))
>>> v = evaluate_node(decompose(m).root, joint_screws(m))
>>> v.dim, v.idle
(1, 0)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator, NamedTuple

import numpy as np

from .joint_screws import JointScrews
from .linalg import left_svd, left_svds, svd
from .screws import SWAP_ROWS
from .tolerance import DEFAULT_TOLERANCE, RankDecision, Tolerance, decide_rank
from .topology import Bridge, JointNode, Node, Parallel, Series

__all__ = ["SystemValue", "MarginTracker", "evaluate_node", "subtree_values"]


@dataclass
class MarginTracker:
    """The worst margins met so far over a series of rank decisions (mutable; see :class:`~mobility.core.tolerance.RankDecision`).

    The analysis turns it into the frozen :class:`~mobility.core.result.Margin` of its result.

    Examples
    --------
    >>> from mobility.core.tolerance import RankDecision
    >>> t = MarginTracker()
    >>> t.add(RankDecision(2, 0.5, 1e-16)); t.add(RankDecision(1, 0.9, 1e-13))
    >>> t.smallest_kept, t.largest_dropped
    (0.5, 1e-13)
    """

    smallest_kept: float = 1.0
    largest_dropped: float = 0.0

    def add(self, d: RankDecision) -> None:
        """Take one more decision into account."""
        if d.smallest_kept < self.smallest_kept:
            self.smallest_kept = d.smallest_kept
        if d.largest_dropped > self.largest_dropped:
            self.largest_dropped = d.largest_dropped


class SystemValue(NamedTuple):
    """Twist system of a node, in normalised coordinates.

    Attributes
    ----------
    basis : ndarray, shape (6, d)
        Orthonormal basis of the twist system.
    wrenches : ndarray, shape (6, 6 - d)
        Basis of the constraint wrench system (reciprocal to ``basis``).
    idle : int
        Motions inside the node that leave its two end links still.
    children : tuple of SystemValue
        Values of the composite children (every child for a parallel node).
    """

    basis: np.ndarray
    wrenches: np.ndarray
    idle: int
    children: tuple["SystemValue", ...] = ()

    @property
    def dim(self) -> int:
        """Dimension of the twist system."""
        return self.basis.shape[1]

    @property
    def mobility(self) -> int:
        """Mobility of the network with one end link fixed."""
        return self.basis.shape[1] + self.idle


def _span(m: np.ndarray, tol: Tolerance, margin: MarginTracker) -> tuple[np.ndarray, np.ndarray]:
    """Orthonormal basis of the column span of ``m`` and its reciprocal system (one SVD, left vectors only)."""
    u, s = left_svd(m)
    d = decide_rank(s, tol)
    margin.add(d)
    return u[:, : d.rank], u[SWAP_ROWS, d.rank :]


def evaluate_node(node: Node, screws: JointScrews, tol: Tolerance = DEFAULT_TOLERANCE, margin: MarginTracker | None = None) -> SystemValue:
    """Twist system, wrench system and idle count of ``node``.

    The nodes are evaluated level by level from the leaves (no recursion, so
    a tree nested as deep as a long ladder of loops costs what a flat one
    does), and the matrices of one level that have the same shape (the limbs
    of a parallel mechanism) are decomposed by one call
    (:func:`~mobility.core.linalg.left_svds`): the same numbers as one call
    each, without paying the call's overhead once per limb.

    Parameters
    ----------
    node : Node
        A node of the decomposition.
    screws : JointScrews
        Joint twists of the mechanism.
    tol : Tolerance
        The rank policy.
    margin : MarginTracker, optional
        Collects the margins of every rank decision made.
    """
    if margin is None:
        margin = MarginTracker()
    values: dict[int, SystemValue] = {}  # by id of the node
    for level in _levels(node):
        pending = []
        for n, children in level:
            if isinstance(n, Bridge):
                values[id(n)] = _bridge(n, [values[id(c)] for c in children], screws, tol, margin)
            else:
                pending.append((n, children, _matrix(n, [values[id(c)] for c in children], screws)))
        for (n, children, m), (u, s) in zip(pending, left_svds([m for _, _, m in pending])):
            d = decide_rank(s, tol)
            margin.add(d)
            values[id(n)] = _value(n, [values[id(c)] for c in children], m, u, d.rank)
    return values[id(node)]


def _levels(node: Node) -> list[list[tuple[Node, list[Node]]]]:
    """The nodes of the tree that get a value, with their children that do, grouped by height (leaves first)."""
    levels: list[list[tuple[Node, list[Node]]]] = []
    height: dict[int, int] = {}
    stack: list[tuple[Node, bool]] = [(node, False)]
    while stack:
        n, ready = stack.pop()
        children = [] if type(n) is JointNode else _composite_children(n)
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


def _composite_children(node: Series | Parallel | Bridge) -> list[Node]:
    """The children of ``node`` that get a value of their own (every child of a parallel node)."""
    if isinstance(node, Parallel):
        return list(node.children)
    children = [c for _, _, c in node.edges] if isinstance(node, Bridge) else node.children
    return [c for c in children if type(c) is not JointNode]


def _matrix(node: JointNode | Series | Parallel, values: list[SystemValue], screws: JointScrews) -> np.ndarray:
    """The matrix whose span a joint, series or parallel node is: twists stacked, or (parallel) constraint wrenches stacked."""
    if type(node) is JointNode:
        return screws.of_joint(node.index)
    if isinstance(node, Parallel):
        return np.concatenate([v.wrenches for v in values], axis=1)
    composite = iter(values)
    joint_columns = screws.columns
    return np.concatenate([joint_columns[c.index] if type(c) is JointNode else next(composite).basis for c in node.children], axis=1)


def _value(node: Node, values: list[SystemValue], m: np.ndarray, u: np.ndarray, rank: int) -> SystemValue:
    """The value of a joint, series or parallel node from the left singular vectors of its matrix and its rank."""
    span, reciprocal = u[:, :rank], u[SWAP_ROWS, rank:]
    if type(node) is JointNode:
        return SystemValue(span, reciprocal, 0)
    idle = sum(v.idle for v in values)
    if isinstance(node, Parallel):  # the span of the constraint wrenches; its reciprocal is the twist system
        return SystemValue(reciprocal, span, idle, tuple(values))
    return SystemValue(span, reciprocal, idle + m.shape[1] - rank, tuple(values))


def _bridge(node: Bridge, values: list[SystemValue], screws: JointScrews, tol: Tolerance, margin: MarginTracker) -> SystemValue:
    """Loop closure of a network that does not reduce (incidence form), from the values of its composite connections."""
    composite = iter(values)
    bases = [screws.of_joint(child.index) if type(child) is JointNode else next(composite).basis for _, _, child in node.edges]
    inner = [x for x in node.links if x != node.source]
    col_of = {x: 6 * i for i, x in enumerate(inner)}
    n_link = 6 * len(inner)
    n_coord = sum(b.shape[1] for b in bases)
    a = np.zeros((6 * len(node.edges), n_link + n_coord))
    c = n_link
    for row, ((u, v, _), b) in enumerate(zip(node.edges, bases)):
        r = slice(6 * row, 6 * row + 6)
        if v != node.source:
            a[r, col_of[v] : col_of[v] + 6] += np.eye(6)
        if u != node.source:
            a[r, col_of[u] : col_of[u] + 6] -= np.eye(6)
        a[r, c : c + b.shape[1]] = -b
        c += b.shape[1]
    _, s, vt = svd(a)
    d = decide_rank(s, tol)
    margin.add(d)
    solutions = vt[d.rank :].T
    target = solutions[col_of[node.target] : col_of[node.target] + 6]
    basis, wrenches = _span(target, tol, margin)
    idle = sum(v.idle for v in values) + solutions.shape[1] - basis.shape[1]
    return SystemValue(basis, wrenches, idle, tuple(values))


def subtree_values(node: Node, value: SystemValue) -> Iterator[tuple[Node, SystemValue | None]]:
    """Every node of the subtree of ``node`` (parents first) with its value from :func:`evaluate_node`.

    A joint inside a series or a bridge has no value of its own (its twists
    enter its parent's matrix directly): ``None`` is given for it.

    Examples
    --------
    >>> from mobility.core.model import Joint, Mechanism
    >>> from mobility.core.topology import decompose, describe
    >>> from mobility.core.joint_screws import joint_screws
    >>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
    >>> m = Mechanism("two limbs", "g", "e", (R("A1", "g", "x", (0, 0, 0)), R("A2", "x", "e", (1, 0, 0)),
    ...                                      R("B1", "g", "y", (0, 1, 0)), R("B2", "y", "e", (1, 1, 0))))
    >>> root = decompose(m).root
    >>> [(describe(n), None if v is None else v.dim) for n, v in subtree_values(root, evaluate_node(root, joint_screws(m)))]
    [('parallel(series(A1,A2), series(B1,B2))', 1), ('series(A1,A2)', 2), ('A1', None), ('A2', None), ('series(B1,B2)', 2), ('B1', None), ('B2', None)]
    """
    stack: list[tuple[Node, SystemValue | None]] = [(node, value)]
    while stack:
        n, v = stack.pop()
        yield n, v
        if isinstance(n, JointNode):
            continue
        assert v is not None  # only a joint inside a series or a bridge has no value
        children = [c for _, _, c in n.edges] if isinstance(n, Bridge) else list(n.children)
        paired: list[tuple[Node, SystemValue | None]]
        if isinstance(n, Parallel):  # a parallel node keeps every child's value
            paired = list(zip(children, v.children))
        else:  # series and bridge nodes keep the values of their composite children only
            values = iter(v.children)
            paired = [(c, None if isinstance(c, JointNode) else next(values)) for c in children]
        stack.extend(reversed(paired))
