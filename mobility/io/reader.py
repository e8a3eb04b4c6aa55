"""Reading a parsed YAML document with one-line errors: the part every document loader shares.

The mechanism and flexure loaders build on :class:`DocumentReader`.  Numbers are checked where they are read (finite,
an expression neither overflowing nor complex); names must be strings (``links: [g, true]`` is an error, not a link ``True``).

Examples
--------
>>> from mobility.io.yaml_source import parse_yaml
>>> data, positions = parse_yaml("parameters: {a: 2}\\npoint: [a, 1, 0]\\n", "p.yaml")
>>> r = DocumentReader("p.yaml", positions)
>>> r.parameters(data["parameters"])
>>> r.vector(data["point"], ("point",))
(2.0, 1.0, 0.0)
>>> r.vector([1, 2], ("point",))
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: p.yaml:2: point: expected a list of 3 numbers, got 2
"""

from __future__ import annotations

import math
import re
from typing import Any, Mapping, cast

from ..core.model import WORLD, Frame, Vector
from ..core.transforms import rotation_from_axis_angle, rotation_from_rpy
from ..errors import MechanismError, MechanismFileError, did_you_mean, name_problem
from .expressions import RESERVED_NAMES, evaluate, uses_radians
from .limits import Limits, current_limits
from .yaml_source import KeyPath, Positions, format_key

__all__ = ["DocumentReader", "describe_value", "parse_key", "NAME_RE", "FRAME_KEYS"]

FRAME_KEYS = ("origin", "rpy", "axis", "angle", "parent")
Required = tuple[str | tuple[str, ...], ...]
"""Required keys: each a key, or a tuple of keys of which one is enough."""
NAME_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


