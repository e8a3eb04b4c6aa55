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
>>> v = evaluate(decompose(m).root, joint_screws(m))
>>> v.dim, v.idle
(1, 0)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .joint_screws import JointScrews
from .linalg import svd
from .screws import SWAP_ROWS
from .tolerance import DEFAULT_TOLERANCE, RankDecision, Tolerance, decide_rank
from .topology import Bridge, JointNode, Node, Parallel, Series

__all__ = ["SystemValue", "Margin", "evaluate"]


@dataclass
class Margin:
    """Worst margins over a set of rank decisions (see :class:`~mobility.core.tolerance.RankDecision`)."""

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


def _span(m: np.ndarray, tol: Tolerance, margin: Margin) -> tuple[np.ndarray, np.ndarray]:
    """Orthonormal basis of the column span of ``m`` and its reciprocal system (one SVD)."""
    u, s, _ = svd(m)
    d = decide_rank(s, tol)
    margin.add(d)
    return u[:, : d.rank], u[SWAP_ROWS, d.rank :]


def evaluate(node: Node, screws: JointScrews, tol: Tolerance = DEFAULT_TOLERANCE, margin: Margin | None = None) -> SystemValue:
    """Twist system, wrench system and idle count of ``node``.

    Parameters
    ----------
    node : Node
        A node of the decomposition.
    screws : JointScrews
        Joint twists of the mechanism.
    tol : Tolerance
        The rank policy.
    margin : Margin, optional
        Collects the margins of every rank decision made.
    """
    if margin is None:
        margin = Margin()
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
                v = evaluate(child, screws, tol, margin)
                values.append(v)
                columns.append(v.basis)
                idle += v.idle
        stacked = np.concatenate(columns, axis=1)
        basis, wrenches = _span(stacked, tol, margin)
        return SystemValue(basis, wrenches, idle + stacked.shape[1] - basis.shape[1], tuple(values))
    if isinstance(node, Parallel):
        values = [evaluate(child, screws, tol, margin) for child in node.children]
        wrenches, basis = _span(np.concatenate([v.wrenches for v in values], axis=1), tol, margin)
        return SystemValue(basis, wrenches, sum(v.idle for v in values), tuple(values))
    return _bridge(node, screws, tol, margin)


def _bridge(node: Bridge, screws: JointScrews, tol: Tolerance, margin: Margin) -> SystemValue:
    """Loop closure of a network that does not reduce (incidence form)."""
    values = []
    bases = []
    for _, _, child in node.edges:
        if isinstance(child, JointNode):
            bases.append(screws.of_joint(child.index))
            values.append(None)
        else:
            v = evaluate(child, screws, tol, margin)
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

