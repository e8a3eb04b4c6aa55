"""A file's own precision: from the digits it writes and from how well its loops close.

Files written by CAD exporters hold about six significant digits: their loops close only to about ``1e-7`` of their
size, and a finer rank decision is about the rounding, not the mechanism (``docs/robot-files.md``).  The precision,
relative to the characteristic length (:func:`~mobility.core.tolerance.characteristic_scale`), is the larger of:

* **its digits** (:class:`DigitCounter`): rounded to ``D >=`` :data:`ROUNDED_DIGITS` digits, each number ``x`` is known to
  ``0.5 * 10**(floor(log10|x|) - D + 1)`` (a length over the characteristic length, an angle in radians);
* **its loops**: the largest relative gap of a loop closure at the pose, up to :data:`ASSEMBLED`.

:func:`~mobility.core.tolerance.file_tolerance` turns it into the rank threshold.

Examples
--------
>>> counter = DigitCounter()
>>> counter.add("0.0926361 0.0115732 0.0764594", "length")
>>> counter.add("2.35619 -2.01031e-14 1.5708", "angle")
>>> r = counter.rounding()
>>> r.digits, r.length, r.angle
(6, 5e-08, 5e-06)
>>> hand = DigitCounter()
>>> hand.add("0 0.25 1.5", "length"); hand.add("0 0 1", "unit")
>>> hand.rounding() is None
True
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any, Iterable

import numpy as np

from ..core.tolerance import characteristic_scale

__all__ = ["Rounding", "DigitCounter", "MJCF_PLACING", "MJCF_DIGIT_KINDS", "count_mjcf_digits", "mjcf_rounding", "ROUNDED_DIGITS", "ASSEMBLED", "FilePrecision", "file_precision", "significant_digits"]

ROUNDED_DIGITS = 5
"""A file whose numbers have a median of at least this many significant digits is read as rounded to that many.

Numbers typed by hand have one to four; ``%g`` gives six; a full-precision export 15 to 17."""

ASSEMBLED = 1e-4
"""A loop gap above this fraction of the mechanism's size is a file not assembled at its pose, not rounding: not counted as its precision."""

_NUMBER = re.compile(r"^[+-]?(\d*)\.?(\d*)(?:[eE][+-]?\d+)?$")


def significant_digits(token: str) -> int:
    """How many significant digits a number is written with (0 for zero, or for what is not a decimal number); trailing
    zeros count after a decimal point (``0.500000`` has six), not in an integer (``500`` has one).

    Examples
    --------
    >>> [significant_digits(t) for t in ("0.0444979", "-2.01031e-14", "1.5708", "500", "0.500000", "0", "-0", "1e-9", "abc")]
    [6, 6, 5, 1, 6, 0, 0, 1, 0]
    """
    match = _NUMBER.match(token)
    if match is None:
        return 0
    whole, fraction = match.group(1), match.group(2)
    digits = (whole + fraction).lstrip("0")
    if not fraction:
        digits = digits.rstrip("0")
    return len(digits)


@dataclass(frozen=True)
class Rounding:
    """The digits a file writes its geometry with: ``D``, the median count of significant ``digits``, and the largest
    rounding of a ``length`` (file's unit) and of an ``angle`` (radians) or direction component."""

    digits: int
    length: float
    angle: float


class DigitCounter:
    """Collects the numbers that place a file's joints, as written, and tells the digits they are rounded to.

    ``kind``: ``"length"``, ``"angle"`` (``scale`` converts to radians),
    ``"unit"`` (direction component) or ``"quat"`` (turns by twice its error).
    """

    _WEIGHT = {"length": 1.0, "angle": 1.0, "unit": 1.0, "quat": 2.0}

    def __init__(self) -> None:
        self.digits: list[int] = []
        self.exponents: dict[str, dict[int, float]] = {"length": {}, "angle": {}}  # decimal exponent of each number: the largest weight

    def add(self, text: str | None, kind: str, scale: float = 1.0) -> None:
        """Count the numbers of one attribute (``None``, or text that is not numbers, adds nothing)."""
        if not text:
            return
        weight = self._WEIGHT[kind] * scale
        for token in text.split():
            count = significant_digits(token)
            value = abs(float(token)) if count else 0.0  # a count: the pattern holds a number
            if not math.isfinite(value) or value == 0.0:
                continue
            if count >= 2:
                self.digits.append(count)
            exponents = self.exponents["length" if kind == "length" else "angle"]
            exponent = math.floor(math.log10(value))
            exponents[exponent] = max(exponents.get(exponent, 0.0), weight)

    def rounding(self) -> Rounding | None:
        """The rounding of the numbers added, or ``None`` when they are not rounded to :data:`ROUNDED_DIGITS` or more digits."""
        if not self.digits:
            return None
        digits = int(np.median(self.digits))
        if digits < ROUNDED_DIGITS:
            return None

        def largest(exponents: dict[int, float]) -> float:
            # half a unit of the D-th digit of each number (written exactly as a decimal), times its weight
            return max((weight * float(f"5e{exponent - digits}") for exponent, weight in exponents.items()), default=0.0)

        return Rounding(digits, largest(self.exponents["length"]), largest(self.exponents["angle"]))