class DocumentReader:
    """Reads the values of one parsed document; every error names file, line and key.

    ``positions``: the lines of the keys, from :func:`~mobility.io.yaml_source.parse_yaml`.
    """

    def __init__(self, file: str, positions: Positions, limits: Limits | None = None) -> None:
        self.file = file
        self.pos = positions
        self.limits = current_limits(limits)
        self.frame_paths: dict[str, KeyPath] = {}
        self.names: dict[str, float] = {}
        self.angle_scale = math.pi / 180.0
        self.angle_unit_given = False
        self.radian_parameters: set[str] = set()
        self.angles: list[tuple[KeyPath, Any, float]] = []
        """Every angle read (a frame's ``rpy`` component or ``angle``): where, as written, its value in the file's unit."""

    def fail(self, path: KeyPath, message: str) -> MechanismFileError:
        return MechanismFileError(format_key(path), message, file=self.file, line=self.pos.line(path))

    def require_known_keys(self, mapping: Mapping[str, Any], allowed: tuple[str, ...], path: KeyPath, what: str) -> None:
        for key in mapping:
            if key not in allowed:
                raise self.fail(path + (key,), f"unknown key in {what}{did_you_mean(key, allowed)}; expected one of: {', '.join(allowed)}")

    def mapping(self, value: Any, path: KeyPath, what: str) -> Mapping[str, Any]:
        if not isinstance(value, dict):
            raise self.fail(path, f"expected a mapping ({what}), got {describe_value(value)}")
        return value

    def record(self, value: Any, path: KeyPath, what: str, allowed: tuple[str, ...], required: Required = (), *, described: str | None = None) -> Mapping[str, Any]:
        """A mapping with only ``allowed`` keys and every ``required`` one (``Required``; a missing one is an error at its key
        path, on the mapping's line); ``described``: what a mapping should hold, when ``value`` is not one.

        Examples
        --------
        >>> r = DocumentReader("j.yaml", Positions({}))
        >>> r.record({"name": "A"}, ("joints", 0), "a joint", ("name", "type"), ("name", "type"))
        Traceback (most recent call last):
        ...
        mobility.errors.MechanismFileError: j.yaml: joints[0].type: missing required key of a joint
        """
        data = self.mapping(value, path, described or what)
        self.require_known_keys(data, allowed, path, what)
        for key in required:
            choices = key if isinstance(key, tuple) else (key,)
            if not any(k in data for k in choices):
                alternatives = f" (or {', '.join(choices[1:])})" if len(choices) > 1 else ""
                raise self.fail(path + (choices[0],), "missing required key" + (f" of {what}" if path else "") + alternatives)
        return data

    def document(self, data: Any, what: str, allowed: tuple[str, ...], required: Required) -> Mapping[str, Any]:
        """The top-level mapping of a document: not empty, only ``allowed`` keys, every ``required`` one (see :meth:`record`).

        Examples
        --------
        >>> r = DocumentReader("empty.yaml", Positions({}))
        >>> r.document(None, "a mechanism", ("name", "joints", "limbs"), ("name", ("joints", "limbs")))
        Traceback (most recent call last):
        ...
        mobility.errors.MechanismFileError: empty.yaml: the file is empty; expected a mapping with name and joints
        """
        if data is None:
            keys = [k[0] if isinstance(k, tuple) else k for k in required]
            listed = f"{', '.join(keys[:-1])} and {keys[-1]}" if len(keys) > 1 else keys[0]
            raise self.fail((), f"the file is empty; expected a mapping with {listed}")
        return self.record(data, (), what, allowed, required)

    def name_and_description(self, doc: Mapping[str, Any]) -> tuple[str, str]:
        """The document's ``name`` (a number is taken as its text) and its ``description`` (default empty)."""
        title = doc["name"]
        name = self.checked_name(self.string(str(title) if isinstance(title, (int, float)) and not isinstance(title, bool) else title, ("name",)), ("name",), "the name of the mechanism")
        description = doc.get("description", "")
        if not isinstance(description, str):
            raise self.fail(("description",), f"expected a string, got {describe_value(description)}")
        return name, description

    def number(self, value: Any, path: KeyPath, names: Mapping[str, float] | None = None) -> float:
        if isinstance(value, bool):
            raise self.fail(path, f"expected a number, got {value!r}")
        if isinstance(value, float):
            if not math.isfinite(value):
                raise self.fail(path, f"expected a finite number, got {value!r}")
            return value
        if isinstance(value, int):
            try:
                return float(value)
            except OverflowError:
                raise self.fail(path, f"expected a finite number, got {describe_value(value)}, too large for a float") from None
        if isinstance(value, str):
            lim = self.limits
            try:
                return evaluate(value, self.names if names is None else names, max_length=lim.max_expression_length, max_depth=lim.max_expression_depth)
            except ValueError as exc:
                raise self.fail(path, str(exc)) from None
        raise self.fail(path, f"expected a number or an expression, got {describe_value(value)}")

    def vector(self, value: Any, path: KeyPath, names: Mapping[str, float] | None = None) -> tuple[float, float, float]:
        if not isinstance(value, list):
            raise self.fail(path, f"expected a list of 3 numbers, got {describe_value(value)}")
        if len(value) != 3:
            raise self.fail(path, f"expected a list of 3 numbers, got {len(value)}")
        x, y, z = (self.number(v, path + (i,), names) for i, v in enumerate(value))
        return (x, y, z)

    def string(self, value: Any, path: KeyPath) -> str:
        if not isinstance(value, str) or not value.strip():
            raise self.fail(path, f"expected a non-empty string, got {describe_value(value)}")
        return value

    def identifier(self, value: Any, path: KeyPath, what: str = "a name") -> str:
        """A name of a link, joint or frame: a non-empty string (a number or ``true`` must be quoted), without control, format or line-break characters (:meth:`checked_name`)."""
        if isinstance(value, str) and value.strip():
            return self.checked_name(value, path, what)
        hint = "; write it in quotes if it is a name" if isinstance(value, (bool, int, float)) else ""
        raise self.fail(path, f"expected {what} (a string), got {describe_value(value)}{hint}")

    def checked_name(self, value: str, path: KeyPath, what: str) -> str:
        """``value``, a name, refused when it holds a character no name may hold (:func:`~mobility.errors.name_problem`: a tab, a line break, a bidirectional override...).

        Examples
        --------
        >>> DocumentReader("n.yaml", Positions({})).checked_name("knee\\u2028", ("joints", 0, "name"), "a joint name")
        Traceback (most recent call last):
        ...
        mobility.errors.MechanismFileError: n.yaml: joints[0].name: a line separator '\\u2028' (U+2028) is not allowed in a joint name
        """
        problem = None if value.isprintable() else name_problem(value, what)  # printable: the common case, at one call's cost
        if problem is not None:
            raise self.fail(path, problem)
        return value

    def units(self, value: Any) -> str:
        if value is None:
            return ""
        units = self.record(value, ("units",), "units", ("angle", "length"))
        angle = units.get("angle", "deg")
        self.angle_unit_given = "angle" in units
        if angle in ("deg", "degree", "degrees"):
            self.angle_scale = math.pi / 180.0
        elif angle in ("rad", "radian", "radians"):
            self.angle_scale = 1.0
        else:
            raise self.fail(("units", "angle"), f"expected deg or rad, got {angle!r}")
        length = units.get("length", "")
        if not isinstance(length, str):
            raise self.fail(("units", "length"), f"expected a unit label such as mm, got {describe_value(length)}")
        return length

    def parameters(self, value: Any) -> None:
        if value is None:
            return
        params = self.mapping(value, ("parameters",), "parameter names to numbers or expressions")
        for key, raw in params.items():
            if not NAME_RE.match(key) or key in RESERVED_NAMES:
                raise self.fail(("parameters", key), "expected a parameter name (letters, digits, _; not pi, tau, e or a function name)")
            self.names[key] = self.number(raw, ("parameters", key))
            if isinstance(raw, str) and self.in_radians(raw):
                self.radian_parameters.add(key)

    def frames(self, value: Any) -> list[Frame]:
        if value is None:
            return []
        frames = self.mapping(value, ("frames",), "frame names to frames")
        if len(frames) > self.limits.max_frames:
            raise self.fail(("frames",), f"{len(frames)} frames are more than the limit of {self.limits.max_frames} ({self.limits.hint('max_frames')})")
        return [self.frame(self.checked_name(str(fname), ("frames", fname), "a frame name"), fdata, ("frames", fname), self.names) for fname, fdata in frames.items()]

    def require_frame_chains(self, frames: list[Frame]) -> None:
        """Bound the chains of ``parent`` frames by the depth limit (unknown parents and cycles are the model's to report)."""
        parents = {f.name: f.parent for f in frames}
        depth: dict[str, int] = {WORLD: 0}
        limit = self.limits.max_depth
        for name in parents:
            chain: list[str] = []
            current = name
            while current not in depth and current in parents and current not in chain and len(chain) <= limit:
                chain.append(current)
                current = parents[current]
            too_deep = len(chain) > limit
            if current in depth:
                for k, link in enumerate(reversed(chain), start=1):
                    depth[link] = depth[current] + k
                too_deep = depth[name] > limit
            if too_deep:
                path = self.frame_paths.get(name, ("frames", name)) + ("parent",)
                raise self.fail(path, f"frames chained through more than the limit of {limit} parents ({self.limits.hint('max_depth')})")
            # otherwise an unknown parent or a cycle, which the model reports

    def in_radians(self, text: str) -> bool:
        """True when expression ``text`` is written in radians (:func:`~mobility.io.expressions.uses_radians`, the file's parameters in radians counted)."""
        lim = self.limits
        return uses_radians(text, self.radian_parameters, max_length=lim.max_expression_length, max_depth=lim.max_expression_depth)

    def angle_notes(self) -> list[str]:
        """Warnings on the angles of a file read in degrees that look written in radians, each ``file:line: key: what``.

        An expression using ``pi`` (``"2*pi/3*i"``), or else every angle at most 2π with one not a round number of degrees.

        Examples
        --------
        >>> from mobility.io.yaml_source import parse_yaml
        >>> data, positions = parse_yaml("frames:\\n  leg: {rpy: [0, 0, 'pi/2']}\\n", "legs.yaml")
        >>> r = DocumentReader("legs.yaml", positions)
        >>> _ = r.frames(data["frames"])
        >>> r.angle_notes()
        ["legs.yaml:2: frames.leg.rpy[2]: the angle 'pi/2' uses pi, but the file's angles are in degrees (the default; units: {angle: deg}): it turns by 1.5708 deg; if 1.5708 rad (90 deg) was meant, write the angle in degrees, or give units: {angle: rad} if every angle of the file is in radians"]
        """
        if self.angle_scale == 1.0 or not self.angles:
            return []
        unit = "the default; units: {angle: deg}" if not self.angle_unit_given else "units: {angle: deg}"
        notes: dict[KeyPath, str] = {}
        for path, written, value in self.angles:
            if isinstance(written, str) and (path not in notes or notes[path] == "") and self.in_radians(written):
                if value == 0.0:
                    notes.setdefault(path, "")  # a limb's first copy (i = 0): the next copy says how far it turns
                    continue
                notes[path] = (f"the angle {written!r} uses pi, but the file's angles are in degrees ({unit}): it turns by {value:.6g} deg; "
                               f"if {value:.6g} rad ({math.degrees(value):.6g} deg) was meant, write the angle in degrees, "
                               "or give units: {angle: rad} if every angle of the file is in radians")
        if notes:
            return [str(self.fail(path, text)) for path, text in notes.items() if text]
        turning = [(path, written, value) for path, written, value in self.angles if value != 0.0]
        if not turning or any(abs(value) > math.tau * (1 + 1e-9) for _, _, value in turning):
            return []
        bare = [(path, value) for path, written, value in turning if not isinstance(written, str) and value * 2 != round(value * 2)]
        if not bare:  # every angle a round number of degrees (a tilt of 3 or 2.5 degrees): as meant
            return []
        path, value = max(bare, key=lambda item: abs(item[1]))
        return [str(self.fail(path, f"every angle of the file is at most 2π (6.283), as in radians, but the file's angles are in degrees ({unit}): "
                                    f"this one turns by only {value:g} deg; if {value:g} rad ({math.degrees(value):.6g} deg) was meant, give units: {{angle: rad}}"))]

    def frame(self, name: str, data: Any, path: KeyPath, names: Mapping[str, float]) -> Frame:
        allowed = FRAME_KEYS + (("name",) if path[0] == "limbs" else ())
        fdata = self.record(data if data is not None else {}, path, "a frame", allowed, described="a frame with origin, rpy, parent")
        self.frame_paths.setdefault(name, path)
        origin = self.vector(fdata["origin"], path + ("origin",), names) if "origin" in fdata else (0.0, 0.0, 0.0)
        if "rpy" in fdata and ("axis" in fdata or "angle" in fdata):
            raise self.fail(path, "give either rpy or axis and angle, not both")
        if "rpy" in fdata:
            rpy = self.vector(fdata["rpy"], path + ("rpy",), names)
            written = fdata["rpy"]
            self.angles += [(path + ("rpy", k), written[k], rpy[k]) for k in range(3)]
            rotation = rotation_from_rpy(tuple(a * self.angle_scale for a in rpy))
        elif "axis" in fdata or "angle" in fdata:
            if "axis" not in fdata or "angle" not in fdata:
                raise self.fail(path, "a rotation by axis and angle needs both keys")
            axis = self.vector(fdata["axis"], path + ("axis",), names)
            norm = math.hypot(*axis)  # no overflow for large components
            if norm == 0.0:
                raise self.fail(path + ("axis",), "expected a non-zero direction, got [0, 0, 0]")
            angle = self.number(fdata["angle"], path + ("angle",), names)
            self.angles.append((path + ("angle",), fdata["angle"], angle))
            rotation = rotation_from_axis_angle([a / norm for a in axis], angle * self.angle_scale)
        else:
            rotation = rotation_from_rpy((0.0, 0.0, 0.0))
        parent = self.identifier(fdata.get("parent", WORLD), path + ("parent",), "a frame name")
        try:
            return Frame(name, origin, cast("tuple[Vector, Vector, Vector]", tuple(map(tuple, rotation))), parent)  # a 3x3 matrix
        except MechanismError as exc:
            raise self.fail(path + tuple(parse_key(exc.key)), exc.message) from None


