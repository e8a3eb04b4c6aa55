"""Coupled joints: linear relations between the rates of one-freedom joints.

A :class:`Coupling` says ``sum_j c_j q'_j = 0`` for the rates of two or more
R, P or H joints in their natural units: a gear pair (``c = (1, r)``), a URDF
``<mimic>`` (``c = (1, -m)``), an MJCF joint equality or fixed tendon.  Its
joints are all slides (P) or all turns (R, H): comparing a slide's rate with a
turn's would need a length, which normalised coordinates change from pose to
pose.  On unit joint twists (:mod:`mobility.core.joint_screws`) a joint's
coordinate is its rate times its twist's norm ``|T_j|``, which is
``1 / |u_j[:3]|`` for a turn and the same ``1 / L`` for every slide, so
:func:`coupling_rows` builds the rows from the unit columns alone.

Examples
--------
>>> gear = Coupling(("A", "B"), (1.0, 2.0))
>>> gear.terms
(('A', 1.0), ('B', 2.0))
>>> Coupling(("A", "A"), (1.0, 2.0))
Traceback (most recent call last):
...
mobility.errors.MechanismError: joints[1]: joint 'A' is already in this coupling; write each joint once, with the sum of its coefficients
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Iterable, Sequence

import numpy as np

from ..errors import MechanismError, RequestError, did_you_mean, name_list, shown_argument

__all__ = ["Coupling", "COUPLED_TYPES", "require_couplings", "coupling_rows", "require_no_couplings"]

COUPLED_TYPES = ("R", "P", "H")
"""The joint types a coupling may hold: one freedom, one rate."""


@dataclass(frozen=True)
class Coupling:
    """``sum_j coefficients[j] * rate(joints[j]) = 0``, rates in each joint's natural unit.

    ``joints`` names two or more distinct R, P or H joints (all slides or all
    turns), ``coefficients`` one finite non-zero number each; a problem raises
    :class:`~mobility.errors.MechanismError` keyed ``joints[1]``, ``coefficients[0]``...
    """

    joints: tuple[str, ...]
    coefficients: tuple[float, ...]

    def __post_init__(self) -> None:
        for key in ("joints", "coefficients"):
            value = getattr(self, key)
            if isinstance(value, (str, bytes, dict)) or not isinstance(value, Iterable):
                raise MechanismError(key, f"expected a list, got {type(value).__name__}")
            object.__setattr__(self, key, tuple(value))
        if len(self.joints) < 2:
            raise MechanismError("joints", f"expected two or more joint names, got {len(self.joints)}")
        if len(self.coefficients) != len(self.joints):
            raise MechanismError("coefficients", f"expected one number per joint ({len(self.joints)}), got {len(self.coefficients)}")
        seen: set[str] = set()
        for i, name in enumerate(self.joints):
            if not isinstance(name, str):
                raise MechanismError(f"joints[{i}]", f"expected a joint name, got {type(name).__name__}")
            if name in seen:
                raise MechanismError(f"joints[{i}]", f"joint {name!r} is already in this coupling; write each joint once, with the sum of its coefficients")
            seen.add(name)
        numbers = []
        for i, c in enumerate(self.coefficients):
            if isinstance(c, bool) or not isinstance(c, (int, float, np.integer, np.floating)) or not math.isfinite(float(c)):
                raise MechanismError(f"coefficients[{i}]", f"expected a finite number, got {shown_argument(c) if isinstance(c, str) else repr(c)}")
            if float(c) == 0.0:
                raise MechanismError(f"coefficients[{i}]", f"expected a non-zero number: joint {self.joints[i]!r} with coefficient 0 takes no part in the coupling; leave it out")
            numbers.append(float(c))
        object.__setattr__(self, "coefficients", tuple(numbers))

    @property
    def terms(self) -> tuple[tuple[str, float], ...]:
        """``(joint, coefficient)`` pairs."""
        return tuple(zip(self.joints, self.coefficients))


def require_couplings(couplings: Any, joints: Sequence[Any]) -> tuple[Coupling, ...]:
    """The couplings of a mechanism, checked against its joints (``name`` and ``type`` of each).

    Examples
    --------
    >>> from types import SimpleNamespace as J
    >>> require_couplings([Coupling(("a", "c"), (1, -1))], [J(name="a", type="R"), J(name="b", type="R")])
    Traceback (most recent call last):
    ...
    mobility.errors.MechanismError: couplings[0].joints[1]: unknown joint 'c'; expected one of: a, b
    """
    if isinstance(couplings, (str, bytes, dict)) or not isinstance(couplings, Iterable):
        raise MechanismError("couplings", f"expected a sequence of Couplings, got {type(couplings).__name__}")
    out = tuple(couplings)
    kinds = {j.name: j.type for j in joints}
    for k, coupling in enumerate(out):
        if not isinstance(coupling, Coupling):
            raise MechanismError(f"couplings[{k}]", f"expected a Coupling, got {type(coupling).__name__}")
        for i, name in enumerate(coupling.joints):
            if name not in kinds:
                raise MechanismError(f"couplings[{k}].joints[{i}]", f"unknown joint {name!r}{did_you_mean(name, list(kinds)) or '; expected one of: ' + name_list(list(kinds))}")
            if kinds[name] not in COUPLED_TYPES:
                raise MechanismError(f"couplings[{k}].joints[{i}]", f"joint {name!r} is of type {kinds[name]}: a coupling relates the rates of one-freedom joints (R, P, H)")
        slides = [kinds[name] == "P" for name in coupling.joints]
        if any(slides) and not all(slides):
            i = slides.index(not slides[0])
            raise MechanismError(
                f"couplings[{k}].joints[{i}]",
                f"joint {coupling.joints[i]!r} is {'a slide (P)' if slides[i] else 'a turn (R, H)'} and joint {coupling.joints[0]!r} is not: "
                "a coupling holds slides only or turns only (a rack and pinion is not supported yet)",
            )
    return out


def coupling_rows(twists: np.ndarray, columns: Sequence[int], coefficients: Sequence[float], slides: bool) -> np.ndarray:
    """One coupling as a row on unit joint twists, at a stack of poses.

    ``twists`` (N, 6, f) are unit joint twists (a locked freedom a zero
    column), ``columns`` each joint's column.  Row ``c_j / |T_j|`` on the unit
    coordinates, scaled to unit length (zeros where every joint is locked).

    Examples
    --------
    >>> u = np.array([[0, 0, 1, 0, -1, 0], [0, 0, 1, 0, 0, 0]], dtype=float).T[None] / [[2 ** 0.5, 1.0]]
    >>> coupling_rows(u, [0, 1], [1.0, 1.0], False).round(6).tolist()   # a turn 1 away from the centre: |T| = sqrt(2)
    [[0.57735, 0.816497]]
    """
    picked = twists[:, 3:, :] if slides else twists[:, :3, :]
    picked = picked[:, :, list(columns)]
    row = np.sqrt(np.einsum("nij,nij->nj", picked, picked)) * np.asarray(coefficients, dtype=float)
    norm = np.sqrt(np.einsum("nj,nj->n", row, row))[:, None]
    return np.divide(row, norm, out=np.zeros_like(row), where=norm > 0)


def require_no_couplings(couplings: Sequence[Coupling], name: str, caller: str, what: str) -> None:
    """Refuse a coupled mechanism where poses are reached by closing loops only (sweeps, sampled poses, full cycles).

    The position solver (:func:`mobility.core.kinematics.newton`) holds no
    coupling yet: its poses could turn coupled joints apart.

    Examples
    --------
    >>> require_no_couplings([Coupling(("A", "B"), (1.0, 2.0))], "gears", "sweep", "the poses of a sweep")
    Traceback (most recent call last):
    ...
    mobility.errors.RequestError: sweep: 'gears' couples joints (A/B), which the poses of a sweep do not follow yet (loops are closed, couplings not); the instantaneous answer is mobility.analyze
    """
    if couplings:
        listed = ", ".join("/".join(c.joints) for c in couplings[:3])
        raise RequestError(f"{name!r} couples joints ({listed}), which {what} do not follow yet (loops are closed, couplings not); "
                           "the instantaneous answer is mobility.analyze", caller=caller)
