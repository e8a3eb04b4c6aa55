"""What a sweep varies: the grid of drive values, checked against the mechanism.

Each coordinate takes ``COUNT`` evenly spaced values from ``START`` to ``STOP``
(both included); the grid is their product, first coordinate slowest.  A
coordinate is a joint (degrees, or the file's length unit for a slide) or an
end-effector pose coordinate ``x`` ... ``rz``, both displaced from the file's
pose (docs/sweeps.md, "The request").  Inside, as in
:mod:`mobility.core.kinematics`: radians, lengths over the characteristic length.

Examples
--------
>>> parse_vary("O1=0:360:361")
('O1', 0.0, 360.0, 361)
>>> import mobility
>>> m = mobility.load("mechanisms/parallelogram.yaml")
>>> plan = plan_grid(m, ["O1=0:360:361"])
>>> plan.shape, plan.axes[0].unit, float(plan.axes[0].values[120])
((361,), 'deg', 120.0)
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Iterable, Mapping, Union, cast

import numpy as np

from ..core.couplings import require_no_couplings
from ..core.joint_screws import joint_screws
from ..core.kinematics import kinematics
from ..core.model import Mechanism
from ..core.validation import integer_from_text, number_from_text
from ..core.tolerance import SAME_GRID_VALUE, SWEEP_REACH
from ..errors import RequestError, clipped, counted, name_list

__all__ = ["POSE_COORDINATES", "DRIVABLE_JOINTS", "WRAPPING_JOINTS", "FULL_TURN", "DEFAULT_MAX_POSES", "SweepAxis", "GridPlan", "VarySpec",
           "parse_vary", "whole_turns", "plan_grid"]

POSE_COORDINATES = ("x", "y", "z", "rx", "ry", "rz")
"""End-effector pose coordinates, in the order of their components ``[p; r]``."""

DRIVABLE_JOINTS = ("R", "P", "H", "C")
"""Joint types a sweep can drive (by one angle or one length)."""

WRAPPING_JOINTS = ("R", "C")
"""Joint types whose driven angle displaced by a whole turn is the same joint state (an H joint's slide goes with its angle)."""

FULL_TURN = 360.0
"""A whole turn, in the unit of a swept angle (degrees)."""

DEFAULT_MAX_POSES = 1_000_000
"""Largest grid :func:`plan_grid` accepts unless told otherwise: a sweep of that many poses takes
about half a GB and under a minute on two cores (docs/sweeps.md, Memory); a larger one is asked for."""

VarySpec = Union[str, tuple, Mapping[str, tuple]]
"""``"NAME=START:STOP:COUNT"``, a tuple ``(name, start, stop, count)``, or a
mapping ``{name: (start, stop, count)}``."""

_SPEC = re.compile(r"^\s*(?P<name>.+?)\s*=\s*(?P<range>[^=]*)$")  # the last '=': a joint's name may hold one


@dataclass(frozen=True)
class SweepAxis:
    """One varied coordinate of a sweep.

    Attributes
    ----------
    name : str
        The joint's name, or a pose coordinate (``x``, ..., ``rz``).
    kind : str
        ``"joint"`` or ``"pose"``.
    unit : str
        ``"deg"`` for angles, else the file's length unit (possibly empty).
    start, stop : float
        First and last value, as displacements from the file's pose.
    count : int
        Number of values, both ends included.
    variable : int
        A joint's driven variable in :class:`~mobility.core.kinematics.Kinematics`
        (a ``C`` joint's rotation); a pose coordinate's component (0..5).
    scale : float
        Internal value per unit value (radians per degree, or one over the characteristic length).
    period : float
        The displacement giving the same joint state: 360 for an ``R`` or ``C``
        angle; 0 for none (an ``H`` angle, whose slide goes with it, a slide, a pose coordinate).
    """

    name: str
    kind: str
    unit: str
    start: float
    stop: float
    count: int
    variable: int
    scale: float
    period: float = 0.0

    @property
    def values(self) -> np.ndarray:
        """The ``count`` values in the user's unit."""
        return np.linspace(self.start, self.stop, self.count) if self.count > 1 else np.array([self.start])

    @property
    def extent(self) -> float:
        """The size the values are shown against (round-off is relative to it): the larger end of the range, 1 for zeros."""
        return max(abs(self.start), abs(self.stop)) or 1.0

    @property
    def step(self) -> float:
        """The distance between neighbouring values (user units; the span of a single value, 0)."""
        return abs(self.stop - self.start) / max(self.count - 1, 1)

    @property
    def anchor(self) -> int:
        """Index of the value nearest the file's pose (displacement 0, round the circle for an angle that wraps); the first of two as near."""
        values = self.values
        distance = np.abs(within_half_turn(values, self.period) if self.period else values)
        return int(np.flatnonzero(distance <= distance.min() + SAME_GRID_VALUE * self.step)[0])  # round-off must not pick between ties

    @property
    def covers_turn(self) -> bool:
        """The values wrap and go round a whole turn (no gap between them round the circle longer than a step)."""
        step = self.step
        return bool(self.period) and self.count >= 2 and abs(self.stop - self.start) + step >= self.period - SAME_GRID_VALUE * step

    @property
    def internal(self) -> np.ndarray:
        """The values as the solver uses them (radians, lengths over the characteristic length).

        An angle that wraps loses whole turns (exactly, in degrees) to come near
        the file's pose: ``3600000`` degrees is solved as 0. A range shorter than
        a turn moves as a whole, keeping its order; the values of a range that
        covers a turn each go within half a turn of the anchor (:mod:`mobility.sweeps.walks`).
        """
        values = self.values
        if self.period:  # by remainders, exact at any size (a value of 5e19 degrees is 140 degrees, not the file's pose)
            anchor = values[self.anchor]
            near = float(within_half_turn(anchor, self.period))  # the anchor's value, near the file's pose
            if self.covers_turn:
                values = near + within_half_turn(np.remainder(values, self.period) - near, self.period)
            else:
                values = near + within_half_turn(values - anchor, self.period) if abs(anchor) > TURNS_EXACT * self.period else values - (anchor - near)
        return values * self.scale

    @property
    def label(self) -> str:
        """``"O1 [deg]"``: the name and the unit, for tables and plots."""
        return f"{self.name} [{self.unit}]" if self.unit else self.name

    def to_dict(self) -> dict:
        """JSON form."""
        return {"name": self.name, "kind": self.kind, "unit": self.unit, "start": self.start, "stop": self.stop, "count": self.count}


@dataclass(frozen=True)
class GridPlan:
    """The checked request: the axes, in order (the first varies slowest).

    Attributes
    ----------
    axes : tuple of SweepAxis
    length : float
        The characteristic length of the file's pose (the unit of internal lengths).
    """

    axes: tuple[SweepAxis, ...]
    length: float

    @property
    def shape(self) -> tuple[int, ...]:
        """Points per axis."""
        return tuple(a.count for a in self.axes)

    @property
    def size(self) -> int:
        """Number of poses of the grid."""
        return math.prod(self.shape)


TURNS_EXACT = 2.0**40
"""Turns of an angle beyond which its values are reduced one by one (below, a range is moved as a whole, which keeps its order exactly)."""


def within_half_turn(values: np.ndarray | float, period: float) -> np.ndarray:
    """``values`` less whole turns, within half a turn of 0 (by remainders: exact at any size, unlike ``values / period``).

    Examples
    --------
    >>> within_half_turn(np.array([350.0, -190.0, 5e19, 180.0]), 360.0).tolist()
    [-10.0, 170.0, -40.0, 180.0]
    """
    r = np.remainder(values, period)
    return np.where(r > 0.5 * period, r - period, r)


def whole_turns(difference: np.ndarray, period: float) -> np.ndarray:
    """The whole turns in ``difference``: the multiple of ``period`` nearest it (0 when ``period`` is 0).

    Examples
    --------
    >>> whole_turns(np.array([350.0, -190.0, 10.0]), 360.0).tolist(), whole_turns(np.array([700.0]), 0.0).tolist()
    ([360.0, -360.0, 0.0], [0.0])
    """
    difference = np.asarray(difference, dtype=float)
    if not period:
        return np.zeros_like(difference)
    return period * np.round(difference / period)


def parse_vary(spec: str) -> tuple[str, float, float, int]:
    """Read ``"NAME=START:STOP:COUNT"``.

    Raises
    ------
    RequestError
        When the text does not have that form, a bound is not a finite number
        or ``COUNT`` is not an integer of at least 1.

    Examples
    --------
    >>> parse_vary(" P1 = -20 : 20 : 5 ")
    ('P1', -20.0, 20.0, 5)
    >>> parse_vary("P1=0:1:0")
    Traceback (most recent call last):
    ...
    mobility.errors.RequestError: --vary 'P1=0:1:0': COUNT must be at least 1, got 0
    """
    where = f"--vary {spec!r}"
    match = _SPEC.match(spec) if isinstance(spec, str) else None
    if match is None:
        raise RequestError(argument=where, expected="NAME=START:STOP:COUNT (e.g. O1=0:360:361)")
    parts = match["range"].split(":")
    if len(parts) != 3:
        raise RequestError(argument=where, expected="NAME=START:STOP:COUNT", got=f"{counted(len(parts), 'part')} after '='")
    return (match["name"],) + _bounds(where, parts[0], parts[1], parts[2])


def _bounds(where: str, start: object, stop: object, count: object) -> tuple[float, float, int]:
    values = []
    for label, text in (("START", start), ("STOP", stop)):
        try:
            x = number_from_text(str(text).strip()) if not isinstance(text, (int, float)) or isinstance(text, bool) else float(text)
        except ValueError:
            raise RequestError(f"{label} must be a number, got {clipped(str(text).strip())!r}", argument=where) from None
        except OverflowError:  # an integer beyond the floats
            raise RequestError(f"{label} must be a finite number, got an integer of {len(str(abs(cast(int, text))))} digits", argument=where) from None
        if isinstance(text, bool) or not math.isfinite(x):
            raise RequestError(f"{label} must be a finite number, got {text!r}", argument=where)
        values.append(x)
    try:
        n = integer_from_text(str(count).strip()) if not isinstance(count, int) or isinstance(count, bool) else count
    except ValueError:
        raise RequestError(f"COUNT must be an integer, got {str(count).strip()!r}", argument=where) from None
    if isinstance(count, bool) or (isinstance(count, float) and count != int(count)):
        raise RequestError(f"COUNT must be an integer, got {count!r}", argument=where)
    if n < 1:
        raise RequestError(f"COUNT must be at least 1, got {n}", argument=where)
    return values[0], values[1], n


def _requests(vary: VarySpec | Iterable) -> list[tuple[str, float, float, int]]:
    """Every accepted way of writing the request, as ``(name, start, stop, count)``."""
    if isinstance(vary, str):
        return [parse_vary(vary)]
    if isinstance(vary, Mapping):
        items: Iterable = [(name, *rng) if isinstance(rng, (tuple, list)) else (name, rng) for name, rng in vary.items()]
    elif isinstance(vary, (list, tuple)):
        items = vary
    else:
        raise RequestError(argument="vary", expected="NAME=START:STOP:COUNT, a list of them or of (name, start, stop, count), or a mapping", got=type(vary).__name__)
    out = []
    for item in items:
        if isinstance(item, str):
            out.append(parse_vary(item))
            continue
        if not isinstance(item, (tuple, list)) or len(item) != 4 or not isinstance(item[0], str):
            raise RequestError(argument="vary", expected="NAME=START:STOP:COUNT or (name, start, stop, count)", got=repr(item))
        out.append((item[0],) + _bounds(f"vary {item[0]!r}", *item[1:]))
    return out


def _require_finite(axis: SweepAxis, length: float) -> None:
    """Refuse a range whose values, or their internal values (radians, lengths over ``length``), leave the floats."""
    with np.errstate(over="ignore", invalid="ignore"):
        values = axis.values
        internal = values * axis.scale
    if not (np.all(np.isfinite(values)) and np.all(np.isfinite(internal))):
        where = f"--vary {axis.name}={axis.start:g}:{axis.stop:g}:{axis.count}"
        size = f" (the mechanism's size is {length:.3g}{' ' + axis.unit if axis.unit and axis.unit != 'deg' else ''})" if axis.unit != "deg" else ""
        raise RequestError(f"its values do not fit in a float (in radians, or over the mechanism's size){size}; choose a smaller range", argument=where)


def _require_within_reach(axis: SweepAxis, length: float) -> None:
    """Refuse a slide, translation or non-wrapping angle that goes farther than :data:`SWEEP_REACH` from the file's pose."""
    if axis.period or (axis.kind == "pose" and axis.unit == "deg"):
        return  # angles that wrap are taken near the file's pose; rotation coordinates: _require_one_rotation
    farthest = max(abs(axis.start), abs(axis.stop))
    if farthest * axis.scale <= SWEEP_REACH:
        return
    where = f"--vary {axis.name}={axis.start:g}:{axis.stop:g}:{axis.count}"
    if axis.unit == "deg":
        limit = f"{math.degrees(SWEEP_REACH):,.0f} deg ({SWEEP_REACH / (2.0 * math.pi):.0f} turns) of an H joint, whose slide goes with its angle"
    else:
        unit = f" {axis.unit}" if axis.unit else ""
        limit = f"{SWEEP_REACH:,.0f} times the mechanism's size ({SWEEP_REACH * length:.4g}{unit}; its size is {length:.4g}{unit})"
    raise RequestError(f"{farthest:g} is beyond what a sweep reaches from the file's pose, {limit}: there double precision cannot close the loops; choose a smaller range", argument=where)


def _require_one_rotation(axes: list[SweepAxis]) -> None:
    """Refuse rotation coordinates (rx, ry, rz) whose rotation vector, at some grid point, turns more than half a turn."""
    rotations = [a for a in axes if a.kind == "pose" and a.unit == "deg"]
    if not rotations:
        return
    farthest = math.hypot(*(max(abs(a.start), abs(a.stop)) for a in rotations))  # at a corner of the grid; hypot cannot overflow
    if farthest <= 180.0 * (1.0 + SAME_GRID_VALUE):
        return
    names = ", ".join(f"{a.name}={a.start:g}:{a.stop:g}:{a.count}" for a in rotations)
    raise RequestError(f"--vary {names}: the end effector's rotation vector reaches {farthest:g} deg, more than half a turn, "
                       "where it no longer names one rotation; sweep rotations of at most 180 deg (or drive a joint, whose angle wraps)")


def plan_grid(mechanism: Mechanism, vary: VarySpec | Iterable, *, max_poses: int = DEFAULT_MAX_POSES) -> GridPlan:
    """Check a sweep request (``vary`` and ``max_poses`` as for :func:`mobility.sweeps.sweep`) against ``mechanism`` and give its axes.

    Raises
    ------
    RequestError
        An unknown name, a joint not driven by one number (S, U, E), a
        coordinate given twice, a range that leaves the floats or reaches beyond
        :data:`~mobility.core.tolerance.SWEEP_REACH`, rotations past half a
        turn, no coordinate, or a grid above ``max_poses``.
    """
    require_no_couplings(mechanism.couplings, mechanism.name, "sweep", "the poses of a sweep")
    requests = _requests(vary)
    if not requests:
        raise RequestError("vary: give at least one coordinate to vary, NAME=START:STOP:COUNT")
    source = f" of {mechanism.source}" if mechanism.source else ""
    names = [j.name for j in mechanism.joints]
    length = joint_screws(mechanism).normalisation.length
    offsets = kinematics(mechanism).offsets
    unit = mechanism.length_unit
    axes: list[SweepAxis] = []
    seen: set[str] = set()
    for name, start, stop, count in requests:
        where = f"--vary {name}={start:g}:{stop:g}:{count}"
        if name in seen:
            raise RequestError(f"{name} is varied twice", argument=where)
        seen.add(name)
        if count > max_poses:  # before any array of that many values is made
            raise RequestError(f"{count:,} values, more than --max-poses {max_poses:,}; raise --max-poses or use fewer points", argument=where)
        if name in names:
            index = names.index(name)
            joint = mechanism.joints[index]
            if joint.type not in DRIVABLE_JOINTS:
                raise RequestError(f"{where}: {name} is {'an' if joint.type in ('S', 'E') else 'a'} {joint.type} joint{source}; only R, H, C joints "
                                   "(by their angle, in degrees) and P joints (by their slide) can be swept")
            angle = joint.type != "P"
            period = FULL_TURN if joint.type in WRAPPING_JOINTS else 0.0
            axes.append(SweepAxis(name, "joint", "deg" if angle else unit, start, stop, count, int(offsets[index]), math.pi / 180.0 if angle else 1.0 / length, period))
        elif name in POSE_COORDINATES:
            component = POSE_COORDINATES.index(name)
            angle = component >= 3
            axes.append(SweepAxis(name, "pose", "deg" if angle else unit, start, stop, count, component, math.pi / 180.0 if angle else 1.0 / length))
        else:
            raise RequestError(f"{where}: {name!r} is not a joint{source}; expected one of: {name_list(names)}, "
                               f"or an end-effector pose coordinate ({', '.join(POSE_COORDINATES)})")
    for axis in axes:
        _require_finite(axis, length)
        _require_within_reach(axis, length)
    _require_one_rotation(axes)
    plan = GridPlan(tuple(axes), length)
    if plan.size > max_poses:
        raise RequestError(f"the grid has {plan.size:,} poses, more than --max-poses {max_poses:,}; raise --max-poses or use fewer points")
    return plan
