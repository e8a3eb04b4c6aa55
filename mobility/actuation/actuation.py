"""Actuation spaces: which joints may drive a mechanism, and how well.

The method is that of Li, Shan, Yu and Ke, "Actuation Spaces Synthesis of
Lower-Mobility Parallel Mechanisms Based on Screw Theory" (Chinese Journal of
Mechanical Engineering, 2021): a choice of inputs is valid when its actuation
wrenches are linearly independent of the constraint wrenches of the end
effector, so that the two together span all six dimensions.

Definitions (all screws in the normalised coordinates of
:mod:`mobility.core.tolerance`; reported in the global frame):

* **limb**: a branch of the top-level parallel connection between ground and
  end effector (:func:`mobility.core.topology.decompose`); a mechanism that is not
  a parallel connection is one limb.
* **actuation wrench** of an actuated freedom (one per freedom of an actuated
  joint): a wrench reciprocal to every *other* twist of its limb but not to
  its own.  It is defined up to the limb's own constraint wrenches; the one
  reported is orthogonal to them in coordinates centred where the limb meets
  the end effector (for an RPS limb: the force along the leg for P, the force
  through the S centre normal to the leg in the leg's plane for R).  When the
  limb's other joints already produce the joint's motion, there is none: the
  joint cannot be driven on its own.
* **verdict** of a choice of ``n`` inputs for an end effector of ``d`` DOF,
  from the rank ``r`` of the actuation and constraint wrenches together (one
  rank decision of the tolerance policy):

  - ``valid``: ``r = 6`` and ``n = d``;
  - ``actuation-singular``: ``r < 6``: with the inputs locked, the end
    effector can still move along ``6 - r`` directions, the twists reciprocal
    to all those wrenches (reported as the *uncontrolled* directions);
  - ``redundant``: ``r = 6`` and ``n > d`` (more inputs than DOF; they must be
    coordinated or they fight each other).
* **actuation conditioning** ``kappa``: the inverse condition number
  ``s_min / s_max`` of the ``n x d`` map ``G`` from the end effector's twists
  to the input rates, ``G[i, k] = (a_i o t_k) / (a_i o $_i)``, where ``t_k`` is
  an orthonormal basis of the end effector's twist system, ``a_i`` the
  actuation wrench and ``$_i`` the actuated joint's twist with unit rate (unit
  angular speed for R and H, unit speed of one characteristic length ``L``
  for P; a force line's input is the speed of its point along it).  ``G`` does
  not depend on which representative of ``a_i`` is taken, nor on the unit of
  length or the placement of the mechanism (normalised coordinates).
  ``kappa`` is 0 at an actuation singularity and 1 when a unit twist of the end
  effector in any direction needs the same input speed; over several poses
  the worst (smallest) value is reported and ranks the valid choices.

The second route, used by the tests: locking the chosen joints
(:func:`lock_joints`, links merged) leaves the end effector with 0 DOF by
loop closure (:func:`locked_dof`) exactly when the actuation and constraint
wrenches span six dimensions.

Examples
--------
>>> from mobility.core.model import Joint, Mechanism
>>> R = lambda n, a, b, p: Joint(n, "R", (a, b), axis=(0, 0, 1), point=p, actuated=(n == "A"))
>>> m = Mechanism("four-bar", "ground", "coupler", (
...     R("A", "ground", "crank", (0, 0, 0)), R("B", "crank", "coupler", (1, 2, 0)),
...     R("C", "coupler", "rocker", (4, 2.5, 0)), R("D", "rocker", "ground", (5, 0, 0))))
>>> check = check_actuation(m)
>>> check.verdict, check.dof, [i.name for i in check.inputs]
('valid', 1, ['A'])
>>> check_actuation(m, ["A", "D"]).verdict
'redundant'
>>> locked_dof(m, ["A"]), locked_dof(m, [])
(0, 1)
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, replace
from math import comb
from typing import Any, Iterable, Sequence

import numpy as np

from ..core.analysis import screw_system_in_frame
from ..errors import MechanismError
from ..core.kinematics import sample_poses
from ..core.joint_screws import JointScrews, Normalisation, joint_screws
from ..core.linalg import singular_values, svd
from ..core.loop_closure import loop_closure
from ..core.model import Joint, Mechanism
from ..core.result import ScrewAxis, pattern_of
from ..core.screw_systems import SystemValue, evaluate
from ..core.screws import SWAP_ROWS, free_vector_subspace
from ..core.tolerance import DEFAULT_TOLERANCE, RankDecision, Tolerance, decide_rank
from ..core.topology import Node, Parallel, Topology, decompose, joints_of

__all__ = [
    "VALID",
    "SINGULAR",
    "REDUNDANT",
    "VERDICTS",
    "ActuationInput",
    "ActuationCheck",
    "Combination",
    "TypeGroup",
    "Enumeration",
    "check_actuation",
    "check_over_poses",
    "enumerate_actuations",
    "combination_type",
    "lock_joints",
    "locked_dof",
    "MAX_COMBINATIONS",
]

VALID = "valid"
SINGULAR = "actuation-singular"
REDUNDANT = "redundant"
VERDICTS = (VALID, REDUNDANT, SINGULAR)
"""The verdicts, best first."""

MAX_COMBINATIONS = 20000
"""Largest number of input combinations :func:`enumerate_actuations` will try."""

_TYPE_ORDER = "RPHCUSEF"


# ---------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------


def _plain(a: Any, scale: float = 1.0) -> Any:
    """JSON-ready floats, round-off (below 1e-12 of ``scale``) set to zero."""
    arr = np.asarray(a, dtype=float)
    arr = np.where(np.abs(arr) < 1e-12 * scale, 0.0, arr) + 0.0
    return arr.tolist()


def _axis_dict(a: ScrewAxis, scale: float) -> dict[str, Any]:
    return {"axis": _plain(a.axis), "point": _plain(a.point, scale), "pitch": _plain(a.pitch, scale), "kind": a.kind}


@dataclass(frozen=True, eq=False)
class ActuationInput:
    """One input (an actuated joint freedom or a linear actuator) and its actuation wrench.

    Attributes
    ----------
    name : str
        Joint name (with ``.k`` for freedom ``k`` of a multi-DOF joint) or actuator name.
    kind : str
        Joint type letter, or ``"F"`` for a linear actuator (a force line).
    limb : int or None
        Index of the limb (0-based) of a joint; ``None`` for a linear actuator or a
        joint off every ground-to-end-effector path.
    wrench : ndarray, shape (6,) or None
        The actuation wrench ``[f; m]`` in the global frame, ``|f| = 1`` (a couple:
        ``|m| = 1``); ``None`` when the input has none.
    axis : ScrewAxis or None
        Its line: ``kind`` ``"force"`` (pitch 0), ``"wrench"`` or ``"couple"``
        (``axis`` is the couple's direction, ``point`` the reference point).
    in_constraint_space : bool
        The wrench is a combination of constraint wrenches: this input cannot
        move the end effector.
    note : str
        Why there is no wrench, or why it is useless; empty otherwise.
    """

    name: str
    kind: str
    limb: int | None
    wrench: np.ndarray | None
    axis: ScrewAxis | None
    in_constraint_space: bool
    note: str = ""

    def to_dict(self, scale: float = 1.0) -> dict[str, Any]:
        """JSON form."""
        return {
            "name": self.name,
            "kind": self.kind,
            "limb": self.limb,
            "wrench": None if self.wrench is None else _plain(self.wrench, scale),
            "axis": None if self.axis is None else _axis_dict(self.axis, scale),
            "in_constraint_space": self.in_constraint_space,
            "note": self.note,
        }


@dataclass(frozen=True, eq=False)
class ActuationCheck:
    """The verdict on one choice of inputs at one pose.

    Attributes
    ----------
    name : str
        Mechanism name.
    kind : str
        ``"rigid"`` or ``"flexure"``.
    dof : int
        DOF of the end effector (of the freedom space, for a flexure).
    pattern : str
        Its motion pattern, e.g. ``"1T2R"``.
    inputs : tuple of ActuationInput
    constraint_couples : ndarray, shape (k, 3)
        Orthonormal basis of the pure couples among the constraint wrenches.
    constraint_forces : tuple of ScrewAxis
        The other constraint wrenches (principal screws).
    constraint_wrenches : ndarray, shape (6 - dof, 6)
        Basis of the constraint wrench system (rows ``[f; m]``, global frame).
    verdict : str
        ``"valid"``, ``"actuation-singular"`` or ``"redundant"``.
    rank : int
        Rank of the actuation and constraint wrenches together.
    uncontrolled_translations : ndarray, shape (k, 3)
        Translations the end effector keeps with every input locked.
    uncontrolled_rotations : tuple of ScrewAxis
        Rotations (or screw motions) it keeps.
    uncontrolled_twists : ndarray, shape (6 - rank, 6)
        Basis of those twists (rows ``[w; v]``, global frame).
    margin : RankDecision
        Of the rank decision: a small ``smallest_kept`` means near an
        actuation singularity.
    conditioning : float
        The actuation conditioning ``kappa`` (see the module docstring); 0
        when the verdict is actuation-singular.
    explanation : str
        One sentence on the verdict.
    warnings : tuple of str
    length_unit : str
    length_scale : float
        For rounding output.
    """

    name: str
    kind: str
    dof: int
    pattern: str
    inputs: tuple[ActuationInput, ...]
    constraint_couples: np.ndarray
    constraint_forces: tuple[ScrewAxis, ...]
    constraint_wrenches: np.ndarray
    verdict: str
    rank: int
    uncontrolled_translations: np.ndarray
    uncontrolled_rotations: tuple[ScrewAxis, ...]
    uncontrolled_twists: np.ndarray
    margin: RankDecision
    conditioning: float
    explanation: str
    warnings: tuple[str, ...] = ()
    length_unit: str = ""
    length_scale: float = 1.0

    @property
    def valid(self) -> bool:
        """True when the verdict is ``"valid"``."""
        return self.verdict == VALID

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        s = self.length_scale
        return {
            "name": self.name,
            "kind": self.kind,
            "dof": self.dof,
            "pattern": self.pattern,
            "verdict": self.verdict,
            "explanation": self.explanation,
            "rank": self.rank,
            "conditioning": self.conditioning,
            "margin": {"smallest_kept": self.margin.smallest_kept, "largest_dropped": self.margin.largest_dropped},
            "inputs": [i.to_dict(s) for i in self.inputs],
            "constraints": {
                "couples": _plain(self.constraint_couples),
                "forces": [_axis_dict(f, s) for f in self.constraint_forces],
                "wrenches": _plain(self.constraint_wrenches, s),
            },
            "uncontrolled": {
                "translations": _plain(self.uncontrolled_translations),
                "rotations": [_axis_dict(r, s) for r in self.uncontrolled_rotations],
                "twists": _plain(self.uncontrolled_twists, s),
            },
            "warnings": list(self.warnings),
            "length_unit": self.length_unit,
        }


@dataclass(frozen=True)
class Combination:
    """One combination of inputs, checked at every pose.

    Attributes
    ----------
    inputs : tuple of str
        Joint (or actuator) names.
    type : str
        The group it belongs to, e.g. ``"2R1P"`` (see :func:`combination_type`).
    verdict : str
        ``"valid"`` only when valid at every pose; otherwise the worst verdict met.
    valid_poses, poses : int
        At how many of the poses it is valid, out of how many.
    conditioning : float
        Smallest actuation conditioning over the poses (0 if singular at any).
    worst_pose : int
        Index of the pose where the conditioning is smallest.
    failures : tuple of (int, str)
        ``(pose index, verdict)`` for every pose where it is not valid.
    """

    inputs: tuple[str, ...]
    type: str
    verdict: str
    valid_poses: int
    poses: int
    conditioning: float
    worst_pose: int
    failures: tuple[tuple[int, str], ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {
            "inputs": list(self.inputs),
            "type": self.type,
            "verdict": self.verdict,
            "valid_poses": self.valid_poses,
            "poses": self.poses,
            "conditioning": self.conditioning,
            "worst_pose": self.worst_pose,
            "failures": [list(f) for f in self.failures],
        }


@dataclass(frozen=True)
class TypeGroup:
    """How many combinations of one type are valid."""

    type: str
    valid: int
    total: int

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {"type": self.type, "valid": self.valid, "total": self.total}


@dataclass(frozen=True)
class Enumeration:
    """Every combination of inputs, checked over several poses and ranked.

    Attributes
    ----------
    name : str
    kind : str
        ``"rigid"`` or ``"flexure"``.
    dof : int
    pattern : str
    mode : str
        ``"limb"`` (one joint per limb), ``"any"`` (any ``k`` candidates).
    k : int
        Inputs per combination (``"any"`` mode; the number of limbs otherwise).
    combinations : tuple of Combination
        Ranked: valid ones first by decreasing conditioning, then redundant,
        then actuation-singular ones.
    groups : tuple of TypeGroup
        Valid and total counts per type.
    poses : tuple of str
        A label for each pose visited (index 0: the given pose).
    warnings : tuple of str
    """

    name: str
    kind: str
    dof: int
    pattern: str
    mode: str
    k: int
    combinations: tuple[Combination, ...]
    groups: tuple[TypeGroup, ...]
    poses: tuple[str, ...]
    warnings: tuple[str, ...] = ()

    @property
    def valid(self) -> tuple[Combination, ...]:
        """The valid combinations, best first."""
        return tuple(c for c in self.combinations if c.verdict == VALID)

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {
            "name": self.name,
            "kind": self.kind,
            "dof": self.dof,
            "pattern": self.pattern,
            "mode": self.mode,
            "k": self.k,
            "poses": list(self.poses),
            "groups": [g.to_dict() for g in self.groups],
            "combinations": [c.to_dict() for c in self.combinations],
            "warnings": list(self.warnings),
        }


# ---------------------------------------------------------------------------
# shared machinery (also used by mobility.flexure.spaces)
# ---------------------------------------------------------------------------


def _wrench_axis(wrench_n: np.ndarray, norm: Normalisation, reference: np.ndarray, tol: Tolerance) -> tuple[np.ndarray, ScrewAxis]:
    """A normalised wrench as a global wrench (``|f| = 1``, or ``|m| = 1`` for a couple) and its line."""
    f, m = wrench_n[:3], wrench_n[3:]
    nf = float(np.linalg.norm(f))
    if nf <= tol.rank * float(np.linalg.norm(wrench_n)):
        c = m / np.linalg.norm(m)
        return np.concatenate([np.zeros(3), c]), ScrewAxis(c, norm.point_to_world(reference), 0.0, "couple")
    f, m = f / nf, m / nf
    pitch = float(f @ m)
    mr = m - np.cross(reference, f)  # moment about the reference point
    point = reference + np.cross(f, mr)
    pitch = 0.0 if abs(pitch) <= tol.rank else pitch
    axis = ScrewAxis(f, norm.point_to_world(point), pitch * norm.length, "force" if pitch == 0.0 else "wrench")
    world = norm.to_world(np.concatenate([f, m]))[:, 0]
    return world, axis


@dataclass(frozen=True)
class _Assessment:
    verdict: str
    decision: RankDecision
    uncontrolled: np.ndarray  # normalised twists, columns
    conditioning: float
    in_constraint: tuple[bool, ...]


def _assess(wrenches: Sequence[np.ndarray | None], rates: Sequence[float], twists: np.ndarray, constraints: np.ndarray, tol: Tolerance) -> _Assessment:
    """Verdict of a choice of inputs from its actuation wrenches (normalised coordinates).

    Parameters
    ----------
    wrenches : sequence of (6,) arrays or None
        Unit actuation wrenches; ``None`` for an input that has none.
    rates : sequence of float
        ``a_i o $_i`` for each input (1 for a force line).
    twists : ndarray, shape (6, d)
        Orthonormal basis of the end effector's twist (freedom) system.
    constraints : ndarray, shape (6, 6 - d)
        Orthonormal basis of its constraint wrench system.
    """
    dof = twists.shape[1]
    present = [w for w in wrenches if w is not None]
    stack = np.concatenate([constraints] + [w[:, None] for w in present], axis=1)
    if stack.shape[1]:
        u, s, _ = svd(stack)
        decision = decide_rank(s, tol)
        uncontrolled = u[SWAP_ROWS, decision.rank :]
    else:
        decision = RankDecision(0)
        uncontrolled = np.eye(6)
    flags = []
    for w in wrenches:
        if w is None:
            flags.append(True)
            continue
        # The part of w outside the constraint system (orthonormal basis): zero when w lies in it.
        rest = w - constraints @ (constraints.T @ w)
        flags.append(decide_rank(np.array([1.0, float(np.linalg.norm(rest))]), tol).rank < 2)
    n = len(wrenches)
    if decision.rank < 6:
        verdict = SINGULAR
    elif n > dof:
        verdict = REDUNDANT
    else:
        verdict = VALID
    conditioning = 0.0
    if verdict != SINGULAR:
        if dof == 0:
            conditioning = 1.0
        else:
            g = np.array([(w[SWAP_ROWS] @ twists) / r for w, r in zip(present, rates)]).reshape(-1, dof)  # a o t_k for every k
            sv = singular_values(g)
            conditioning = float(sv[dof - 1] / sv[0]) if sv.size >= dof and sv[0] > 0 else 0.0
    return _Assessment(verdict, decision, uncontrolled, conditioning, tuple(flags))


def _explain(verdict: str, n: int, dof: int, rank: int, useless: Sequence[str]) -> str:
    if verdict == VALID:
        return (
            f"the {n} actuation wrench(es) and the {6 - dof} constraint wrench(es) span all six dimensions: "
            "with the inputs locked the end effector cannot move"
        )
    if verdict == REDUNDANT:
        return f"{n} inputs for {dof} DOF: {n - dof} more than needed (they must be coordinated or they fight each other)"
    text = f"actuation and constraint wrenches span only {rank} of 6 dimensions: with the inputs locked the end effector can still move along {6 - rank} direction(s)"
    if n < dof:
        text += f" (fewer inputs, {n}, than DOF, {dof})"
    if useless:
        text += "; useless input(s): " + ", ".join(useless)
    return text


def _build_check(
    name: str,
    kind: str,
    inputs: Sequence[tuple[str, str, int | None, np.ndarray | None, str]],
    rates: Sequence[float],
    twists: np.ndarray,
    constraints: np.ndarray,
    norm: Normalisation,
    reference: np.ndarray,
    tol: Tolerance,
    warnings: Sequence[str],
    length_unit: str,
) -> ActuationCheck:
    """Assemble an :class:`ActuationCheck` from normalised wrenches (rigid and flexure alike)."""
    present_rates = [r for (_, _, _, w, _), r in zip(inputs, rates) if w is not None]
    a = _assess([w for _, _, _, w, _ in inputs], present_rates, twists, constraints, tol)
    out_inputs = []
    useless = []
    for (label, jkind, limb, w, note), flag in zip(inputs, a.in_constraint):
        if w is None:
            out_inputs.append(ActuationInput(label, jkind, limb, None, None, True, note))
            useless.append(label)
            continue
        world, axis = _wrench_axis(w, norm, reference, tol)
        if flag:
            useless.append(label)
            note = note or "its actuation wrench lies in the constraint space: it cannot move the end effector"
        out_inputs.append(ActuationInput(label, jkind, limb, world, axis, flag, note))
    dof = twists.shape[1]
    ctr, cax, crows = screw_system_in_frame(constraints, norm, reference, ("force", "wrench"), tol)
    pattern = _pattern(twists, tol)
    ut, ur, urows = screw_system_in_frame(a.uncontrolled, norm, reference, ("rotation", "helical"), tol)
    warns = list(warnings)
    if a.verdict != SINGULAR and a.decision.smallest_kept < tol.near_singular:
        warns.append(
            f"near an actuation singularity: relative singular value {a.decision.smallest_kept:.2e} of the actuation and constraint wrenches"
        )
    return ActuationCheck(
        name=name,
        kind=kind,
        dof=dof,
        pattern=pattern,
        inputs=tuple(out_inputs),
        constraint_couples=ctr,
        constraint_forces=cax,
        constraint_wrenches=crows,
        verdict=a.verdict,
        rank=a.decision.rank,
        uncontrolled_translations=ut,
        uncontrolled_rotations=ur,
        uncontrolled_twists=urows,
        margin=a.decision,
        conditioning=a.conditioning,
        explanation=_explain(a.verdict, len(inputs), dof, a.decision.rank, useless),
        warnings=tuple(warns),
        length_unit=length_unit,
        length_scale=norm.length + float(np.linalg.norm(norm.centre)),
    )


def combination_type(kinds: Iterable[str]) -> str:
    """The type of a combination of inputs, as the paper writes it: counts of each joint type.

    Examples
    --------
    >>> combination_type("RPR"), combination_type(["P", "P", "P"]), combination_type("PRP")
    ('2R1P', '3P', '1R2P')
    """
    kinds = list(kinds)
    order = sorted(set(kinds), key=lambda k: (_TYPE_ORDER.find(k) if k in _TYPE_ORDER else len(_TYPE_ORDER), k))
    return "".join(f"{kinds.count(k)}{k}" for k in order) or "0"


def _type_key(t: str) -> tuple:
    """Sort key putting 3R, 2R1P, 1R2P, 3P in the paper's order."""
    counts = dict.fromkeys(_TYPE_ORDER, 0)
    number = ""
    for ch in t:
        if ch.isdigit():
            number += ch
        else:
            counts[ch] = counts.get(ch, 0) + int(number or 0)
            number = ""
    return tuple(-counts[k] for k in _TYPE_ORDER) + (t,)


def _rank_combinations(found: Sequence[Combination]) -> tuple[tuple[Combination, ...], tuple[TypeGroup, ...]]:
    ranked = sorted(found, key=lambda c: (VERDICTS.index(c.verdict), -c.conditioning, c.inputs))
    groups: dict[str, list[int]] = {}
    for c in found:
        g = groups.setdefault(c.type, [0, 0])
        g[0] += c.verdict == VALID
        g[1] += 1
    return tuple(ranked), tuple(TypeGroup(t, v, n) for t, (v, n) in sorted(groups.items(), key=lambda kv: _type_key(kv[0])))


def _combine(inputs: tuple[str, ...], kind: str, per_pose: Sequence[_Assessment]) -> Combination:
    verdicts = [a.verdict for a in per_pose]
    worst = max(verdicts, key=VERDICTS.index)
    cond = [a.conditioning for a in per_pose]
    k = int(np.argmin(cond))
    failures = tuple((i, v) for i, v in enumerate(verdicts) if v != VALID)
    return Combination(inputs, kind, worst, len(per_pose) - len(failures), len(per_pose), float(cond[k]), k, failures)


# ---------------------------------------------------------------------------
# rigid mechanisms
# ---------------------------------------------------------------------------


class _Pose:
    """What one pose of a rigid mechanism needs for actuation checks (computed once)."""

    def __init__(self, mechanism: Mechanism, tol: Tolerance) -> None:
        self.mechanism = mechanism
        self.tol = tol
        self.topology: Topology = decompose(mechanism)
        self.screws: JointScrews = joint_screws(mechanism)
        self.root: SystemValue = evaluate(self.topology.root, self.screws, tol)
        root = self.topology.root
        if isinstance(root, Parallel):
            self.limbs: list[tuple[Node, SystemValue]] = list(zip(root.children, self.root.children))
        else:
            self.limbs = [(root, self.root)]
        self.limb_of: dict[int, int] = {}
        for k, (node, _) in enumerate(self.limbs):
            for j in joints_of(node):
                self.limb_of[j] = k
        self._attach: dict[int, np.ndarray] = {}
        self._cache: dict[tuple[int, int], tuple[np.ndarray | None, float, str]] = {}

    def attachment(self, limb: int) -> np.ndarray:
        """Normalised centroid of the points of the limb's joints on the end effector."""
        if limb not in self._attach:
            node = self.limbs[limb][0]
            ee = self.mechanism.end_effector
            world = self.mechanism.world_joints
            pts = [world[j].point for j in joints_of(node) if ee in world[j].links and world[j].point is not None]
            norm = self.screws.normalisation
            self._attach[limb] = norm.point_from_world(np.mean(pts, axis=0)) if pts else self.screws.reference
        return self._attach[limb]

    def wrench(self, joint: int, freedom: int) -> tuple[np.ndarray | None, float, str]:
        """Unit actuation wrench (normalised), ``a o $`` and a note, for one freedom of a joint."""
        key = (joint, freedom)
        if key not in self._cache:
            self._cache[key] = self._compute(joint, freedom)
        return self._cache[key]

    def _compute(self, joint: int, freedom: int) -> tuple[np.ndarray | None, float, str]:
        if joint not in self.limb_of:
            return None, 1.0, "not on a path between the ground and the end effector"
        limb = self.limb_of[joint]
        node, value = self.limbs[limb]
        col = int(self.screws.offsets[joint]) + freedom
        others = evaluate(node, _locked_column(self.screws, col), self.tol)
        p = self.attachment(limb)
        shift = _shift(p)
        own = value.wrenches
        w_other = shift @ others.wrenches
        if own.shape[1]:
            q, _ = np.linalg.qr(shift @ own)
            w_other = w_other - q @ (q.T @ w_other)
        if w_other.shape[1] == 0:
            return None, 1.0, "its motion is produced by the other joints of its limb: it cannot be driven on its own"
        u, s, _ = svd(w_other)
        if decide_rank(s, self.tol).rank == 0:
            return None, 1.0, "its motion is produced by the other joints of its limb: it cannot be driven on its own"
        a = np.linalg.solve(shift, u[:, 0])
        a /= np.linalg.norm(a)
        twist = self.screws.twists[:, col]
        wn = float(np.linalg.norm(twist[:3]))
        if wn > self.tol.rank:
            twist = twist / wn  # unit angular rate (R, H); P columns are already unit linear rate
        rate = float(a[SWAP_ROWS] @ twist)
        if rate < 0:
            a, rate = -a, -rate
        return a, rate, ""


def _locked_column(screws: JointScrews, col: int) -> JointScrews:
    """The same joint twists with column ``col`` set to zero (that freedom locked)."""
    masked = screws.twists.copy()
    masked[:, col] = 0.0
    changes: dict[str, Any] = {"twists": masked}
    if hasattr(screws, "columns"):
        o = screws.offsets
        changes["columns"] = tuple(masked[:, o[j] : o[j + 1]] for j in range(len(o) - 1))
    return replace(screws, **changes)


def _shift(p: np.ndarray) -> np.ndarray:
    """6x6 map of screw coordinates to an origin at ``p``: ``[a; b] -> [a; b - p x a]``."""
    m = np.eye(6)
    x, y, z = p
    m[3:, :3] = -np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return m


def _inputs_of(mechanism: Mechanism, names: Sequence[str]) -> list[tuple[int, int, str]]:
    """``(joint index, freedom, label)`` for every freedom of the named joints."""
    index = {j.name: i for i, j in enumerate(mechanism.joints)}
    out = []
    for name in names:
        if name not in index:
            raise MechanismError("actuated", f"unknown joint {name!r}; expected one of: {', '.join(index)}")
        j = mechanism.joints[index[name]]
        out += [(index[name], k, name if j.dof == 1 else f"{name}.{k}") for k in range(j.dof)]
    return out


def _check_at(pose: _Pose, names: Sequence[str], warnings: Sequence[str] = ()) -> ActuationCheck:
    m = pose.mechanism
    entries, rates = [], []
    for joint, freedom, label in _inputs_of(m, names):
        w, rate, note = pose.wrench(joint, freedom)
        limb = pose.limb_of.get(joint)
        entries.append((label, m.joints[joint].type, limb, w, note))
        rates.append(rate)
    return _build_check(
        m.name, "rigid", entries, rates, pose.root.basis, pose.root.wrenches, pose.screws.normalisation, pose.screws.reference, pose.tol, warnings, m.length_unit
    )


def check_actuation(mechanism: Mechanism, actuated: Sequence[str] | None = None, *, tol: Tolerance = DEFAULT_TOLERANCE) -> ActuationCheck:
    """Check one choice of actuated joints at the mechanism's pose.

    Parameters
    ----------
    mechanism : Mechanism
    actuated : sequence of str, optional
        Joint names; default: the joints marked ``actuated: true``.  Every
        freedom of a multi-DOF joint is one input.
    tol : Tolerance

    Returns
    -------
    ActuationCheck

    Raises
    ------
    MechanismError
        When a name is not a joint of the mechanism.
    """
    names = [j.name for j in mechanism.joints if j.actuated] if actuated is None else list(actuated)
    warnings = [] if names else ["no joint is actuated (mark joints with `actuated: true`, or name them)"]
    return _check_at(_Pose(mechanism, tol), names, warnings)


def _check_pose(reference: Mechanism, pose: Mechanism, label: str) -> None:
    sig = lambda m: (m.ground, m.end_effector, tuple((j.name, j.type, j.links) for j in m.joints))  # noqa: E731
    if sig(pose) != sig(reference):
        raise MechanismError("poses", f"{label} is not a pose of {reference.name!r}: its joints, links, ground or end effector differ")


def check_over_poses(mechanism: Mechanism, actuated: Sequence[str] | None, poses: Sequence[Mechanism], *, tol: Tolerance = DEFAULT_TOLERANCE) -> tuple[ActuationCheck, ...]:
    """:func:`check_actuation` of one choice at several poses of the same mechanism.

    Each pose must have the same joints (names, types, links), ground and end
    effector; only the geometry differs.
    """
    names = [j.name for j in mechanism.joints if j.actuated] if actuated is None else list(actuated)
    out = []
    for i, pose in enumerate(poses):
        _check_pose(mechanism, pose, pose.source or f"pose {i}")
        out.append(_check_at(_Pose(pose, tol), names))
    return tuple(out)


def enumerate_actuations(
    mechanism: Mechanism,
    *,
    mode: str = "limb",
    k: int | None = None,
    poses: Sequence[Mechanism] = (),
    samples: int = 0,
    step: float = 0.1,
    seed: int = 0,
    tol: Tolerance = DEFAULT_TOLERANCE,
) -> Enumeration:
    """Check every combination of inputs over several poses, and rank the valid ones.

    Candidate inputs are the joints with one freedom (R, P, H) on a path
    between the ground and the end effector.

    Parameters
    ----------
    mechanism : Mechanism
        The given pose (pose 0).
    mode : {"limb", "any"}
        ``"limb"``: one joint in each limb (the paper's enumeration);
        ``"any"``: any ``k`` candidates.
    k : int, optional
        Inputs per combination in ``"any"`` mode (default: the DOF).
    poses : sequence of Mechanism
        Further poses of the same mechanism (listed by the user).
    samples : int
        Further poses reached by moving the mechanism, from
        :func:`mobility.core.kinematics.sample_poses` (with ``step`` and ``seed``).
    tol : Tolerance

    Returns
    -------
    Enumeration
    """
    if mode not in ("limb", "any"):
        raise ValueError(f"mode must be 'limb' or 'any', got {mode!r}")
    warnings: list[str] = []
    first = _Pose(mechanism, tol)
    dof = first.root.dim
    pose_list: list[tuple[str, Mechanism]] = [("given pose", mechanism)]
    for i, p in enumerate(poses):
        label = p.source or f"pose {i + 1}"
        _check_pose(mechanism, p, label)
        pose_list.append((label, p))
    if samples:
        sampled = sample_poses(mechanism, samples, step=step, seed=seed)
        pose_list += [(f"sampled pose {i + 1}", p) for i, p in enumerate(sampled)]
    candidates = [[j for j in joints_of(node) if mechanism.joints[j].dof == 1] for node, _ in first.limbs]
    if mode == "limb":
        k = len(first.limbs)
        for i, c in enumerate(candidates):
            if not c:
                warnings.append(f"limb {i + 1} has no one-freedom joint to actuate")
        combos: Iterable[tuple[int, ...]] = itertools.product(*candidates)
        count = int(np.prod([len(c) for c in candidates]))
    else:
        flat = sorted(j for c in candidates for j in c)
        k = dof if k is None else int(k)
        if k < 0:
            raise ValueError("k must be non-negative")
        combos = itertools.combinations(flat, k)
        count = _binomial(len(flat), k)
    if count > MAX_COMBINATIONS:
        raise ValueError(f"{count} combinations to try (more than {MAX_COMBINATIONS}); choose a smaller k or mode 'limb'")
    if k != dof:
        warnings.append(f"{k} inputs per combination for {dof} DOF: none can be valid ({'redundant' if k > dof else 'too few'})")
    combos = [tuple(c) for c in combos]
    states = [first] + [_Pose(p, tol) for _, p in pose_list[1:]]
    per_combo: list[list[_Assessment]] = [[] for _ in combos]
    for index, state in enumerate(states):
        ws = state.root.basis
        wc = state.root.wrenches
        if ws.shape[1] != dof:
            warnings.append(f"the end effector has {ws.shape[1]} DOF at pose {index} ({pose_list[index][0]}), {dof} at the given pose")
        for c, found in zip(combos, per_combo):
            got = [state.wrench(j, 0) for j in c]
            found.append(_assess([g[0] for g in got], [g[1] for g in got if g[0] is not None], ws, wc, tol))
    names = mechanism.joints
    results = [_combine(tuple(names[j].name for j in c), combination_type(names[j].type for j in c), f) for c, f in zip(combos, per_combo)]
    ranked, groups = _rank_combinations(results)
    pattern = _pattern(first.root.basis, tol)
    return Enumeration(mechanism.name, "rigid", dof, pattern, mode, k, ranked, groups, tuple(label for label, _ in pose_list), tuple(warnings))


def _pattern(basis: np.ndarray, tol: Tolerance) -> str:
    rot = free_vector_subspace(basis, tol, coefficients=False).rank
    return pattern_of(basis.shape[1] - rot, rot)


def _binomial(n: int, k: int) -> int:
    return comb(n, k) if 0 <= k <= n else 0


# ---------------------------------------------------------------------------
# the second route: lock the inputs, count what is left
# ---------------------------------------------------------------------------


def lock_joints(mechanism: Mechanism, names: Iterable[str]) -> Mechanism | None:
    """The mechanism with the named joints made rigid: each removed, its two links merged.

    Joints left joining a link to itself (their links were merged through
    other locked joints) are removed too: they cannot move.

    Returns
    -------
    Mechanism or None
        ``None`` when the end effector is merged with the ground (it cannot move).

    Raises
    ------
    MechanismError
        When a name is not a joint of the mechanism.
    """
    names = set(names)
    known = {j.name for j in mechanism.joints}
    for n in sorted(names - known):
        raise MechanismError("actuated", f"unknown joint {n!r}")
    parent: dict[str, str] = {}

    def find(x: str) -> str:
        while parent.get(x, x) != x:
            x = parent[x]
        return x

    keep = (mechanism.ground, mechanism.end_effector)
    for j in mechanism.joints:
        if j.name in names:
            a, b = find(j.links[0]), find(j.links[1])
            if a != b:
                if b in keep and a not in keep:
                    a, b = b, a
                if a == mechanism.end_effector and b == mechanism.ground:
                    a, b = b, a
                parent[b] = a
    if find(mechanism.end_effector) == find(mechanism.ground):
        return None
    joints = []
    for j in mechanism.joints:
        if j.name in names:
            continue
        a, b = find(j.links[0]), find(j.links[1])
        if a == b:
            continue
        joints.append(j if (a, b) == j.links else _relinked(j, (a, b)))
    return mechanism.replace(joints=tuple(joints), expected=None)


def _relinked(joint: Joint, links: tuple[str, str]) -> Joint:
    return replace(joint, links=links)


def locked_dof(mechanism: Mechanism, names: Iterable[str], *, tol: Tolerance = DEFAULT_TOLERANCE) -> int:
    """DOF of the end effector with the named joints locked, by loop closure (an independent route).

    Examples
    --------
    >>> from mobility.core.model import Joint, Mechanism
    >>> m = Mechanism("RR arm", "g", "hand", (Joint("A", "R", ("g", "arm"), axis=(0, 0, 1), point=(0, 0, 0)),
    ...                                      Joint("B", "R", ("arm", "hand"), axis=(0, 0, 1), point=(1, 0, 0))))
    >>> locked_dof(m, []), locked_dof(m, ["A"]), locked_dof(m, ["A", "B"])
    (2, 1, 0)
    """
    locked = lock_joints(mechanism, names)
    if locked is None:
        return 0
    return int(loop_closure(locked, tol).end_effector_twists.shape[1])
