"""The actuation-space algebra shared by rigid and flexure mechanisms: verdict and conditioning.

In the normalised coordinates of :mod:`mobility.core.tolerance`; results are
reported in the global frame.  The verdict (``valid``, ``actuation-singular``,
``redundant``), the conditioning ``kappa`` and the actuation margin are
defined in docs/actuation.md, "Definitions".

Examples
--------
A slider along ``x``: its constraint wrenches are every wrench without a
force along ``x``.

>>> import numpy as np
>>> twists = np.eye(6)[:, [3]]                   # the twist [0; e_x]
>>> constraints = np.eye(6)[:, [1, 2, 3, 4, 5]]  # f_y, f_z and every couple
>>> a = assess_wrenches([np.eye(6)[0]], [1.0], twists, constraints)  # a force along x
>>> a.verdict, a.decision.rank, a.conditioning
('valid', 6, 1.0)
>>> b = assess_wrenches([np.eye(6)[1]], [1.0], twists, constraints)  # a force along y
>>> b.verdict, b.in_constraint, b.uncontrolled.shape
('actuation-singular', (True,), (6, 1))
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np

from ..core.analysis import screw_system_in_frame
from ..errors import AnalysisError, counted
from ..core.frozen import ReadOnlyArrays, read_only
from ..core.joint_screws import Normalisation
from ..core.linalg import singular_values, svd
from ..core.result import ScrewAxis
from ..core.screws import SWAP_ROWS, motion_pattern
from ..core.tolerance import DEFAULT_TOLERANCE, RankDecision, Tolerance, decide_rank
from .results import REDUNDANT, SINGULAR, VALID, ActuationCheck, ActuationInput

__all__ = ["EndEffectorSpaces", "InputWrench", "Assessment", "assess_wrenches", "assess_inputs"]


@dataclass(frozen=True, eq=False)
class EndEffectorSpaces(ReadOnlyArrays):
    """The end effector's twist and constraint systems, normalised, with the coordinates to report them in.

    Its arrays (the normalisation's centre too) are read-only, also after a pickle round trip.

    Attributes
    ----------
    twists : ndarray, shape (6, d)
        Orthonormal basis of its twist (freedom) system, normalised coordinates.
    constraints : ndarray, shape (6, 6 - d)
        Orthonormal basis of its constraint wrench system.
    normalisation : Normalisation
        From normalised coordinates to the global frame and the document's unit.
    reference : ndarray, shape (3,)
        Reference point (normalised): reported axes pass through their point nearest to it.
    """

    twists: np.ndarray
    constraints: np.ndarray
    normalisation: Normalisation
    reference: np.ndarray

    def __post_init__(self) -> None:
        super().__post_init__()
        norm = self.normalisation
        if isinstance(norm, Normalisation):
            centre = read_only(norm.centre)
            if centre is not norm.centre:  # one the caller can still write into: these coordinates get their own
                object.__setattr__(self, "normalisation", Normalisation(centre, norm.length))

    def __setstate__(self, state: dict[str, Any]) -> None:
        super().__setstate__(state)
        norm = state.get("normalisation")
        if isinstance(norm, Normalisation):  # unpickled (or deep-copied) with the rest: a new array, frozen in place
            read_only(norm.centre, copy=False)

    @property
    def dof(self) -> int:
        """Dimension of the twist system."""
        return int(self.twists.shape[1])


@dataclass(frozen=True, eq=False)
class InputWrench(ReadOnlyArrays):
    """One input and its actuation wrench, before assessment (``wrench`` read-only, a copy of a writable one given).

    Attributes
    ----------
    name : str
    kind : str
        Joint type letter, or ``"F"`` for a linear actuator.
    limb : int or None
    wrench : ndarray, shape (6,) or None
        Unit actuation wrench, normalised coordinates; ``None`` when there is none.
    rate : float
        ``a o $`` of the input's twist at unit rate (1 for a force line whose wrench has unit force).
    note : str
        Why there is no wrench, if there is none.
    transmission : float
        ``|a o $| / (|a| |$|)``, in ``[0, 1]`` (default: a force line's, its rate).
    """

    name: str
    kind: str
    limb: int | None
    wrench: np.ndarray | None
    rate: float = 1.0
    note: str = ""
    transmission: float | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.transmission is None:  # a force line's: its rate, that of a unit wrench against a unit translation along it
            object.__setattr__(self, "transmission", min(abs(float(self.rate)), 1.0))


@dataclass(frozen=True, eq=False)
class Assessment(ReadOnlyArrays):
    """The verdict on a set of actuation wrenches (normalised coordinates; ``uncontrolled`` read-only).

    Attributes
    ----------
    verdict : str
    decision : RankDecision
        Of the actuation and constraint wrenches together.
    uncontrolled : ndarray, shape (6, 6 - rank)
        Basis of the twists still free with every input locked (columns).
    conditioning : float
        ``kappa``; 0 when actuation-singular.
    in_constraint : tuple of bool
        Per input: it has no wrench, or its wrench lies in the constraint space.
    actuation_margin : float
        The distance to an actuation singularity (docs/actuation.md).
    """

    verdict: str
    decision: RankDecision
    uncontrolled: np.ndarray
    conditioning: float
    in_constraint: tuple[bool, ...]
    actuation_margin: float = 1.0


def assess_wrenches(wrenches: Sequence[np.ndarray | None], rates: Sequence[float], twists: np.ndarray, constraints: np.ndarray,
                    tol: Tolerance = DEFAULT_TOLERANCE, held: np.ndarray | None = None, transmissions: Sequence[float] | None = None) -> Assessment:
    """Verdict, conditioning and actuation margin of a choice of inputs from its actuation wrenches.

    Parameters
    ----------
    wrenches : sequence of (6,) arrays or None
        Unit actuation wrenches (normalised); ``None`` for an input that has none.
    rates : sequence of float
        ``a o $`` of each input (ignored where the wrench is ``None``).
    twists, constraints : ndarray, shape (6, d) and (6, 6 - d)
        Orthonormal bases of the end effector's twist and constraint wrench systems.
    held : ndarray, shape (6, k), optional
        Wrenches that locking the inputs adds beyond their own (a limb's, where
        an input has none: :meth:`~mobility.actuation.rigid_pose.RigidPose.locked_wrenches`).
    transmissions : sequence of float, optional
        ``|a o $| / (|a| |$|)`` of each input; default: each rate, at most 1 (force lines).
    """
    dof = twists.shape[1]
    present = [(w, r) for w, r in zip(wrenches, rates) if w is not None]
    stack = np.concatenate([constraints] + [w[:, None] for w, _ in present] + ([] if held is None else [held]), axis=1)
    if stack.shape[1]:
        u, s, _ = svd(stack)
        decision = decide_rank(s, tol)
        uncontrolled = u[SWAP_ROWS, decision.rank :]
    else:
        decision = RankDecision(0)
        uncontrolled = np.eye(6)
    read_only(uncontrolled, copy=False)  # computed here for the assessment alone: frozen in place, not copied
    in_constraint = tuple(w is None or _lies_in(w, constraints, tol) for w in wrenches)
    n = len(wrenches)
    verdict = SINGULAR if decision.rank < 6 else REDUNDANT if n > dof else VALID
    conditioning = 0.0 if verdict == SINGULAR else 1.0 if dof == 0 else _conditioning(present, twists)
    rho = [min(abs(float(r)), 1.0) for r in rates] if transmissions is None else [float(t) for t in transmissions]
    margin = _actuation_margin(verdict, decision, [(w, t) for w, t in zip(wrenches, rho) if w is not None], len(wrenches), twists)
    return Assessment(verdict, decision, uncontrolled, conditioning, in_constraint, margin)


def _actuation_margin(verdict: str, decision: RankDecision, present: Sequence[tuple[np.ndarray, float]], n: int, twists: np.ndarray) -> float:
    """The ``d``-th singular value of ``H[i, k] = rho_i (a_i o t_k)`` (docs/actuation.md, "Actuation margin"), with its conventions.

    Examples
    --------
    One input on one freedom: the product of the input's transmission and of
    how much of its wrench the freedom sees.

    >>> t = np.eye(6)[:, [3]]  # a translation along x
    >>> _actuation_margin(VALID, RankDecision(6, 1.0), [(np.eye(6)[0], 0.5)], 1, t)
    0.5
    >>> _actuation_margin(VALID, RankDecision(6, 1.0), [(np.eye(6)[0], 0.0)], 1, t)  # the input drives nothing
    0.0
    >>> _actuation_margin(VALID, RankDecision(6, 0.25), [(np.eye(6)[0], 1.0)], 1, t)  # the verdict's rank margin, when smaller
    0.25
    """
    dof = twists.shape[1]
    if verdict == SINGULAR or (dof == 0 and n > 0):
        return 0.0
    if dof == 0 or len(present) < n:  # nothing to drive, or an input held only with the others of its limb
        return float(decision.smallest_kept)
    h = np.array([t * (w[SWAP_ROWS] @ twists) for w, t in present]).reshape(-1, dof)
    sv = singular_values(h)
    return min(float(sv[dof - 1]), float(decision.smallest_kept)) if sv.size >= dof else 0.0


def _lies_in(wrench: np.ndarray, constraints: np.ndarray, tol: Tolerance) -> bool:
    """Whether a unit wrench lies in the span of an orthonormal basis (its part outside is negligible)."""
    rest = wrench - constraints @ (constraints.T @ wrench)
    return decide_rank(np.array([1.0, float(np.linalg.norm(rest))]), tol).rank < 2


def _conditioning(present: Sequence[tuple[np.ndarray, float]], twists: np.ndarray) -> float:
    """``s_min / s_max`` of ``G[i, k] = (a_i o t_k) / (a_i o $_i)``."""
    dof = twists.shape[1]
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        g = np.array([(w[SWAP_ROWS] @ twists) / r for w, r in present]).reshape(-1, dof)
    if not np.all(np.isfinite(g)):
        # an input whose rate vanishes against its effect (a force line ~1e154 characteristic lengths away or
        # farther): its row outgrows every other beyond any float, so s_min / s_max is 0 in the limit
        return 0.0
    sv = singular_values(g)
    return float(sv[dof - 1] / sv[0]) if sv.size >= dof and sv[0] > 0 else 0.0


def assess_inputs(name: str, kind: str, inputs: Sequence[InputWrench], spaces: EndEffectorSpaces, tol: Tolerance = DEFAULT_TOLERANCE, *,
                  warnings: Sequence[str] = (), length_unit: str = "", idle_inputs: Sequence[str] | None = None,
                  held: np.ndarray | None = None) -> ActuationCheck:
    """The full verdict on named inputs, written in the global frame (rigid and flexure alike).

    Parameters
    ----------
    name : str
        The mechanism's name.
    kind : str
        ``"rigid"`` or ``"flexure"``.
    warnings : sequence of str
        Warnings to report before those of the assessment.
    idle_inputs : sequence of str, optional
        Given when the inputs can be set independently (a rigid mechanism's loop
        closure tells): those that move the mechanism but not the end effector.
        Extra inputs are then said to drive idle motions, not to fight.
    held : ndarray, shape (6, k), optional
        As for :func:`assess_wrenches`.

    Examples
    --------
    >>> import numpy as np
    >>> from mobility.core.joint_screws import Normalisation
    >>> slider = EndEffectorSpaces(np.eye(6)[:, [3]], np.eye(6)[:, 1:], Normalisation(np.zeros(3), 1.0), np.zeros(3))
    >>> check = assess_inputs("slider", "rigid", [InputWrench("P", "P", 0, np.eye(6)[0])], slider)
    >>> check.verdict, check.pattern, check.inputs[0].axis.kind
    ('valid', '1T', 'force')
    """
    a = assess_wrenches([i.wrench for i in inputs], [i.rate for i in inputs], spaces.twists, spaces.constraints, tol, held,
                        [float(i.transmission or 0.0) for i in inputs])
    norm, reference = spaces.normalisation, spaces.reference
    out_inputs = []
    useless = []
    for i, flag in zip(inputs, a.in_constraint):
        if i.wrench is None:
            out_inputs.append(ActuationInput(i.name, i.kind, i.limb, None, None, True, i.note))
            useless.append(i.name)
            continue
        with np.errstate(over="ignore", invalid="ignore"):  # checked here: a number past the largest float is refused, never shown
            world, axis = _wrench_in_world(i.wrench, norm, reference, tol)
        if not (np.all(np.isfinite(world)) and np.all(np.isfinite(axis.point)) and np.isfinite(axis.pitch)):
            raise AnalysisError(f"the actuation wrench of {i.name!r} lies beyond the largest float in the mechanism's unit "
                                f"(characteristic length {norm.length:.3g}): write the mechanism in a larger length unit")
        note = i.note
        if flag:
            useless.append(i.name)
            note = note or "its actuation wrench lies in the constraint space: it cannot move the end effector"
        out_inputs.append(ActuationInput(i.name, i.kind, i.limb, world, axis, flag, note))
    dof = spaces.dof
    couples, forces, constraint_rows = screw_system_in_frame(spaces.constraints, norm, reference, ("force", "wrench"), tol)
    translations, rotations, twist_rows = screw_system_in_frame(a.uncontrolled, norm, reference, ("rotation", "helical"), tol)
    warns = list(warnings)
    if a.verdict != SINGULAR and a.decision.smallest_kept < tol.near_singular:
        warns.append(f"near an actuation singularity: relative singular value {a.decision.smallest_kept:.2e} of the actuation and constraint wrenches")
    elif a.verdict != SINGULAR and a.actuation_margin < tol.near_singular:
        warns.append(f"near an actuation singularity: actuation margin {a.actuation_margin:.2e} (the inputs barely drive the end effector, if at all)")
    return ActuationCheck(name=name, kind=kind, dof=dof, pattern=motion_pattern(spaces.twists, tol), inputs=tuple(out_inputs),
                          constraint_couples=couples, constraint_forces=forces, constraint_wrenches=constraint_rows, verdict=a.verdict,
                          rank=a.decision.rank, uncontrolled_translations=translations, uncontrolled_rotations=rotations,
                          uncontrolled_twists=twist_rows, margin=a.decision, conditioning=a.conditioning,
                          explanation=_explanation(a.verdict, len(inputs), dof, a.decision.rank, useless, idle_inputs),
                          warnings=tuple(warns), length_unit=length_unit, length_scale=norm.size, actuation_margin=a.actuation_margin)


def _wrench_in_world(wrench_n: np.ndarray, norm: Normalisation, reference: np.ndarray, tol: Tolerance) -> tuple[np.ndarray, ScrewAxis]:
    """A normalised wrench as a global wrench (``|f| = 1``, or ``|m| = 1`` for a couple) and its line."""
    f, m = wrench_n[:3], wrench_n[3:]
    nf = float(np.linalg.norm(f))
    if nf <= tol.rank * float(np.linalg.norm(wrench_n)):
        c = m / np.linalg.norm(m)
        return np.concatenate([np.zeros(3), c]), ScrewAxis(c, norm.point_to_world(reference), 0.0, "couple")
    f, m = f / nf, m / nf
    pitch = float(f @ m)
    moment = m - np.cross(reference, f)  # moment about the reference point
    point = reference + np.cross(f, moment)
    pitch = 0.0 if abs(pitch) <= tol.rank else pitch
    axis = ScrewAxis(f, norm.point_to_world(point), pitch * norm.length, "force" if pitch == 0.0 else "wrench")
    world = norm.to_world(np.concatenate([f, m]))[:, 0]
    return world, axis


def _explanation(verdict: str, n: int, dof: int, rank: int, useless: Sequence[str], idle_inputs: Sequence[str] | None = None) -> str:
    """One sentence on a verdict.

    Examples
    --------
    >>> _explanation(REDUNDANT, 4, 3, 6, ())
    '4 inputs for 3 DOF: 1 more than needed (they must be coordinated or they fight each other)'
    >>> _explanation(REDUNDANT, 1, 0, 6, (), ["A"])
    '1 input for 0 DOF, yet the inputs do not fight: each moves the mechanism on its own, and A moves it without moving the end effector (a self-motion of the mechanism, or a serial singularity where the end effector has lost a freedom at this pose)'
    """
    if verdict == VALID:
        return (f"the {counted(n, 'actuation wrench', 'es')} and the {counted(6 - dof, 'constraint wrench', 'es')} span all six dimensions: "
                "with the inputs locked the end effector cannot move")
    inputs = f"{counted(n, 'input')} for {dof} DOF"
    if verdict == REDUNDANT and idle_inputs:
        movers = ", ".join(idle_inputs)
        return (f"{inputs}, yet the inputs do not fight: each moves the mechanism on its own, and {movers} "
                f"move{'s' if len(idle_inputs) == 1 else ''} it without moving the end effector "
                "(a self-motion of the mechanism, or a serial singularity where the end effector has lost a freedom at this pose)")
    if verdict == REDUNDANT:
        return f"{inputs}: {n - dof} more than needed (they must be coordinated or they fight each other)"
    text = f"actuation and constraint wrenches span only {rank} of 6 dimensions: with the inputs locked the end effector can still move along {counted(6 - rank, 'direction')}"
    if n < dof:
        text += f" (fewer inputs, {n}, than DOF, {dof})"
    if useless:
        text += f"; useless input{'' if len(useless) == 1 else 's'}: " + ", ".join(useless)
    return text

