"""The loop-closure route: one constraint Jacobian for the whole joint graph.

An independent second route to the answers of :func:`mobility.analyze`, used
to cross-check it (tests, benchmarks) and available to users.  It does not
use the series/parallel decomposition:

1. a spanning tree of the joint graph is grown from the ground (breadth-first);
   every link's twist is then a linear map of the joint rates along its tree
   path, ``t_x = P_x q'``;
2. each joint off the tree (a *chord*, including a second joint between two
   already joined links) closes one independent loop:
   ``P_b q' - P_a q' - S_j q'_j = 0`` for a chord ``j`` from ``a`` to ``b``;
3. stacked, these are the loop-closure equations ``K q' = 0``; the mobility is
   ``sum f - rank K`` and the end effector's twist system is
   ``P_ee null(K)``.

Examples
--------
>>> from mobility.core.model import Joint, Mechanism
>>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
>>> m = Mechanism("four-bar", "g", "c", (R("A", "g", "k", (0, 0, 0)), R("B", "k", "c", (1, 2, 0)),
...                                        R("C", "c", "r", (4, 2.5, 0)), R("D", "r", "g", (5, 0, 0))))
>>> lc = loop_closure(m)
>>> lc.mobility, lc.rank, lc.loops, lc.end_effector_twists.shape[1]
(1, 3, 1, 1)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .joint_screws import joint_screws
from .linalg import svd
from .model import Mechanism
from .screws import span_and_reciprocal
from .tolerance import DEFAULT_TOLERANCE, RankDecision, Tolerance, decide_rank
from .topology import spanning_tree

__all__ = ["LoopClosure", "loop_closure"]


@dataclass(frozen=True)
class LoopClosure:
    """Answers of the loop-closure route.

    Attributes
    ----------
    jacobian : ndarray, shape (6 * loops, sum f)
        Loop-closure equations in normalised coordinates.
    rank : int
        Rank of ``jacobian``.
    loops : int
        Independent loops (chords of the spanning tree).
    mobility : int
        ``sum f - rank``.
    end_effector_twists : ndarray, shape (6, dof)
        Orthonormal basis of the end effector's twist system, normalised coordinates.
    end_effector_map : ndarray, shape (6, sum f)
        Twist of the end effector as a function of the joint rates (tree path).
    joint_rates : ndarray, shape (sum f, mobility)
        Basis of the joint rates that close every loop.
    decision : RankDecision
    """

    jacobian: np.ndarray
    rank: int
    loops: int
    mobility: int
    end_effector_twists: np.ndarray
    end_effector_map: np.ndarray
    joint_rates: np.ndarray
    decision: RankDecision


def loop_closure(mechanism: Mechanism, tol: Tolerance = DEFAULT_TOLERANCE) -> LoopClosure:
    """Loop-closure Jacobian of the whole mechanism, its rank and the end effector's twists."""
    screws = joint_screws(mechanism)
    n = screws.twists.shape[1]
    tree, chords = spanning_tree(mechanism)
    path_map: dict[str, np.ndarray] = {mechanism.ground: np.zeros((6, n))}
    for edge in tree:
        p = path_map[edge.parent].copy()
        lo, hi = screws.offsets[edge.joint], screws.offsets[edge.joint + 1]
        p[:, lo:hi] += (1.0 if edge.forward else -1.0) * screws.twists[:, lo:hi]
        path_map[edge.child] = p
    rows = []
    for index in chords:
        a, b = mechanism.joints[index].links
        k = path_map[b] - path_map[a]
        lo, hi = screws.offsets[index], screws.offsets[index + 1]
        k[:, lo:hi] -= screws.twists[:, lo:hi]
        rows.append(k)
    jacobian = np.vstack(rows) if rows else np.zeros((0, n))
    if rows:
        _, s, vt = svd(jacobian)
        decision = decide_rank(s, tol)
        rates = vt[decision.rank :].T
    else:
        decision = RankDecision(0)
        rates = np.eye(n)
    ee_map = path_map[mechanism.end_effector]
    ee = span_and_reciprocal(ee_map @ rates, tol).basis
    return LoopClosure(jacobian, decision.rank, len(rows), n - decision.rank, ee, ee_map, rates, decision)
