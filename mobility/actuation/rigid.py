"""Actuation of rigid mechanisms: one choice of actuated joints, or every choice, over poses.

The actuation wrenches come from :class:`~mobility.actuation.rigid_pose.RigidPose`,
the verdicts from :mod:`mobility.actuation.assessment`.

Examples
--------
>>> from mobility.core.model import Joint, Mechanism
>>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
>>> arm = Mechanism("RR arm", "g", "hand", (R("A", "g", "upper", (0, 0, 0)), R("B", "upper", "hand", (1, 0, 0))))
>>> check_actuation(arm, ["A", "B"]).verdict, check_actuation(arm, ["A"]).verdict
('valid', 'actuation-singular')
>>> [(c.inputs, c.type, c.verdict) for c in enumerate_actuations(arm, mode="any").combinations]
[(('A', 'B'), '2R', 'valid')]
"""

from __future__ import annotations

import itertools
from typing import Iterable, Sequence

import numpy as np

from ..core.linalg import singular_values, svd
from ..core.loop_closure import loop_closure
from ..core.model import Mechanism, joint_freedoms, require_mechanism
from ..core.validation import joint_names, require_no_repeats
from ..core.poses import DEFAULT_STEP, require_pose_count, sample_poses
from ..core.screws import motion_pattern
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, decide_rank, require_tolerance
from ..core.topology import joints_of
from ..errors import MechanismError, RequestError, counted, shown_argument
from .assessment import Assessment, assess_inputs, assess_wrenches
from .ranking import combination_type, combinations_count, combine_poses, inputs_per_combination, limit_combinations, rank_combinations
from .results import ActuationCheck, Enumeration
from .rigid_pose import RigidPose

__all__ = ["check_actuation", "check_over_poses", "enumerate_actuations", "ENUMERATION_MODES"]

ENUMERATION_MODES = ("limb", "any")
"""``"limb"``: one joint in each limb (the paper's enumeration; in DOF of them when there are more limbs than DOF); ``"any"``: any ``k`` candidates."""


def check_actuation(mechanism: Mechanism, actuated: Sequence[str] | None = None, *, tol: Tolerance = DEFAULT_TOLERANCE) -> ActuationCheck:
    """Assess one choice of actuated joints at the mechanism's pose.

    Parameters
    ----------
    actuated : sequence of str, optional
        Joint names; default: the joints marked ``actuated: true``.  Every
        freedom of a multi-DOF joint is one input, labelled ``NAME.k`` (``k``
        from 0), and such a label names that freedom alone.

    Raises
    ------
    MechanismError
        When a name is not a joint of the mechanism.

    Examples
    --------
    The 3-RPS with its three legs' sliders driven, then with two of them (the
    platform can still move with the inputs locked), then with a fourth input:

    >>> import mobility
    >>> m = mobility.load("mechanisms/actuation_3rps.yaml")
    >>> c = check_actuation(m)
    >>> c.verdict, [i.name for i in c.inputs], round(c.conditioning, 3)
    ('valid', ['P1', 'P2', 'P3'], 0.311)
    >>> check_actuation(m, ["P1", "P2"]).uncontrolled_twists.shape
    (1, 6)
    >>> check_actuation(m, ["P1", "P2", "P3", "R1"]).verdict
    'redundant'
    """
    mechanism = require_mechanism(mechanism, "check_actuation")
    tol = require_tolerance(tol, "check_actuation")
    names = _actuated_names(mechanism, actuated)
    warnings = [] if names else ["no joint is actuated (mark joints with `actuated: true`, or name them)"]
    return _assess_at(RigidPose(mechanism, tol), names, warnings)


