"""Branches: group the poses reached by the moves, and measure each branch of finite motion.

:func:`group_by_tangent` groups the poses reached by their tangent spaces;
:func:`examine_branch` repeats the moves from one pose of each branch to count
its finite mobility and take its DOF and pattern (docs/finite.md, "How it
decides", steps 5 and 6).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import cast

import numpy as np

from ..core.analysis import analyze
from .moves import MovePlan, probe_directions
from .moves import probes as probe_each
from .orders import canonical_basis, end_effector_pattern
from .parameters import MOVING_RANK, SAME_SUBSPACE
from .results import Branch, Probe, SecondOrder

__all__ = ["TangentGroup", "same_tangent", "group_by_tangent", "rank_of_moves", "tangent_from_second_order", "examine_branch"]


@dataclass
class TangentGroup:
    """Moves whose poses share one tangent space (filled while grouping).

    Attributes
    ----------
    tangent : ndarray, shape (n, m1)
        The tangent space at the first pose of the group.
    probes : list of int
        Indices of the moves (in the run's probes).
    mobility : int
        First-order mobility ``m1`` at the first pose.
    """

    tangent: np.ndarray
    mobility: int
    probes: list[int] = field(default_factory=list)


def same_tangent(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two orthonormal tangent bases of nearby poses span the same space, up to O(step).

    Examples
    --------
    >>> import numpy as np
    >>> same_tangent(np.eye(3)[:, :1], np.array([[0.99], [0.141], [0.0]])), same_tangent(np.eye(3)[:, :1], np.eye(3)[:, 1:2])
    (True, False)
    """
    if a.shape[1] != b.shape[1]:
        return False
    if a.shape[1] == 0:
        return True
    return float(np.linalg.svd(a.T @ b, compute_uv=False).min()) >= SAME_SUBSPACE


def group_by_tangent(probes: tuple[Probe, ...], k: int) -> tuple[list[TangentGroup], int]:
    """Group the moves that moved by the tangent spaces they reached, each group from its most regular pose.

    (Least mobility, then most DOF, then largest margin: a wrist turned about
    its locked axes does not stand for a branch whose other poses have more DOF.)

    Returns
    -------
    groups : list of TangentGroup
        The groups kept: those that reached poses less singular than the given
        one (mobility below ``k``), or every group when none did.
    set_aside : int
        Moves that reached poses as singular as the given one, left out
        because less singular poses exist.
    """
    moved = [i for i, p in enumerate(probes) if p.moved]
    groups: list[TangentGroup] = []
    for i in sorted(moved, key=lambda i: (probes[i].mobility, -(probes[i].dof or 0), -(probes[i].margin or 0.0))):
        p = probes[i]
        assert p.tangent is not None and p.mobility is not None  # a probe that moved was examined where it arrived
        for g in groups:
            if same_tangent(g.tangent, p.tangent):
                g.probes.append(i)
                break
        else:
            groups.append(TangentGroup(p.tangent, p.mobility, [i]))
    still_singular = [g for g in groups if g.mobility >= k]
    regular = [g for g in groups if g.mobility < k]
    set_aside = sum(len(g.probes) for g in still_singular) if regular else 0
    return regular or still_singular, set_aside


def rank_of_moves(chords: list[np.ndarray]) -> tuple[int, np.ndarray]:
    """Independent directions among unit chords, and an orthonormal basis of them.

    Examples
    --------
    >>> import numpy as np
    >>> r, basis = rank_of_moves([np.array([1.0, 0, 0]), np.array([0.999, 0.045, 0]), np.array([0.0, 1, 0])])
    >>> r, basis.shape
    (2, (3, 2))
    """
    if not chords:
        return 0, np.zeros((0, 0))
    m = np.array(chords).T
    u, s, _ = np.linalg.svd(m, full_matrices=False)
    r = int(np.count_nonzero(s > MOVING_RANK * s[0]))
    return r, u[:, :r]


def tangent_from_second_order(second: SecondOrder | None, chords: list[np.ndarray], dim: int) -> np.ndarray | None:
    """The exact tangent of a branch at the given pose, if the second-order forms single it out.

    It is the common null space of the forms when that has the branch's
    dimension and holds the moves that reached the branch (to their O(step)).
    """
    if second is None or second.forms.shape[0] == 0:
        return None
    kernel = second.isotropic_kernel()
    if kernel.shape[1] != dim or not chords:
        return None
    off = max(float(np.linalg.norm(c - kernel @ (kernel.T @ c))) for c in chords)
    return kernel if off < MOVING_RANK else None


def examine_branch(plan: MovePlan, group: TangentGroup, probes: tuple[Probe, ...], second: SecondOrder | None, rng: np.random.Generator) -> tuple[Branch, str]:
    """Measure the branch of one group from its first pose.

    ``probes`` are the moves from the given pose (``group.probes`` indexes
    them), ``rng`` draws the random local directions.  Returns the
    :class:`Branch` and a warning (empty, or why its pattern is only approximate).
    """
    kin = plan.kinematics
    rep = probes[group.probes[0]]
    m1, n1 = rep.mobility, rep.tangent
    assert m1 is not None and n1 is not None and rep.q is not None  # the group's probes moved and were examined
    local_plan = plan.local()
    local = probe_each(local_plan, rep.q, [("local", d) for _, d in probe_directions(canonical_basis(n1), rng, randoms=2, pairs=False)], examine=False)
    dim, moves = rank_of_moves(cast("list[np.ndarray]", [p.achieved for p in local if p.moved]))  # a probe that moved has a direction
    nearby = analyze(kin.mechanism_at(rep.q), tol=plan.nearby_tol)  # a pose Newton closed, judged as the moves judge nearby poses
    warning = ""
    tangent: np.ndarray | None
    if dim == m1:
        # a regular point of its branch: the screw route there gives the branch's DOF and pattern
        tangent, source = n1, "nearby pose"
        dof, pattern = nearby.dof, nearby.pattern
    else:
        # fewer moves than first-order motions along the whole branch: its tangent at the given
        # pose is where the second-order forms vanish identically, when they single it out
        tangent = tangent_from_second_order(second, cast("list[np.ndarray]", [probes[i].achieved for i in group.probes]), dim)
        if tangent is not None:
            source = "second-order forms"
            dof, pattern = end_effector_pattern(kin.end_effector_jacobian(np.zeros(kin.variable_count)) @ tangent, plan.tol)  # exact, at the given pose
        else:
            source = "moves (approximate)"
            tangent = np.linalg.qr(n1 @ (n1.T @ moves))[0] if dim else np.zeros((kin.variable_count, 0))
            dof, pattern = end_effector_pattern(kin.end_effector_jacobian(rep.q) @ tangent, plan.nearby_tol)
            warning = f"the pattern of a branch of dimension {dim} comes from finite moves only (approximate)"
    branch = Branch(dim, dof, pattern, m1, nearby, tangent, rep.q, float(np.linalg.norm(rep.q)), tuple(sorted(group.probes)), local, source)
    return branch, warning
