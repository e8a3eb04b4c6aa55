"""The loop-closure route: one constraint Jacobian for the whole joint graph.

A second route to the answers of :func:`mobility.analyze`, without the
series/parallel decomposition, to cross-check it.  A breadth-first spanning
tree from the ground makes each link's twist ``t_x = P_x q'``; each chord
``j`` from ``a`` to ``b`` closes a loop, ``P_b q' - P_a q' - S_j q'_j = 0``;
each coupling adds a row (:func:`~mobility.core.couplings.coupling_rows`).
Stacked, ``K q' = 0``: the mobility is ``sum f - rank K`` and the end
effector's twists ``P_ee null(K)``.  ``null(K)`` comes from one SVD up to
:data:`WHOLE_SVD_SIZE`, beyond it chord by chord on the rates that close the
loops so far (time and memory grow with the joints, not their square; the
same counts, the margin the worst over the chords).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import RequestError, shown_argument
from .frozen import ReadOnlyArrays, read_only, read_only_cached_property
from .couplings import coupling_rows
from .joint_screws import JointScrews, joint_screws
from .linalg import svd
from .model import Mechanism, require_mechanism
from .screws import span_and_reciprocal
from .tolerance import DEFAULT_TOLERANCE, RankDecision, Tolerance, decide_rank, require_tolerance
from .topology import TreeEdge, spanning_tree

__all__ = ["LoopClosure", "loop_closure", "WHOLE_SVD_SIZE"]

WHOLE_SVD_SIZE = 300
"""Largest loop-closure Jacobian (rows and columns) ``method="auto"`` decomposes by one SVD; a 1,200 x 400 one takes a second, its chords milliseconds."""

Terms = tuple[tuple[int, float], ...]
"""One loop's equation: ``(joint, sign)`` pairs, the equation being ``sum sign * S_joint q'_joint = 0``."""


@dataclass(frozen=True)
class LoopClosure(ReadOnlyArrays):
    """Answers of the loop-closure route.

    Attributes
    ----------
    rank, loops, mobility : int
        Rank of ``jacobian``, chords of the spanning tree, ``sum f - rank``.
    end_effector_twists : ndarray, shape (6, dof)
        Orthonormal basis of the end effector's twists in normalised
        coordinates (:attr:`world_twists` compares with :attr:`mobility.Result.twists`).
    end_effector_map : ndarray, shape (6, sum f)
        The end effector's twist as a function of the joint rates.
    joint_rates : ndarray, shape (sum f, mobility)
        Orthonormal basis of the joint rates that close every loop.
    decision : RankDecision
    jacobian : ndarray, shape (6 * loops + couplings, sum f)
        The equations in normalised coordinates, coupling rows last (built on first access).
    couplings : ndarray, shape (couplings, sum f)
    """

    rank: int
    loops: int
    mobility: int
    end_effector_twists: np.ndarray
    end_effector_map: np.ndarray
    joint_rates: np.ndarray
    decision: RankDecision
    equations: tuple[Terms, ...] = field(repr=False)
    screws: JointScrews = field(repr=False)
    couplings: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)), repr=False)

    @read_only_cached_property
    def world_twists(self) -> np.ndarray:
        """``end_effector_twists`` in the global frame and the file's length unit, as rows ``[w; v]`` like :attr:`mobility.Result.twists` (a basis, not orthonormal there).

        Examples
        --------
        >>> import mobility
        >>> from mobility.core.screws import same_subspace
        >>> m = mobility.load("mechanisms/3prs.yaml")
        >>> lc, result = mobility.loop_closure(m), mobility.analyze(m)
        >>> same_subspace(lc.world_twists.T, result.twists.T), same_subspace(lc.end_effector_twists, result.twists.T)
        (True, False)
        """
        return self.screws.normalisation.to_world(self.end_effector_twists).T

    @read_only_cached_property
    def jacobian(self) -> np.ndarray:
        """The loop-closure equations ``K`` as one dense matrix (6 rows per loop)."""
        return np.concatenate([_dense(self.equations, self.screws), self.couplings.reshape(-1, self.screws.twists.shape[1])])

    def __setstate__(self, state: dict[str, Any]) -> None:
        super().__setstate__(state)
        screws = state.get("screws")
        if isinstance(screws, JointScrews):  # unpickled (or deep-copied) with the rest: new arrays, frozen in place
            read_only((screws.twists, screws.reference, screws.columns, screws.reference_in_world, screws.normalisation.centre), copy=False)


def loop_closure(mechanism: Mechanism, tol: Tolerance = DEFAULT_TOLERANCE, *, method: str = "auto") -> LoopClosure:
    """Loop-closure equations of the whole mechanism, their rank and the end effector's twists.

    ``method`` is ``"svd"`` (one SVD of the whole Jacobian), ``"chords"`` or
    ``"auto"`` (the first up to :data:`WHOLE_SVD_SIZE`).

    Examples
    --------
    >>> import mobility
    >>> four_bar = mobility.load("mechanisms/four_bar.yaml")
    >>> lc = loop_closure(four_bar)
    >>> lc.mobility, lc.rank, lc.loops, lc.end_effector_twists.shape[1]
    (1, 3, 1, 1)
    >>> loop_closure(four_bar, method="chords").mobility
    1
    """
    mechanism = require_mechanism(mechanism, "loop_closure")
    tol = require_tolerance(tol, "loop_closure")
    if not isinstance(method, str) or method not in ("auto", "svd", "chords"):
        shown = shown_argument(method) if isinstance(method, str) else type(method).__name__
        raise RequestError(caller="loop_closure", argument="method", expected="'auto', 'svd' or 'chords'", got=shown)
    screws = joint_screws(mechanism)
    n = screws.twists.shape[1]
    tree, chords = spanning_tree(mechanism)
    up = {edge.child: edge for edge in tree}
    depth = {mechanism.ground: 0}
    for edge in tree:  # breadth-first: a parent comes first
        depth[edge.child] = depth[edge.parent] + 1
    equations = tuple(_tree_path(up, depth, *mechanism.joints[c].links) + ((c, -1.0),) for c in chords)
    ee_map = np.zeros((6, n))
    for joint, sign in _tree_path(up, depth, mechanism.ground, mechanism.end_effector):
        lo, hi = screws.offsets[joint], screws.offsets[joint + 1]
        ee_map[:, lo:hi] += sign * screws.twists[:, lo:hi]
    couplings = _coupling_rows(mechanism, screws)
    whole = method == "svd" or (method == "auto" and max(6 * len(equations) + len(couplings), n) <= WHOLE_SVD_SIZE)
    if not equations and not len(couplings):
        decision, rates = RankDecision(0), np.eye(n)
    elif whole:
        _, s, vt = svd(np.concatenate([_dense(equations, screws), couplings]))
        decision = decide_rank(s, tol)
        rates = vt[decision.rank :].T
    else:
        decision, rates = _chord_by_chord(equations, screws, tol, couplings)
    ee = span_and_reciprocal(ee_map @ rates, tol).basis
    return LoopClosure(decision.rank, len(equations), n - decision.rank, ee, ee_map, rates, decision, equations, screws, couplings)


def _coupling_rows(mechanism: Mechanism, screws: JointScrews) -> np.ndarray:
    """One row on every joint column per coupling of ``mechanism``."""
    rows = np.zeros((len(mechanism.couplings), screws.twists.shape[1]))
    index = {j.name: i for i, j in enumerate(mechanism.joints)}
    for row, coupling in zip(rows, mechanism.couplings):
        columns = [screws.offsets[index[name]] for name in coupling.joints]
        row[columns] = coupling_rows(screws.twists[None], columns, coupling.coefficients, mechanism.joints[index[coupling.joints[0]]].type == "P")[0]
    return rows


def _tree_path(up: dict[str, TreeEdge], depth: dict[str, int], a: str, b: str) -> Terms:
    """The tree joints between links ``a`` and ``b`` with the signs of ``P_b - P_a`` (the common part cancels)."""
    from_a: list[tuple[int, float]] = []
    from_b: list[tuple[int, float]] = []
    while a != b:
        if depth[a] >= depth[b]:
            edge = up[a]
            from_a.append((edge.joint, -1.0 if edge.forward else 1.0))
            a = edge.parent
        else:
            edge = up[b]
            from_b.append((edge.joint, 1.0 if edge.forward else -1.0))
            b = edge.parent
    return tuple(from_a) + tuple(reversed(from_b))


def _columns(terms: Terms, screws: JointScrews) -> tuple[list[int], np.ndarray]:
    """The variables of one loop equation and its 6 x k matrix on them."""
    variables: list[int] = []
    blocks = []
    for joint, sign in terms:
        lo, hi = int(screws.offsets[joint]), int(screws.offsets[joint + 1])
        variables.extend(range(lo, hi))
        blocks.append(sign * screws.twists[:, lo:hi])
    return variables, np.concatenate(blocks, axis=1)


def _dense(equations: tuple[Terms, ...], screws: JointScrews) -> np.ndarray:
    n = screws.twists.shape[1]
    k = np.zeros((6 * len(equations), n))
    for row, terms in enumerate(equations):
        variables, block = _columns(terms, screws)
        k[6 * row : 6 * row + 6, variables] = block  # each joint once: tree joints and the chord
    return k


def _chord_by_chord(equations: tuple[Terms, ...], screws: JointScrews, tol: Tolerance, couplings: np.ndarray) -> tuple[RankDecision, np.ndarray]:
    """Null space of the loop equations, one chord at a time (see the module docstring), then of the coupling rows, one at a time."""
    n = screws.twists.shape[1]
    row_of: dict[int, int] = {}  # variable -> row of `basis`
    basis = np.zeros((0, 0))  # orthonormal basis of the rates of the variables met so far that close the loops so far
    kept, dropped, rank = 1.0, 0.0, 0
    coupled = [(np.flatnonzero(c).tolist(), c[np.flatnonzero(c)][None]) for c in couplings]
    for variables, block in [_columns(terms, screws) for terms in equations] + coupled:
        new = [v for v in dict.fromkeys(variables) if v not in row_of]
        if new:
            grown = np.zeros((basis.shape[0] + len(new), basis.shape[1] + len(new)))
            grown[: basis.shape[0], : basis.shape[1]] = basis
            grown[basis.shape[0] :, basis.shape[1] :] = np.eye(len(new))
            for v in new:
                row_of[v] = len(row_of)
            basis = grown
        restricted = block @ basis[[row_of[v] for v in variables]]  # the chord's equations on the current solutions
        _, s, vt = svd(restricted)
        d = decide_rank(s, tol)
        kept, dropped, rank = min(kept, d.smallest_kept), max(dropped, d.largest_dropped), rank + d.rank
        basis = basis @ vt[d.rank :].T
    rates = np.zeros((n, basis.shape[1] + n - len(row_of)))
    rows = np.fromiter(row_of.keys(), dtype=int, count=len(row_of))
    rates[rows, : basis.shape[1]] = basis[np.fromiter(row_of.values(), dtype=int, count=len(row_of))]
    free = np.setdiff1d(np.arange(n), rows)  # variables of no loop: free
    rates[free, basis.shape[1] + np.arange(len(free))] = 1.0
    return RankDecision(rank, kept, dropped), rates