MJCF_PLACING = frozenset({"body", "frame", "joint", "site", "connect", "weld"})
"""Elements whose numbers place joints: counted for the file's precision (geoms, inertias and the rest are not)."""

MJCF_DIGIT_KINDS = {"pos": ("length",), "anchor": ("length",), "quat": ("quat",), "axis": ("unit",), "zaxis": ("unit",), "xyaxes": ("unit",),
                "euler": ("angle",), "axisangle": ("unit", "unit", "unit", "angle"), "relpose": ("length",) * 3 + ("quat",) * 4}
"""What each number of a placing attribute is, for :class:`~mobility.io.precision.DigitCounter` (the last kind repeats)."""


def count_mjcf_digits(digits: DigitCounter, element: Any, angle_scale: float) -> None:
    """Add the numbers that place ``element`` to ``digits``, each as the kind of number it is (angles in the file's unit)."""
    for attribute, kinds in MJCF_DIGIT_KINDS.items():
        value = element.get(attribute)
        if not value:
            continue
        for i, token in enumerate(value.split()):
            kind = kinds[min(i, len(kinds) - 1)]
            digits.add(token, kind, angle_scale if kind == "angle" else 1.0)


def mjcf_rounding(roots: Iterable[Any]) -> Rounding | None:
    """The rounding of the numbers that place an MJCF model's bodies, joints, sites and equalities, in its file and the files it includes.

    Angles are in the unit of ``<compiler angle>`` (default: degrees).

    Examples
    --------
    >>> from xml.etree.ElementTree import fromstring
    >>> root = fromstring('<mujoco><compiler angle="radian"/><worldbody><body pos="0.0926361 0.0115732 0.0764594" '
    ...                   'euler="2.35619 0 1.5708"><joint axis="0 0 1"/></body></worldbody></mujoco>')
    >>> mjcf_rounding([root])
    Rounding(digits=6, length=5e-08, angle=5e-06)
    """
    digits = DigitCounter()
    scale = math.pi / 180.0
    for root in roots:
        for element in root.iter():
            if element.tag == "compiler" and element.get("angle") in ("radian", "degree"):
                scale = 1.0 if element.get("angle") == "radian" else math.pi / 180.0
            if element.tag in MJCF_PLACING:
                count_mjcf_digits(digits, element, scale)
    return digits.rounding()


@dataclass(frozen=True)
class FilePrecision:
    """A file's precision ``value``, relative to the characteristic length (``None``: nothing says the file is inexact), and
    what it was found from: the ``digits`` it is rounded to, the largest relative ``gap`` of its loop closures at the pose."""

    value: float | None
    digits: int | None = None
    gap: float = 0.0

    def describe(self) -> str:
        """What the precision was found from, for a note.

        Examples
        --------
        >>> FilePrecision(5e-6, 6, 2.1e-7).describe()
        'numbers written with 6 significant digits; loops closing to 2.1e-07 of its size'
        """
        parts = []
        if self.digits is not None:
            parts.append(f"numbers written with {self.digits} significant digits")
        if self.gap > 1e-12:  # below: round-off of the reading itself, not worth a word
            parts.append(f"loops closing to {self.gap:.2g} of its size")
        return "; ".join(parts)


def file_precision(rounding: Rounding | None, gaps: Iterable[float], angle_gaps: Iterable[float], points: Iterable[object]) -> FilePrecision:
    """The precision of a file from its rounding and its loops' gaps (absolute lengths, and angles in radians).

    ``points``: its joints' points, whose characteristic length scales the gaps.

    Examples
    --------
    >>> pts = [(0, 0, 0), (0.1, 0, 0), (0.1, 0.1, 0), (0, 0.1, 0)]
    >>> p = file_precision(Rounding(6, 5e-8, 5e-6), [1e-8], [], pts)
    >>> p.value, p.digits, round(p.gap, 9)
    (5e-06, 6, 1.41e-07)
    >>> file_precision(None, [0.0], [], pts).value is None, file_precision(None, [0.05], [], pts).value is None
    (True, True)
    """
    pts = np.array([p for p in points if p is not None], dtype=float).reshape(-1, 3)
    length = characteristic_scale(pts)[1] if len(pts) else 1.0
    relative = [g / length for g in gaps] + list(angle_gaps)
    gap = max((g for g in relative if g <= ASSEMBLED), default=0.0)
    found = [gap] if gap > 0.0 else []
    if rounding is not None:
        found += [rounding.length / length, rounding.angle]
    value = max(found, default=0.0)
    return FilePrecision(value if value > 0.0 else None, rounding.digits if rounding is not None else None, gap)
