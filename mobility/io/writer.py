"""Writing a mechanism file: a :class:`~mobility.core.model.Mechanism` out as YAML text.

Version 1 of the format (plus ``actuated`` and ``couplings``), one joint per line in flow style, in the global frame.
Round-off (below ``round_off`` of the characteristic length, or of 1 for a direction) is written as 0, every number as
the shortest decimal within a few units of its last place (``0.15``): the second round trip is exact to the bit.

Examples
--------
>>> from mobility.core.model import Joint, Mechanism
>>> import mobility
>>> m = Mechanism("slide", "g", "s", (Joint("p", "P", ("g", "s"), axis=(0, 0, 1), actuated=True),))
>>> print(mechanism_to_yaml(m, expected={"dof": 1, "pattern": "1T"}))
name: slide
ground: g
end_effector: s
joints:
  - {name: p, type: P, links: [g, s], axis: [0, 0, 1], actuated: true}
expected: {dof: 1, pattern: 1T}
<BLANKLINE>
>>> mobility.loads(mechanism_to_yaml(m)).joints[0].actuated
True
"""

from __future__ import annotations

import json
import math
import re
import textwrap
from typing import Any, Iterable

import numpy as np
import yaml

from ..core.model import Mechanism
from ..core.tolerance import DEFAULT_TOLERANCE, WRITE_DRIFT, characteristic_scale, clean_numbers
from ..errors import MechanismFileError

__all__ = ["mechanism_to_yaml", "yaml_scalar", "require_written_faithfully"]

_PLAIN = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.\-()+/ ]*[A-Za-z0-9_.)]|[A-Za-z_]")


def yaml_scalar(value: Any) -> str:
    """A name or number written so that YAML reads it back unchanged.

    Examples
    --------
    >>> yaml_scalar("crank"), yaml_scalar("2T3R"), yaml_scalar("on"), yaml_scalar("1.5"), yaml_scalar("a: b"), yaml_scalar(0.5)
    ('crank', '2T3R', '"on"', '"1.5"', '"a: b"', '0.5')
    """
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return _number(value)
    text = str(value)
    if _PLAIN.fullmatch(text) and yaml.safe_load(text) == text:  # not read as a number, boolean or null
        return text
    return json.dumps(text, ensure_ascii=False)  # a JSON string is a YAML double-quoted scalar


NOISE_ULPS = 4
"""How many units in the last place of a number (or of the mechanism's size) a written number may move to drop the digits of round-off."""


def _number(x: float, scale: float = 1.0) -> str:
    """``x`` as the shortest decimal within :data:`NOISE_ULPS` units in the last place of ``x`` or of ``scale``, round-off of
    ``scale`` written as 0 (:func:`~mobility.core.tolerance.clean_numbers`); a fixed point: what it reads back to is written the same.

    Examples
    --------
    >>> _number(0.1 + 0.05), _number(0.1 + 0.2), _number(1 / 3), _number(10.1 - 10, 10.0), _number(1e-20)
    ('0.15', '0.3', '0.333333333333333', '0.1', '0')
    >>> _number(2.0**60), _number(-0.0), _number(1e-250, 1e-250)
    ('1.152921504606847e+18', '0', '1e-250')
    """
    text = _written(float(x), scale)
    for _ in range(17):  # each pass keeps or shortens the text: a fixed point within 17 digits
        again = _written(float(text), scale)
        if again == text:
            break
        text = again
    return text


def _written(x: float, scale: float) -> str:
    """One pass of :func:`_number`: the shortest decimal of ``x`` within round-off of it."""
    x = clean_numbers(x, scale)
    if x == 0.0:
        return "0"
    room = NOISE_ULPS * max(math.ulp(x), math.ulp(scale))
    for digits in range(1, 17):
        y = float(f"{x:.{digits}g}")
        if abs(y - x) <= room:
            x = y
            break
    return _integral(x) or repr(x)


def _integral(x: float) -> str | None:
    """``x`` written as an integer when it is one that a double holds exactly (``None`` otherwise)."""
    return str(int(x)) if x.is_integer() and abs(x) < 2.0**53 else None


def _direction(v: Iterable[float]) -> str:
    """A unit direction: each component the shortest decimal within units of its own last place, round-off written as 0, when they still make a vector of unit length (read as written); else to the last bit."""
    exact = [float(x) for x in v]
    short = [_number(x, 0.0) if abs(x) >= DEFAULT_TOLERANCE.round_off else "0" for x in exact]  # within units of its own last place
    if math.hypot(*exact) == 1.0 and math.hypot(*(float(t) for t in short)) != 1.0:  # shorter digits would be normalised on reading
        short = [_integral(x) or repr(x) for x in (clean_numbers(x, 1.0) for x in exact)]  # to the last bit: the same vector
    return "[" + ", ".join(short) + "]"