def check_over_poses(mechanism: Mechanism, actuated: Sequence[str] | None, poses: Sequence[Mechanism], *, tol: Tolerance = DEFAULT_TOLERANCE) -> tuple[ActuationCheck, ...]:
    """:func:`check_actuation` of one choice at several poses of the same mechanism (same joints, links, ground and end effector).

    Raises
    ------
    MechanismError
        When a pose is not one of ``mechanism``, or a name is not a joint.
    RequestError
        When ``mechanism`` or a pose is not a :class:`~mobility.core.model.Mechanism`.
    """
    mechanism = require_mechanism(mechanism, "check_over_poses")
    tol = require_tolerance(tol, "check_over_poses")
    names = _actuated_names(mechanism, actuated)
    out = []
    for i, pose in enumerate(_poses(poses, "check_over_poses")):
        _require_same_mechanism(mechanism, pose, pose.source or f"pose {i}")
        out.append(_assess_at(RigidPose(pose, tol), names))
    return tuple(out)


def enumerate_actuations(mechanism: Mechanism, *, mode: str = "limb", k: int | None = None, poses: Sequence[Mechanism] = (), samples: int = 0,
                         step: float = DEFAULT_STEP, seed: int = 0, tol: Tolerance = DEFAULT_TOLERANCE) -> Enumeration:
    """Assess every combination of inputs over several poses, and rank the valid ones.

    Candidate inputs are the joints with one freedom (R, P, H) on a path
    between the ground and the end effector.

    Parameters
    ----------
    mechanism : Mechanism
        The given pose (pose 0).
    mode : {"limb", "any"}
        ``"limb"``: one joint in each limb (the paper's enumeration; with more
        limbs than DOF, in DOF of them); ``"any"``: any ``k`` candidates.
    k : int, optional
        Inputs per combination; default the DOF. Mode ``"limb"`` fixes it
        (the number of limbs, or the DOF when smaller): a ``k`` that differs is refused.
    poses : sequence of Mechanism
        Further poses of the same mechanism.
    samples : int
        Further poses from :func:`mobility.core.poses.sample_poses` (with ``step``, ``seed``, ``tol``).

    Raises
    ------
    RequestError
        On an unknown mode, a bad ``k`` or ``samples``, a pose that is not a
        Mechanism, or more than :data:`~mobility.actuation.ranking.MAX_COMBINATIONS` combinations.
    MechanismError
        When a pose is not one of ``mechanism``.

    Examples
    --------
    >>> import mobility
    >>> found = enumerate_actuations(mobility.load("mechanisms/actuation_3rps.yaml"))
    >>> found.mode, found.k, found.combinations[0].verdict
    ('limb', 3, 'valid')
    >>> enumerate_actuations(mobility.load("mechanisms/actuation_3rps.yaml"), mode="limb", k=2)
    Traceback (most recent call last):
    mobility.errors.RequestError: k: mode 'limb' takes one input in each limb, 3 here, got k=2 (leave k out, or use mode 'any')
    """
    mechanism = require_mechanism(mechanism, "enumerate_actuations")
    tol = require_tolerance(tol, "enumerate_actuations")
    if not isinstance(mode, str) or mode not in ENUMERATION_MODES:
        shown = shown_argument(mode) if isinstance(mode, str) else type(mode).__name__
        raise RequestError(f"mode must be 'limb' or 'any', got {shown}", caller="enumerate_actuations")
    given_k = None if k is None else inputs_per_combination(k, 0)
    samples = require_pose_count(samples, "samples")
    poses = _poses(poses, "enumerate_actuations")
    warnings: list[str] = []
    first = RigidPose(mechanism, tol)
    dof = first.spaces.dof
    limb_k = _limb_inputs(len(first.limbs), dof)
    if mode == "limb" and given_k is not None and given_k != limb_k:
        raise RequestError(f"k: mode 'limb' takes one input in each limb, {limb_k} here, got k={given_k} (leave k out, or use mode 'any')")
    pose_list: list[tuple[str, Mechanism]] = [("given pose", mechanism)]
    for i, p in enumerate(poses):
        label = p.source or f"pose {i + 1}"
        _require_same_mechanism(mechanism, p, label)
        pose_list.append((label, p))
    if samples:
        sampled = sample_poses(mechanism, samples, step=step, seed=seed, tol=tol)
        pose_list += [(f"sampled pose {i + 1}", p) for i, p in enumerate(sampled)]
    candidates = [[j for j in joints_of(node) if mechanism.joints[j].dof == 1] for node, _ in first.limbs]
    if mode == "limb":
        k = limb_k
        warnings += [f"limb {i + 1} has no one-freedom joint to actuate" for i, c in enumerate(candidates) if not c]
        limit_combinations(_limb_combinations(candidates, k), "check chosen inputs, or use mode 'any' with a small k")
        driven = itertools.combinations(candidates, k)  # k of the limbs: all of them, unless there are more limbs than DOF
        combos: Iterable[tuple[int, ...]] = itertools.chain.from_iterable(itertools.product(*chosen) for chosen in driven)
    else:
        flat = sorted(j for c in candidates for j in c)
        k = dof if given_k is None else given_k
        combinations_count(len(flat), k, "choose a smaller k or mode 'limb'")
        combos = itertools.combinations(flat, k)
    if k != dof:
        warnings.append(f"{counted(k, 'input')} per combination for {dof} DOF: none can be valid ({'redundant' if k > dof else 'too few'})")
    combos = [tuple(c) for c in combos]
    states = [first] + [RigidPose(p, tol) for _, p in pose_list[1:]]
    per_combo: list[list[Assessment]] = [[] for _ in combos]
    for index, state in enumerate(states):
        spaces = state.spaces
        if spaces.dof != dof:
            warnings.append(f"the end effector has {spaces.dof} DOF at pose {index} ({pose_list[index][0]}), {dof} at the given pose")
        for c, found in zip(combos, per_combo):
            got = [state.wrench(j, 0) for j in c]
            held = state.locked_wrenches([(j, 0) for j in c])
            found.append(assess_wrenches([g[0] for g in got], [g[1] for g in got], spaces.twists, spaces.constraints, tol, held,
                                         [state.transmission(j, 0) for j in c]))
    joints = mechanism.joints
    results = [combine_poses(tuple(joints[j].name for j in c), combination_type(joints[j].type for j in c), f) for c, f in zip(combos, per_combo)]
    ranked, groups = rank_combinations(results)
    pattern = motion_pattern(first.spaces.twists, tol)
    return Enumeration(mechanism.name, "rigid", dof, pattern, mode, k, ranked, groups, tuple(label for label, _ in pose_list), tuple(warnings), len(first.limbs))


