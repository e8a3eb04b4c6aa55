"""The actuation verdict and conditioning of one choice of inputs, at many poses at once.

The definitions and each step are those of :mod:`mobility.actuation` (Li,
Shan, Yu and Ke, 2021) and :func:`mobility.check_actuation` at one pose, on
stacks of poses, so the verdicts agree (the tests check it on random poses).

Examples
--------
>>> import numpy as np
>>> import mobility
>>> from mobility.core.kinematics import kinematics
>>> from mobility.sweeps.posed_screws import posed_screws
>>> from mobility.core.screw_systems import analyse_poses
>>> from mobility.core.topology import decompose
>>> m = mobility.load("mechanisms/actuation_3rps.yaml")
>>> posed = posed_screws(kinematics(m), np.zeros((1, 15)))
>>> a = actuation_at_poses(m, posed, analyse_poses(decompose(m), posed.twists, posed.offsets), actuated_inputs(m))
>>> a.verdict.tolist(), round(float(a.conditioning[0]), 3), round(mobility.check_actuation(m).conditioning, 3)
(['valid'], 0.311, 0.311)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..actuation import REDUNDANT, SINGULAR, VALID
from ..actuation.input_wrenches import input_wrenches
from ..core.model import Mechanism, joint_freedoms
from ..core.validation import joint_names, require_no_repeats
from ..core.linalg import singular_values
from ..core.screw_systems import PoseAnswers, evaluate
from ..core.screws import SWAP_ROWS
from ..core.tolerance import DEFAULT_TOLERANCE, RankDecisions, Tolerance, decide_ranks
from ..core.topology import Parallel, decompose, joints_of
from .posed_screws import PosedScrews

__all__ = ["ActuationInputs", "actuated_inputs", "BatchActuation", "actuation_at_poses"]


@dataclass(frozen=True)
class ActuationInputs:
    """The inputs of a choice of actuated joints: one per freedom.

    Attributes
    ----------
    names : tuple of str
        The actuated joints, as given.
    freedoms : tuple of (int, int)
        ``(joint index, freedom)`` of each input.
    """

    names: tuple[str, ...]
    freedoms: tuple[tuple[int, int], ...]


def actuated_inputs(mechanism: Mechanism, names: Sequence[str] | None = None) -> ActuationInputs:
    """The inputs of the named joints (default: those marked ``actuated: true``).

    Raises
    ------
    MechanismError
        When a name is not a joint of the mechanism.
    """
    chosen = [j.name for j in mechanism.joints if j.actuated] if names is None else joint_names(names, "actuated")
    require_no_repeats(chosen, "actuated")
    freedoms = [(j, k) for j, k, _ in joint_freedoms(mechanism, chosen)]  # NAME.k: freedom k of a multi-freedom joint
    return ActuationInputs(tuple(chosen), tuple(freedoms))


@dataclass(frozen=True, eq=False)
class BatchActuation:
    """Verdict and conditioning of one choice of inputs at every pose.

    Attributes
    ----------
    verdict : ndarray of str
    rank : ndarray of int
        Rank of the constraint and actuation wrenches together.
    margin : ndarray of float
        The actuation margin of :func:`mobility.check_actuation`.
    conditioning : ndarray of float
    wrenches : ndarray, shape (N, n, 6)
        The unit actuation wrench of each input (zeros where it has none).
    """

    verdict: np.ndarray
    rank: np.ndarray
    margin: np.ndarray
    conditioning: np.ndarray
    wrenches: np.ndarray | None = None


def actuation_at_poses(mechanism: Mechanism, posed: PosedScrews, answers: PoseAnswers, inputs: ActuationInputs, tol: Tolerance = DEFAULT_TOLERANCE) -> BatchActuation:
    """The verdict and conditioning of ``inputs`` at every pose of ``posed``.

    ``answers``: :func:`~mobility.core.screw_systems.analyse_poses` of the same poses.
    """
    count = posed.twists.shape[0]
    root = decompose(mechanism).root
    value = answers.root
    limbs = list(zip(root.children, value.children)) if isinstance(root, Parallel) else [(root, value)]
    limb_of = {j: k for k, (node, _) in enumerate(limbs) for j in joints_of(node)}
    world = mechanism.world_joints
    ee = mechanism.end_effector
    wrenches, rates, transmissions = [], [], []
    lacking: dict[int, np.ndarray] = {}  # by limb: the poses where an input of it has no wrench of its own (the limb's other joints produce its motion)
    for joint, freedom in inputs.freedoms:
        w, rate, transmission = np.zeros((count, 6)), np.ones(count), np.zeros(count)
        if joint in limb_of:
            node, limb = limbs[limb_of[joint]]
            on_ee = [world[j].name for j in joints_of(node) if ee in world[j].links and world[j].point is not None]
            attach = posed.normalised(np.mean([posed.points[n] for n in on_ee], axis=0)) if on_ee else posed.reference
            w, rate, transmission, has = input_wrenches(node, limb, posed.twists, posed.offsets, posed.offsets[joint] + freedom, attach, tol)
            lacking[limb_of[joint]] = lacking.get(limb_of[joint], np.zeros(count, dtype=bool)) | ~has
        wrenches.append(w)
        rates.append(rate)
        transmissions.append(transmission)
    n = len(inputs.freedoms)
    dof = answers.dof
    present = np.stack([np.any(w != 0.0, axis=1) for w in wrenches], axis=1) if n else np.zeros((count, 0), dtype=bool)
    held, held_counts = _held(limbs, lacking, inputs, posed, tol)
    stack = np.concatenate([value.wrenches] + [w[:, :, None] for w in wrenches] + held, axis=2)
    counts = (6 - dof) + present.sum(axis=1) + held_counts
    decision = decide_ranks(singular_values(stack), tol, np.minimum(counts, 6))
    code = np.where(decision.rank < 6, 0, np.where(n > dof, 1, 2))
    verdict = np.array([SINGULAR, REDUNDANT, VALID], dtype=object)[code]  # the three strings shared, not one per pose
    conditioning = np.zeros(count)
    regular = decision.rank == 6
    conditioning[regular & (dof == 0)] = 1.0
    if n and value.basis.shape[2]:
        a = np.stack(wrenches, axis=1)  # (N, n, 6)
        g = (a[:, :, SWAP_ROWS] @ value.basis) / np.stack(rates, axis=1)[:, :, None]
        finite = np.all(np.isfinite(g), axis=(1, 2))
        g[~finite] = 0.0
        sv = np.linalg.svd(g, compute_uv=False)
        rows = np.arange(count)
        d = np.clip(dof - 1, 0, sv.shape[1] - 1)
        ok = regular & finite & (dof > 0) & (present.sum(axis=1) >= dof) & (sv[:, 0] > 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            conditioning = np.where(ok, sv[rows, d] / sv[:, 0], conditioning)
    margin = _actuation_margin(decision, wrenches, transmissions, present, value.basis, dof, regular)
    return BatchActuation(verdict, decision.rank, margin, conditioning, np.stack(wrenches, axis=1) if n else np.zeros((count, 0, 6)))


def _actuation_margin(decision: RankDecisions, wrenches: list[np.ndarray], transmissions: list[np.ndarray], present: np.ndarray,
                      basis: np.ndarray, dof: np.ndarray, regular: np.ndarray) -> np.ndarray:
    """The actuation margin of :func:`mobility.check_actuation` at every pose, with its conventions (:mod:`mobility.actuation.assessment`)."""
    count, n = present.shape
    margin = np.where(regular, decision.smallest_kept, 0.0)
    if n == 0:
        return margin
    margin = np.where(dof == 0, 0.0, margin)
    full = regular & (dof > 0) & present.all(axis=1)
    if basis.shape[2] and full.any():
        a = np.stack(wrenches, axis=1)  # (N, n, 6)
        h = (a[:, :, SWAP_ROWS] @ basis) * np.stack(transmissions, axis=1)[:, :, None]
        sv = singular_values(h)
        d = np.clip(dof - 1, 0, sv.shape[1] - 1)
        margin = np.where(full, np.where(dof <= sv.shape[1], np.minimum(sv[np.arange(count), d], margin), 0.0), margin)
    return margin


def _held(limbs: list, lacking: dict[int, np.ndarray], inputs: ActuationInputs, posed: PosedScrews, tol: Tolerance) -> tuple[list[np.ndarray], np.ndarray]:
    """:meth:`mobility.actuation.rigid_pose.RigidPose.locked_wrenches` at the poses where an input has no wrench of its own (zero columns elsewhere), and each pose's count."""
    count = posed.twists.shape[0]
    held, counts = [], np.zeros(count, dtype=int)
    for limb, where in sorted(lacking.items()):
        if not where.any():
            continue
        members = set(joints_of(limbs[limb][0]))
        locked = posed.twists.copy()
        locked[:, :, [posed.offsets[j] + k for j, k in inputs.freedoms if j in members]] = 0.0
        value = evaluate(limbs[limb][0], locked, posed.offsets, tol)
        held.append(np.where(where[:, None, None], value.wrenches, 0.0))
        counts += np.where(where, 6 - value.dim, 0)
    return held, counts
