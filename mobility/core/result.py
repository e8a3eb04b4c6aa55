"""Frozen results of an analysis.

Answers only, in the global frame and the file's length unit; screws are
rows (``twists[i] = [w; v]``, ``wrenches[i] = [f; m]``).  Every array a result
holds or computes is read-only (:class:`~mobility.core.frozen.ReadOnlyArrays`).
"""

from __future__ import annotations

from collections import deque
from dataclasses import asdict, dataclass, field
from dataclasses import fields as dataclass_fields
from functools import cached_property
from types import MappingProxyType
from typing import Any, Mapping, NamedTuple, Protocol

import numpy as np

from ..errors import RequestError, clipped, counted
from .frozen import ReadOnlyArrays, read_only_cached_property
from .model import Mechanism
from .screws import pattern_of
from .tolerance import DEFAULT_TOLERANCE, PRECISION_CEILING, PRECISION_FACTOR, clean_numbers, file_tolerance
from .topology import Bridge, Node, Parallel, Series, Topology, describe, joints_of

__all__ = ["ScrewAxis", "Margin", "LimbSystem", "NodeSystem", "Result", "ResultDetail", "pattern_of", "require_result",
           "require_result_of", "require_same_mechanism"]


@dataclass(frozen=True, eq=False)
class ScrewAxis(ReadOnlyArrays):
    """A screw axis in the global frame.

    For a twist, a rotation about ``axis`` through ``point`` with ``pitch``
    (length per radian) of translation along it; for a wrench, a force along
    ``axis`` with a couple ``pitch`` times it.

    Examples
    --------
    >>> ScrewAxis(np.array([0.0, 0.0, 1.0]), np.zeros(3), 0.0, "rotation").to_dict()["axis"]
    [0.0, 0.0, 1.0]
    """

    axis: np.ndarray
    point: np.ndarray
    pitch: float
    kind: str

    def to_dict(self, scale: float = 1.0) -> dict[str, Any]:
        """JSON form: axis, point, pitch, kind."""
        return {"axis": clean_numbers(self.axis), "point": clean_numbers(self.point, scale), "pitch": clean_numbers(self.pitch, scale), "kind": self.kind}


@dataclass(frozen=True)
class Margin:
    """How far the rank decisions of an analysis were from changing.

    ``smallest_kept``: the smallest singular value counted, relative to the
    largest of its matrix (small: near a singularity); ``largest_dropped``: the
    largest counted as zero (well above round-off: geometry only nearly
    special); ``near_singular`` and ``inexact`` say whether the policy warned.

    Examples
    --------
    >>> Margin(0.5, 0.0, False, False).to_dict()["smallest_kept"]
    0.5
    """

    smallest_kept: float
    largest_dropped: float
    near_singular: bool
    inexact: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return asdict(self)


@dataclass(frozen=True, eq=False)
class LimbSystem(ReadOnlyArrays):
    """Twist and constraint systems of one limb (a branch of the top parallel connection).

    Written in ``frame`` (the one all the limb's joints are written in, else
    ``world``), in the canonical form of :class:`Result`.
    """

    structure: str
    frame: str
    dof: int
    idle_dof: int
    translations: np.ndarray
    rotations: tuple[ScrewAxis, ...]
    twists: np.ndarray
    couples: np.ndarray
    forces: tuple[ScrewAxis, ...]
    wrenches: np.ndarray

    def to_dict(self, scale: float = 1.0) -> dict[str, Any]:
        """JSON form."""
        return {"structure": self.structure, "frame": self.frame, "dof": self.dof, "idle_dof": self.idle_dof,
                "translations": clean_numbers(self.translations), "rotations": [r.to_dict(scale) for r in self.rotations],
                "twists": clean_numbers(self.twists, scale),
                "constraints": {"couples": clean_numbers(self.couples), "forces": [f.to_dict(scale) for f in self.forces]},
                "wrenches": clean_numbers(self.wrenches, scale)}


class NodeSystem(NamedTuple):
    """What the analysis found at one node of the series/parallel tree.

    ``dof``: dimension of the twist system between the node's two end links
    (a joint's DOF); ``idle``: motions inside the node that leave them still.

    Examples
    --------
    >>> NodeSystem(2, 1).mobility
    3
    """

    dof: int
    idle: int

    @property
    def mobility(self) -> int:
        """Mobility of the node's network with one end link fixed: ``dof + idle``."""
        return self.dof + self.idle


