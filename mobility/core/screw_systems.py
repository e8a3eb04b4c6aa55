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
from .linalg import svd
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
    """Orthonormal basis of the column span of ``m`` and its reciprocal system (one SVD)."""
    u, s, _ = svd(m)
    d = decide_rank(s, tol)
    margin.add(d)
    return u[:, : d.rank], u[SWAP_ROWS, d.rank :]


def evaluate_node(node: Node, screws: JointScrews, tol: Tolerance = DEFAULT_TOLERANCE, margin: MarginTracker | None = None) -> SystemValue:
    """Twist system, wrench system and idle count of ``node``.

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
    if isinstance(node, JointNode):
        basis, wrenches = _span(screws.of_joint(node.index), tol, margin)
        return SystemValue(basis, wrenches, 0)
    if isinstance(node, Series):
        columns, idle, values = [], 0, []
        joint_columns = screws.columns
        for child in node.children:
            if type(child) is JointNode:
                columns.append(joint_columns[child.index])
            else:
                v = evaluate_node(child, screws, tol, margin)
                values.append(v)
                columns.append(v.basis)
                idle += v.idle
        stacked = np.concatenate(columns, axis=1)
        basis, wrenches = _span(stacked, tol, margin)
        return SystemValue(basis, wrenches, idle + stacked.shape[1] - basis.shape[1], tuple(values))
    if isinstance(node, Parallel):
        values = [evaluate_node(child, screws, tol, margin) for child in node.children]
        wrenches, basis = _span(np.concatenate([v.wrenches for v in values], axis=1), tol, margin)
        return SystemValue(basis, wrenches, sum(v.idle for v in values), tuple(values))
    return _bridge(node, screws, tol, margin)


def _bridge(node: Bridge, screws: JointScrews, tol: Tolerance, margin: MarginTracker) -> SystemValue:
    """Loop closure of a network that does not reduce (incidence form)."""
    values = []
    bases = []
    for _, _, child in node.edges:
        if isinstance(child, JointNode):
            bases.append(screws.of_joint(child.index))
            values.append(None)
        else:
            v = evaluate_node(child, screws, tol, margin)
            bases.append(v.basis)
            values.append(v)
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
    idle = sum(v.idle for v in values if v is not None) + solutions.shape[1] - basis.shape[1]
    return SystemValue(basis, wrenches, idle, tuple(v for v in values if v is not None))


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
        children = [c for _, _, c in n.edges] if isinstance(n, Bridge) else list(n.children)
        if isinstance(n, Parallel):  # a parallel node keeps every child's value
            paired = list(zip(children, v.children))
        else:  # series and bridge nodes keep the values of their composite children only
            values = iter(v.children)
            paired = [(c, None if isinstance(c, JointNode) else next(values)) for c in children]
        stack.extend(reversed(paired))