def describe_value(value: Any) -> str:
    """Describe a parsed YAML value for an error message."""
    if value is None:
        return "nothing"
    if isinstance(value, bool):
        return f"{value!r}".lower()
    if isinstance(value, int) and len(str(abs(value))) > 20:
        return f"an integer of {len(str(abs(value)))} digits"
    if isinstance(value, (int, float)):
        return f"the number {value!r}"
    if isinstance(value, str):
        return f"the string {value if len(value) <= 40 else value[:37] + '...'!r}"
    if isinstance(value, list):
        return f"a list of {len(value)} item" + ("" if len(value) == 1 else "s")
    if isinstance(value, dict):
        return "a mapping"
    return type(value).__name__


def shown_value(value: Any) -> str:
    """A value in a message: its ``repr`` when short, else :func:`describe_value` (``a list of 300 items``).

    Examples
    --------
    >>> shown_value("yes"), shown_value(list(range(300)))
    ("'yes'", 'a list of 300 items')
    """
    text = repr(value)
    return text if len(text) <= 40 else describe_value(value)


def parse_key(key: str) -> KeyPath:
    """Parse ``joints[3].axes[0]`` into ``("joints", 3, "axes", 0)``."""
    return tuple(int(part.group(2)) if part.group(2) is not None else part.group(1) for part in re.finditer(r"([^.\[\]]+)|\[(\d+)\]", key))