class ResultDetail(Protocol):
    """What a :class:`Result` computes its lazy parts from (provided by the analysis)."""

    mechanism: Mechanism
    topology: Topology

    def node_systems(self) -> dict[Node, NodeSystem]: ...
    def twist_form(self) -> tuple[np.ndarray, tuple[ScrewAxis, ...], np.ndarray]: ...
    def wrench_form(self) -> tuple[np.ndarray, tuple[ScrewAxis, ...], np.ndarray]: ...
    def limbs(self) -> tuple[LimbSystem, ...]: ...
    def common_constraints(self) -> int: ...
    def common_motion(self) -> str: ...


@dataclass(frozen=True, eq=False)
class Result(ReadOnlyArrays):
    """What :func:`mobility.analyze` finds.

    The counts come with it; directions, limb systems and common constraints
    are computed on first access and kept.  It pickles at any time; two
    results are equal only when they are the same object.

    Attributes
    ----------
    name : str
    dof : int
        End-effector DOF at this pose.
    pattern : str
        ``{nT}T{nR}R``, e.g. ``"1T2R"``.
    mobility : int
        DOF of the whole mechanism (idle motions included).
    gruebler_kutzbach : int
        ``6 (n - 1 - j) + sum f``.
    redundant_constraints : int
        ``mobility - gruebler_kutzbach``: loop-closure equations that repeat others.
    idle_dof : int
        ``mobility - dof``: motions that leave the end effector still.
    loops : int
        Independent loops ``j - n + 1``.
    links, joints, joint_freedoms : int
        Counts of the joint graph.
    structure : str
        The series/parallel decomposition.
    margin : Margin
    warnings : tuple of str
    length_unit : str
    length_scale : float
        Characteristic size of the mechanism (for rounding output).
    reference_point : ndarray, shape (3,)
        The end effector's centre (centroid of its joints' points): axes are
        reported through their point nearest to it, so an axis away from it
        (or a non-zero pitch) shows how rotating moves this point.

    Examples
    --------
    >>> import mobility, numpy as np
    >>> r = mobility.analyze(mobility.load("mechanisms/3prs.yaml"))
    >>> r.dof, r.pattern, (np.round(r.translations, 12) + 0.0).tolist()  # + 0.0: no -0.0 of round-off
    (3, '1T2R', [[0.0, 0.0, 1.0]])
    >>> [(a.kind, round(a.pitch, 9)) for a in r.rotations], r.wrenches.shape
    ([('rotation', 0.0), ('rotation', 0.0)], (3, 6))
    >>> r.to_dict()["mobility"]
    3
    """

    name: str
    dof: int
    pattern: str
    mobility: int
    gruebler_kutzbach: int
    redundant_constraints: int
    idle_dof: int
    loops: int
    links: int
    joints: int
    joint_freedoms: int
    structure: str
    margin: Margin
    warnings: tuple[str, ...]
    length_unit: str
    length_scale: float
    reference_point: np.ndarray
    detail: ResultDetail = field(repr=False)

    @read_only_cached_property
    def _twist_form(self) -> tuple[np.ndarray, tuple[ScrewAxis, ...], np.ndarray]:
        return self.detail.twist_form()

    @read_only_cached_property
    def _wrench_form(self) -> tuple[np.ndarray, tuple[ScrewAxis, ...], np.ndarray]:
        return self.detail.wrench_form()

    @property
    def translations(self) -> np.ndarray:
        """Orthonormal basis (rows, shape (nT, 3)) of the pure-translation subspace."""
        return self._twist_form[0]

    @property
    def rotations(self) -> tuple[ScrewAxis, ...]:
        """One screw axis per rotational DOF (:mod:`mobility.core.canonical`), ``kind`` ``"rotation"`` (pitch 0) or ``"helical"``."""
        return self._twist_form[1]

    @property
    def twists(self) -> np.ndarray:
        """Basis (rows ``[w; v]``, shape (dof, 6)) of the end-effector twist system: translations, then rotations."""
        return self._twist_form[2]

    @property
    def couples(self) -> np.ndarray:
        """Orthonormal basis (rows) of the pure constraint couples."""
        return self._wrench_form[0]

    @property
    def forces(self) -> tuple[ScrewAxis, ...]:
        """The constraint wrenches that are not pure couples, as axes: ``kind`` ``"force"`` (pitch 0) or ``"wrench"``."""
        return self._wrench_form[1]

    @property
    def wrenches(self) -> np.ndarray:
        """Basis (rows ``[f; m]``, shape (6 - dof, 6)) of the constraint wrench system on the end effector: couples, then forces."""
        return self._wrench_form[2]

    @read_only_cached_property
    def limbs(self) -> tuple[LimbSystem, ...]:
        """Twist and constraint systems of each branch of a top-level parallel connection, in its own frame."""
        return self.detail.limbs()

    @cached_property
    def common_constraints(self) -> int:
        """Number of independent wrenches reciprocal to every joint twist (3 for a planar mechanism)."""
        return self.detail.common_constraints()

    @property
    def topology(self) -> Topology:
        """The series/parallel decomposition the analysis used (``structure`` writes its root out)."""
        return self.detail.topology

    @property
    def mechanism(self) -> Mechanism:
        """The mechanism that was analysed (at the pose analysed)."""
        return self.detail.mechanism

    @cached_property
    def _node_systems(self) -> dict[Node, NodeSystem]:
        return self.detail.node_systems()  # kept as a dict: a mapping proxy cached here would not pickle

    @property
    def node_systems(self) -> Mapping[Node, NodeSystem]:
        """DOF and idle count of every node of :attr:`topology` (root, detached networks, joints), read-only.

        Examples
        --------
        >>> import mobility
        >>> m = mobility.loads('''
        ... name: two sliders in series
        ... ground: g
        ... end_effector: e
        ... joints:
        ...   - {name: P1, type: P, links: [g, x], axis: [1, 0, 0]}
        ...   - {name: P2, type: P, links: [x, e], axis: [1, 0, 0]}
        ... ''')
        >>> r = mobility.analyze(m)
        >>> r.node_systems[r.topology.root]
        NodeSystem(dof=1, idle=1)
        """
        return MappingProxyType(self._node_systems)

    @property
    def precision(self) -> float | None:
        """The precision of the mechanism's file, relative to its size (:attr:`Mechanism.precision`); ``None``: exact."""
        return getattr(getattr(self.detail, "mechanism", None), "precision", None)  # a result rebuilt without its mechanism: exact

    @property
    def rank_threshold(self) -> float:
        """The relative rank threshold that decided the counts (:attr:`~mobility.core.tolerance.Tolerance.rank`)."""
        tol = getattr(self.detail, "tol", None)
        return DEFAULT_TOLERANCE.rank if tol is None else float(tol.rank)

    @property
    def precision_summary(self) -> str:
        """What the file's precision did to the threshold, in one sentence; empty when it did nothing (an exact file).

        Examples
        --------
        >>> import mobility
        >>> mobility.analyze(mobility.load("mechanisms/four_bar.yaml")).precision_summary
        ''
        """
        precision = self.precision
        own = file_tolerance(precision).rank
        if precision is None or own <= DEFAULT_TOLERANCE.rank:
            return ""
        found = f"the file is precise to {precision:.1e} of its size"
        if self.rank_threshold == own:
            factor = "its ceiling" if own == PRECISION_CEILING < PRECISION_FACTOR * precision else f"{PRECISION_FACTOR:g} x its precision"
            return (f"{found}: ranks decided at {own:.1e} ({factor}) instead of {DEFAULT_TOLERANCE.rank:.0e}, "
                    "as its designer drew it; --tol decides at another threshold")
        return f"{found}: ranks decided at {self.rank_threshold:.1e} as asked (its precision would give {own:.1e}): its rounding may decide counts"

    @property
    def translation_count(self) -> int:
        """Number of independent pure translations (nT)."""
        return int(self.pattern.split("T")[0]) if "T" in self.pattern else 0

    @property
    def gruebler_kutzbach_explanation(self) -> str:
        """Why the Grübler–Kutzbach count differs from the mobility (empty when it does not)."""
        if self.redundant_constraints == 0:
            return ""
        redundant = self.redundant_constraints
        loops = "the 1 independent loop imposes" if self.loops == 1 else f"each of the {self.loops} independent loops imposes"
        coupled = len(getattr(getattr(self.detail, "mechanism", None), "couplings", ()))  # one constraint each (a result rebuilt without its mechanism: none)
        by_couplings = f" and each of the {coupled} couplings of joints 1" if coupled > 1 else " and the coupling of joints 1" if coupled else ""
        text = (
            f"Grübler–Kutzbach assumes {loops} 6 independent "
            f"constraints{by_couplings} ({6 * self.loops + coupled} in all); the loop-closure equations have rank {self.joint_freedoms - self.mobility}, so "
            f"{redundant} constraint{' is' if redundant == 1 else 's are'} redundant and the mobility is "
            f"{self.gruebler_kutzbach} + {redundant} = {self.mobility}."
        )
        common = self.common_constraints * self.loops
        if common:
            kind = {
                "translation": " (three couples: every joint only translates)",
                "planar": " (every joint moves in one plane)",
                "spherical": " (three forces through one point: every joint turns about it)",
            }.get(self.detail.common_motion(), "")
            each = self.common_constraints
            text += (
                f" {common} of them come{'s' if common == 1 else ''} from {counted(each, 'wrench', 'es')} reciprocal to every joint twist"
                f"{kind}: {'the loop loses' if self.loops == 1 else 'each loop loses'} {counted(each, 'equation')}."
            )
        rest = self.redundant_constraints - common
        inner = self._inner_loops()
        within = min(sum(beyond for _, beyond in inner), rest)
        if within > 0:
            shown = [describe(node) for node, _ in inner[:3]] + ([f"{len(inner) - 3} more"] if len(inner) > 3 else [])
            counts = sorted({beyond for _, beyond in inner})
            share = f"{counts[0]} each" if len(counts) == 1 else "between them"
            more = " more" if common else ""
            text += (
                f" {within}{more} come{'s' if within == 1 else ''} from {'the loop' if len(inner) == 1 else f'{len(inner)} sub-networks of loops'} "
                f"inside the limbs, whose joints share further constraint wrenches (planar loops such as parallelograms, "
                f"spherical loops): {'; '.join(shown)} ({share}{', beyond those common to every joint' if common else ''})."
            )
            rest -= within
        if rest > 0:
            other = "other " if within > 0 else ""
            text += f" {rest} come{'s' if rest == 1 else ''} from the special geometry of the {other}loops (parallel or intersecting axes, repeated constraints of parallel limbs)."
        return text

    def _inner_loops(self) -> list[tuple[Node, int]]:
        """``(node, redundant)`` of each outermost sub-network of loops below the top (a parallelogram in a limb) with redundant > 0:
        its mobility less its own Grübler–Kutzbach count and less :attr:`common_constraints` per loop."""
        root, mechanism = self.topology.root, getattr(self.detail, "mechanism", None)  # a result rebuilt without its mechanism: nothing to attribute
        if mechanism is None or not isinstance(root, (Series, Parallel)):
            return []
        systems = self.node_systems
        joints = mechanism.joints
        out: list[tuple[Node, int]] = []
        stack: deque[Node] = deque(root.children)  # in tree order, without recursion
        while stack:
            node = stack.popleft()
            if isinstance(node, Series):
                stack.extendleft(reversed(node.children))
            elif isinstance(node, (Parallel, Bridge)) and node in systems:
                members = joints_of(node)
                links = {link for j in members for link in joints[j].links}
                loops = len(members) - len(links) + 1
                count = 6 * (len(links) - 1 - len(members)) + sum(joints[j].dof for j in members)
                beyond = systems[node].mobility - count - self.common_constraints * loops
                if loops > 0 and beyond > 0:
                    out.append((node, beyond))
        return out

    def to_dict(self) -> dict[str, Any]:
        """The JSON form: the spec's Result keys plus the whole-mechanism numbers (``precision`` when the file's would raise the threshold)."""
        s = self.length_scale
        counts = ("mobility", "gruebler_kutzbach", "redundant_constraints", "idle_dof", "loops", "links", "joints", "joint_freedoms",
                  "common_constraints", "gruebler_kutzbach_explanation", "structure")
        return (
            {"name": self.name, "dof": self.dof, "pattern": self.pattern, "translations": clean_numbers(self.translations),
             "rotations": [r.to_dict(s) for r in self.rotations], "twists": clean_numbers(self.twists, s),
             "wrenches": clean_numbers(self.wrenches, s),
             "constraints": {"couples": clean_numbers(self.couples), "forces": [f.to_dict(s) for f in self.forces]}}
            | {key: getattr(self, key) for key in counts}
            | {"margin": self.margin.to_dict(), "warnings": list(self.warnings), "limbs": [limb.to_dict(s) for limb in self.limbs],
               "length_unit": self.length_unit, "reference_point": clean_numbers(self.reference_point, s)}
            | ({"precision": {"value": self.precision, "rank_threshold": self.rank_threshold,
                              "raised": self.rank_threshold == file_tolerance(self.precision).rank}} if self.precision_summary else {})
        )


