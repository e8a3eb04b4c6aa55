"""What an actuation assessment answers: frozen results and their JSON form.

Numbers go to JSON through :func:`mobility.core.tolerance.clean_numbers` (round-off shown as 0).

Examples
--------
>>> c = Combination(("P1", "P2", "P3"), "3P", VALID, 2, 2, 0.3, 1)
>>> c.to_dict()["failures"], VERDICTS.index(REDUNDANT) < VERDICTS.index(SINGULAR)
([], True)
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields
from typing import Any

import numpy as np

from ..core.frozen import ReadOnlyArrays
from ..core.result import ScrewAxis
from ..core.tolerance import RankDecision, clean_numbers

__all__ = ["VALID", "SINGULAR", "REDUNDANT", "VERDICTS", "ActuationInput", "ActuationCheck", "Combination", "TypeGroup", "Enumeration"]

VALID = "valid"
SINGULAR = "actuation-singular"
REDUNDANT = "redundant"
VERDICTS = (VALID, REDUNDANT, SINGULAR)
"""The verdicts, best first."""


@dataclass(frozen=True, eq=False)
class ActuationInput(ReadOnlyArrays):
    """One input (an actuated joint freedom or a linear actuator) and its actuation wrench.

    Attributes
    ----------
    name : str
        Joint name (with ``.k`` for freedom ``k`` of a multi-DOF joint) or actuator name.
    kind : str
        Joint type letter, or ``"F"`` for a linear actuator (a force line).
    limb : int or None
        The joint's limb (0-based); ``None`` for a linear actuator or a joint off every path.
    wrench : ndarray, shape (6,) or None
        The actuation wrench ``[f; m]``, global frame, ``|f| = 1`` (a couple: ``|m| = 1``).
    axis : ScrewAxis or None
        Its line: ``"force"`` (pitch 0), ``"wrench"`` or ``"couple"`` (the
        couple's direction, through the reference point).
    in_constraint_space : bool
        The wrench is a combination of constraint wrenches: the input cannot move the end effector.
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
        """JSON form; ``scale`` is the length that round-off of points is relative to."""
        return {"name": self.name, "kind": self.kind, "limb": self.limb, "wrench": None if self.wrench is None else clean_numbers(self.wrench, scale),
                "axis": None if self.axis is None else self.axis.to_dict(scale), "in_constraint_space": self.in_constraint_space, "note": self.note}


@dataclass(frozen=True, eq=False)
class ActuationCheck(ReadOnlyArrays):
    """The verdict on one choice of inputs at one pose.

    Attributes
    ----------
    name, kind : str
        The mechanism's name; ``"rigid"`` or ``"flexure"``.
    dof : int
        DOF of the end effector (of the freedom space, for a flexure).
    pattern : str
        Its motion pattern, e.g. ``"1T2R"``.
    inputs : tuple of ActuationInput
    constraint_couples, constraint_forces, constraint_wrenches : ndarray (k, 3), tuple of ScrewAxis, ndarray (6 - dof, 6)
        The pure couples among the constraint wrenches (orthonormal), the other
        constraint wrenches (principal screws), and a basis (rows ``[f; m]``, global frame).
    verdict : str
        ``"valid"``, ``"actuation-singular"`` or ``"redundant"``.
    rank : int
        Rank of the actuation and constraint wrenches together.
    uncontrolled_translations, uncontrolled_rotations, uncontrolled_twists : ndarray (k, 3), tuple of ScrewAxis, ndarray (6 - rank, 6)
        What the end effector keeps with every input locked: translations,
        rotations (or screw motions), and a basis (rows ``[w; v]``, global frame).
    margin : RankDecision
        Of the verdict's rank decision: a small ``smallest_kept`` means near a
        pose where the locked inputs no longer hold the end effector.
    conditioning : float
        The actuation conditioning ``kappa``; 0 when actuation-singular.
    explanation : str
        One sentence on the verdict.
    warnings : tuple of str
    length_unit : str
    length_scale : float
        For rounding output.
    actuation_margin : float
        The distance to an actuation singularity (:mod:`mobility.actuation.assessment`).
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
    actuation_margin: float = 1.0

    @property
    def valid(self) -> bool:
        """True when the verdict is ``"valid"``."""
        return self.verdict == VALID

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        s = self.length_scale
        return {"name": self.name, "kind": self.kind, "dof": self.dof, "pattern": self.pattern, "verdict": self.verdict, "explanation": self.explanation,
                "rank": self.rank, "conditioning": self.conditioning,
                "margin": {"smallest_kept": self.margin.smallest_kept, "largest_dropped": self.margin.largest_dropped},
                "actuation_margin": self.actuation_margin, "inputs": [i.to_dict(s) for i in self.inputs],
                "constraints": {"couples": clean_numbers(self.constraint_couples), "forces": [f.to_dict(s) for f in self.constraint_forces],
                                "wrenches": clean_numbers(self.constraint_wrenches, s)},
                "uncontrolled": {"translations": clean_numbers(self.uncontrolled_translations), "rotations": [r.to_dict(s) for r in self.uncontrolled_rotations],
                                 "twists": clean_numbers(self.uncontrolled_twists, s)},
                "warnings": list(self.warnings), "length_unit": self.length_unit}


@dataclass(frozen=True)
class Combination:
    """One combination of inputs, assessed at every pose.

    Attributes
    ----------
    inputs : tuple of str
        Joint (or actuator) names.
    type : str
        Its group, e.g. ``"2R1P"`` (:func:`mobility.actuation.combination_type`).
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
    margin : float
        Smallest actuation margin over the poses where it is not
        actuation-singular; at most 1.0, and 1.0 when there is none.
    margin_pose : int
        Index of the pose where it is smallest.
    """

    inputs: tuple[str, ...]
    type: str
    verdict: str
    valid_poses: int
    poses: int
    conditioning: float
    worst_pose: int
    failures: tuple[tuple[int, str], ...] = ()
    margin: float = 1.0
    margin_pose: int = 0

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {f.name: getattr(self, f.name) for f in fields(self)} | {"inputs": list(self.inputs), "failures": [list(f) for f in self.failures]}


@dataclass(frozen=True)
class TypeGroup:
    """How many combinations of one type are valid."""

    type: str
    valid: int
    total: int

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return asdict(self)


@dataclass(frozen=True)
class Enumeration:
    """Every combination of inputs, assessed over several poses and ranked.

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
        Inputs per combination.
    combinations : tuple of Combination
        Ranked: valid ones by decreasing conditioning, then redundant, then actuation-singular.
    groups : tuple of TypeGroup
        Valid and total counts per type.
    poses : tuple of str
        A label for each pose visited (index 0: the given pose).
    warnings : tuple of str
    limbs : int
        The rigid mechanism's limbs (0 for a flexure).
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
    limbs: int = 0

    @property
    def valid(self) -> tuple[Combination, ...]:
        """The valid combinations, best first."""
        return tuple(c for c in self.combinations if c.verdict == VALID)

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {"name": self.name, "kind": self.kind, "dof": self.dof, "pattern": self.pattern, "mode": self.mode, "k": self.k, "limbs": self.limbs,
                "poses": list(self.poses), "groups": [g.to_dict() for g in self.groups], "combinations": [c.to_dict() for c in self.combinations],
                "warnings": list(self.warnings)}