def _limb_inputs(limbs: int, dof: int) -> int:
    """Inputs per combination of mode ``"limb"``: one in each limb, or in ``dof`` of them when there are more limbs than DOF.

    (A four-bar seen from its coupler, the Tricept: one in each limb would make every combination redundant.)

    Examples
    --------
    >>> _limb_inputs(3, 3), _limb_inputs(2, 1), _limb_inputs(4, 3), _limb_inputs(2, 3)
    (3, 1, 3, 2)
    """
    return dof if 0 < dof < limbs else limbs


def _limb_combinations(candidates: Sequence[Sequence[int]], k: int) -> int:
    """How many combinations mode ``"limb"`` tries: one candidate in each of ``k`` of the limbs.

    The elementary symmetric polynomial of degree ``k`` of the candidate
    counts, in exact integers, known before any subset is listed.

    Examples
    --------
    >>> _limb_combinations([[0, 1], [2, 3], [4, 5]], 2), _limb_combinations([[0, 1]] * 70, 70) == 2**70
    (12, True)
    """
    counts = [1] + [0] * k  # counts[j]: choices of one candidate in each of j limbs among those seen so far
    for limb in candidates:
        for j in range(k, 0, -1):
            counts[j] += counts[j - 1] * len(limb)
    return counts[k]