def require_result(value: object, caller: str) -> Result:
    """``value`` when it is a :class:`Result`, else a :class:`~mobility.errors.RequestError` naming ``caller``.

    Examples
    --------
    >>> require_result(None, "text_report")
    Traceback (most recent call last):
    mobility.errors.RequestError: text_report: expected a Result (from mobility.analyze), got NoneType
    """
    if not isinstance(value, Result):
        raise RequestError(caller=caller, expected="a Result (from mobility.analyze)", got=type(value).__name__)
    return value


def require_result_of(mechanism: Mechanism, value: object, caller: str) -> Result:
    """``value`` when it is a :class:`Result` of ``mechanism``, else a :class:`~mobility.errors.RequestError` naming ``caller``.

    Examples
    --------
    >>> import mobility
    >>> four_bar, head = mobility.load("mechanisms/four_bar.yaml"), mobility.load("mechanisms/3prs.yaml")
    >>> require_result_of(four_bar, mobility.analyze(four_bar), "plot_mechanism").pattern
    '1R'
    >>> require_result_of(four_bar, mobility.analyze(head), "plot_mechanism")
    Traceback (most recent call last):
    mobility.errors.RequestError: plot_mechanism: the result is of another mechanism ('3-PRS parallel head (Sprint Z3), symmetric pose') than 'planar four-bar'; pass the result of analysing this one, or none
    """
    result = require_result(value, caller)
    require_same_mechanism(mechanism, result, caller)
    return result