def mechanism_to_yaml(mechanism: Mechanism, *, description: str = "", expected: dict[str, Any] | None = None) -> str:
    """A mechanism file for ``mechanism``, its joints in the global frame, ``description`` folded, ``expected`` as its block (see the module's example)."""
    lines = [f"name: {yaml_scalar(mechanism.name)}"]
    if description:  # folded: lines of at most 101 characters, a longer word alone on its line
        lines += ["description: >", *textwrap.wrap(" ".join(description.split()), 101, initial_indent="  ", subsequent_indent="  ",
                                                    break_long_words=False, break_on_hyphens=False)]
    if mechanism.length_unit:
        lines.append(f"units: {{length: {yaml_scalar(mechanism.length_unit)}}}")
    lines += [f"ground: {yaml_scalar(mechanism.ground)}", f"end_effector: {yaml_scalar(mechanism.end_effector)}", "joints:"]
    joints = mechanism.world_joints
    size = _size(mechanism)
    for j in joints:
        fields = [f"name: {yaml_scalar(j.name)}", f"type: {j.type}", f"links: [{yaml_scalar(j.links[0])}, {yaml_scalar(j.links[1])}]"]
        if j.axis is not None:
            fields.append(f"axis: {_direction(j.axis)}")
        if j.axes is not None:
            fields.append(f"axes: [{_direction(j.axes[0])}, {_direction(j.axes[1])}]")
        if j.point is not None and j.type != "P":
            fields.append(f"point: [{', '.join(_number(x, size) for x in j.point)}]")
        if j.pitch is not None:
            fields.append(f"pitch: {_number(j.pitch, size)}")
        if j.normal is not None:
            fields.append(f"normal: {_direction(j.normal)}")
        if j.actuated:
            fields.append("actuated: true")
        lines.append("  - {" + ", ".join(fields) + "}")
    if mechanism.couplings:
        lines.append("couplings:")
        for c in mechanism.couplings:
            lines.append("  - {joints: [" + ", ".join(yaml_scalar(n) for n in c.joints) + "], coefficients: [" + ", ".join(_number(x, abs(x)) for x in c.coefficients) + "]}")
    if expected:
        lines.append("expected: {" + ", ".join(f"{k}: {yaml_scalar(v)}" for k, v in expected.items()) + "}")
    return "\n".join(lines) + "\n"


def _size(mechanism: Mechanism) -> float:
    """The characteristic length of ``mechanism``'s joint points and pitches (:func:`~mobility.core.tolerance.characteristic_scale`)."""
    joints = mechanism.world_joints
    points = [j.point for j in joints if j.point is not None]
    pitches = [j.pitch for j in joints if j.pitch is not None]
    return characteristic_scale(np.array(points, dtype=float).reshape(-1, 3), pitches=np.array(pitches, dtype=float))[1]


def require_written_faithfully(mechanism: Mechanism, text: str, where: str) -> None:
    """Read ``text`` (written by :func:`mechanism_to_yaml`) back and refuse it, in one line, unless its joints are ``mechanism``'s.

    Round-off is written as 0: a mechanism whose numbers span more than double
    precision holds relative to its size would come back another mechanism.  A
    joint may change by :data:`~mobility.core.tolerance.WRITE_DRIFT` (relative to
    the characteristic length for points and pitches); ``where`` names the file.

    Raises
    ------
    MechanismFileError
        Naming the first joint and field that would change.

    Examples
    --------
    >>> from mobility.core.model import Joint, Mechanism
    >>> z = (0, 0, 1)
    >>> m = Mechanism("arm", "g", "b", (Joint("A", "R", ("g", "a"), axis=z, point=(0, 0, 0)),
    ...                                 Joint("B", "R", ("a", "b"), axis=z, point=(1, 1e-300, 0))))
    >>> text = mechanism_to_yaml(m)
    >>> require_written_faithfully(m, text, "arm.yaml")      # 1e-300 is round-off: written as 0, and that is faithful
    >>> require_written_faithfully(m, text.replace("point: [1, 0, 0]", "point: [1, 0.001, 0]"), "arm.yaml")
    Traceback (most recent call last):
    mobility.errors.MechanismFileError: arm.yaml: joints[1].point: joint 'B' would not be written faithfully (it changes by 0.002 of the mechanism's size once written with the writer's digits); the mechanism is too small or too large to convert
    """
    from .loader import loads  # the reader, to read back what was written

    back = loads(text, file=where)
    length = _size(mechanism)
    for i, (a, b) in enumerate(zip(mechanism.world_joints, back.world_joints)):
        for name, size in (("point", length), ("pitch", length), ("axis", 1.0), ("normal", 1.0), ("axes", 1.0)):
            x, y = getattr(a, name), getattr(b, name)
            if x is None or (name == "point" and a.type == "P"):
                continue
            with np.errstate(over="ignore", invalid="ignore"):
                drift = float(np.max(np.abs(np.subtract(x, y, dtype=float)))) / size if y is not None else np.inf
            if not drift <= WRITE_DRIFT:
                raise MechanismFileError(f"joints[{i}].{name}", f"joint {a.name!r} would not be written faithfully (it changes by {drift:.2g} of the "
                                         "mechanism's size once written with the writer's digits); the mechanism is too small or too large to convert",
                                         file=str(mechanism.source or where))
