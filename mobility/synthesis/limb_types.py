"""Limb types: joint sequences found by the synthesis, named as in Sun et al. (2018).

Each one-DOF joint of the enumeration is a :class:`CandidateJoint` (a
:class:`~mobility.core.finite_screws.ScrewJoint` with the labels of its
direction and point).  :func:`joint_groups` names runs of joints as the paper
does (docs/finite-screws.md, "Type synthesis": ``S``, ``U``, ``Rc``, ``Rs1``,
``P1``); the sequences with the same group names form one limb type
(:class:`SynthesizedLimb`), e.g. ``UP1RcP2``.

Examples
--------
>>> from mobility.core.finite_screws import ScrewJoint
>>> R = lambda d, e: CandidateJoint(ScrewJoint("R", e), d, "O")
>>> P = lambda d, e: CandidateJoint(ScrewJoint("P", e), d)
>>> seq = (R("s1", (1, 0, 0)), R("s2", (0, 1, 0)), P("s1", (1, 0, 0)), R("c", (0, 0, 1)))
>>> [(name, len(members)) for name, members in joint_groups(seq, ("s1", "s2"))]
[('U', 2), ('P1', 1), ('Rc', 1)]
>>> seq[0].label, seq[2].label
('R[s1@O]', 'P[s1]')
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

from ..core.finite_screws import ScrewJoint

__all__ = ["TABLE_1_2T3R", "CandidateJoint", "SynthesizedLimb", "joint_groups", "limb_types"]

TABLE_1_2T3R = ("SP1P2", "UP1P2Rc", "UP1RcP2", "SP1Rc", "SRcRc", "UP1RcRc", "SRcP1")
"""The seven 5-DOF limbs of Table 1 of Sun et al. (2018) for 2T3R PKMs (for comparison only)."""


@dataclass(frozen=True)
class CandidateJoint:
    """A one-DOF joint of the enumeration, with the labels of its direction and point."""

    joint: ScrewJoint
    direction: str
    point: str = ""

    @property
    def label(self) -> str:
        """e.g. ``R[c@g1]`` or ``P[s1]``."""
        return f"{self.joint.kind}[{self.direction}{'@' + self.point if self.point else ''}]"


@dataclass(frozen=True)
class SynthesizedLimb:
    """A limb type found by :func:`~mobility.synthesis.synthesize`: a name and every joint sequence realising it.

    Attributes
    ----------
    name : str
        Paper-style name, e.g. ``"UP1RcP2"``.
    groups : tuple of str
        The joint groups in order (``S``, ``U``, ``Rc``, ``P1``...).
    realizations : tuple of tuple of CandidateJoint
        The joint sequences found (directions and points from the pattern).
    conditions : tuple of str
        One line per group: the directions and points it was found with.
    in_table_1 : bool
        Whether the name is among the seven of Table 1 of Sun et al. (2018)
        (meaningful for the 2T3R pattern only; for comparison, not used to decide).
    """

    name: str
    groups: tuple[str, ...]
    realizations: tuple[tuple[CandidateJoint, ...], ...]
    conditions: tuple[str, ...]
    in_table_1: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {"name": self.name, "groups": list(self.groups), "conditions": list(self.conditions), "in_table_1": self.in_table_1,
                "realizations": [[c.label for c in r] for r in self.realizations]}


def joint_groups(seq: Sequence[CandidateJoint], plane: tuple[str, ...]) -> list[tuple[str, list[CandidateJoint]]]:
    """Split a joint sequence into named groups: runs of R through one point (S, U), Rc, P1, P2...

    A P along one of the pattern's translation directions ``plane`` (``s1, s2``)
    is numbered ``P1, P2...``, any other named by its direction.
    """
    out: list[tuple[str, list[CandidateJoint]]] = []
    i = 0
    p_count = 0
    while i < len(seq):
        c = seq[i]
        if c.joint.kind == "R":
            j = i
            while j + 1 < len(seq) and seq[j + 1].joint.kind == "R" and seq[j + 1].point == c.point:
                j += 1
            for k in range(i, j + 1, 3):  # three R through one point are an S, two a U
                take = list(seq[k : min(k + 3, j + 1)])
                out.append(({3: "S", 2: "U"}.get(len(take)) or ("Rc" if take[0].direction == "c" else f"R{take[0].direction}"), take))
            i = j + 1
        else:
            p_count += c.direction in plane
            out.append((f"P{p_count}" if c.direction in plane else f"P{c.direction}", [c]))
            i += 1
    return out


def limb_types(found: Sequence[tuple[CandidateJoint, ...]], pattern_name: str, plane: tuple[str, ...]) -> tuple[SynthesizedLimb, ...]:
    """Group the joint sequences kept by the enumeration into limb types, in order of first discovery.

    Table 1 is marked for the pattern ``"2T3R"`` only; ``plane``: as for :func:`joint_groups`.
    """
    by_name: dict[str, list[tuple[tuple[str, ...], tuple[CandidateJoint, ...], list[list[CandidateJoint]]]]] = {}
    for seq in found:
        groups = joint_groups(seq, plane)
        name = "".join(g for g, _ in groups)
        by_name.setdefault(name, []).append((tuple(g for g, _ in groups), seq, [m for _, m in groups]))
    out = []
    for name, entries in by_name.items():
        names = entries[0][0]
        conditions = []
        for k, g in enumerate(names):
            members = [e[2][k] for e in entries]
            pts = sorted({c.point for m in members for c in m if c.point})
            where = f" through {' or '.join(pts)}" if pts else ""
            if g == "S":
                conditions.append(f"S: three R{where}")
            elif g == "U":
                axes = sorted({"(" + ", ".join(c.direction for c in m) + ")" for m in members})
                conditions.append(f"U: two R{where}, axes {' or '.join(axes)}")
            else:
                dirs = sorted({m[0].direction for m in members})
                what = "along" if g.startswith("P") else "axis along"
                conditions.append(f"{g}: {what} {' or '.join(dirs)}{where}")
        out.append(SynthesizedLimb(name, names, tuple(e[1] for e in entries), tuple(conditions), pattern_name == "2T3R" and name in TABLE_1_2T3R))
    return tuple(out)