def require_same_mechanism(mechanism: Mechanism, result: object, caller: str) -> None:
    """A :class:`~mobility.errors.RequestError` naming ``caller`` when ``result`` analysed another mechanism than ``mechanism``.

    Mechanisms compare by value (fields, joints, pose; not where the file was
    read from); a result that does not keep its mechanism is taken as it is.

    Examples
    --------
    >>> import mobility
    >>> four_bar = mobility.load("mechanisms/four_bar.yaml")
    >>> moved = mobility.sample_poses(four_bar, 1, step=0.2, seed=1)[0]
    >>> require_same_mechanism(four_bar, mobility.analyze(mobility.load("mechanisms/four_bar.yaml")), "plot_graph")  # an equal one
    >>> require_same_mechanism(four_bar, mobility.analyze(moved), "plot_graph")
    Traceback (most recent call last):
    mobility.errors.RequestError: plot_graph: the result is of another mechanism than 'planar four-bar' (of the same name, with other joints, pose or fields); pass the result of analysing this one, or none
    """
    analysed = getattr(result, "mechanism", None)
    if analysed is None or analysed is mechanism:
        return
    same = (getattr(analysed, f.name) == getattr(mechanism, f.name) for f in dataclass_fields(Mechanism) if f.compare and f.name != "source")
    if not isinstance(analysed, Mechanism) or not all(same):  # equal but perhaps for where it was read from
        name = clipped(repr(mechanism.name), 60)
        other = clipped(repr(getattr(analysed, "name", analysed)), 60)
        which = f"than {name} (of the same name, with other joints, pose or fields)" if other == name else f"({other}) than {name}"
        raise RequestError(f"the result is of another mechanism {which}; pass the result of analysing this one, or none", caller=caller)