def _poses(poses: Iterable[Mechanism], caller: str) -> list[Mechanism]:
    """``poses`` as a list, each a :class:`~mobility.core.model.Mechanism` (else a :class:`RequestError` naming it)."""
    if isinstance(poses, (str, bytes, Mechanism)) or not isinstance(poses, Iterable):
        raise RequestError(f"poses must be a sequence of Mechanisms, got {type(poses).__name__}", caller=caller)
    return [require_mechanism(p, f"{caller}: poses[{i}]") for i, p in enumerate(poses)]


def _actuated_names(mechanism: Mechanism, actuated: Sequence[str] | None) -> list[str]:
    return [j.name for j in mechanism.joints if j.actuated] if actuated is None else joint_names(actuated, "actuated")


def _assess_at(pose: RigidPose, names: Sequence[str], warnings: Sequence[str] = ()) -> ActuationCheck:
    """The check of the inputs named (a joint: each of its freedoms; ``NAME.k``: freedom ``k``) at one pose."""
    m = pose.mechanism
    require_no_repeats(names, "actuated")
    freedoms = joint_freedoms(m, names)
    inputs = [pose.input_wrench(j, k, label) for j, k, label in freedoms]
    idle = _idle_inputs(pose, names) if len(inputs) > pose.spaces.dof else None
    held = pose.locked_wrenches([(j, k) for j, k, _ in freedoms])
    return assess_inputs(m.name, "rigid", inputs, pose.spaces, pose.tol, warnings=warnings, length_unit=m.length_unit, idle_inputs=idle, held=held)


def _idle_inputs(pose: RigidPose, names: Sequence[str]) -> tuple[str, ...] | None:
    """The inputs that move the mechanism without moving the end effector, when the inputs can be set independently.

    None when the inputs' rows of the loop closure's joint-rate basis lose rank (their rates are tied: they fight).

    Examples
    --------
    A slider-crank at its dead centre: the crank moves, the slider does not.

    >>> from mobility.core.model import Joint, Mechanism
    >>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p)
    >>> m = Mechanism("slider-crank", "ground", "slider", (R("A", "ground", "crank", (0, 0, 0)), R("B", "crank", "rod", (1, 0, 0)),
    ...     R("C", "rod", "slider", (3, 0, 0)), Joint("S", "P", ("slider", "ground"), axis=(1, 0, 0))))
    >>> _idle_inputs(RigidPose(m), ["A"]), _idle_inputs(RigidPose(m), ["A", "S"])
    (('A',), None)
    """
    closure = loop_closure(pose.mechanism, pose.tol)
    offsets = closure.screws.offsets
    chosen = joint_freedoms(pose.mechanism, names)
    labels = [label for _, _, label in chosen]
    columns = [int(offsets[j]) + k for j, k, _ in chosen]
    rates = closure.joint_rates[columns]  # (inputs, mobility)
    if rates.shape[1] < len(columns) or decide_rank(singular_values(rates), pose.tol).rank < len(columns):
        return None
    _, s, vt = svd(closure.end_effector_map @ closure.joint_rates)
    idle = vt[decide_rank(s, pose.tol).rank :].T  # motions of the mechanism that leave the end effector still
    moved = np.linalg.norm(rates @ idle, axis=1) if idle.size else np.zeros(len(columns))
    return tuple(label for label, size in zip(labels, moved) if decide_rank(np.array([1.0, size]), pose.tol).rank == 2)


def _require_same_mechanism(reference: Mechanism, pose: Mechanism, label: str) -> None:
    """Refuse a pose whose joints (names, types, links), ground or end effector differ."""

    def signature(m: Mechanism) -> tuple:
        return (m.ground, m.end_effector, tuple((j.name, j.type, j.links) for j in m.joints))

    if signature(pose) != signature(reference):
        raise MechanismError("poses", f"{label} is not a pose of {reference.name!r}: its joints, links, ground or end effector differ")
