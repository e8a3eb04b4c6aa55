"""Read mechanism files (YAML) into :class:`~mobility.model.Mechanism` objects.

Implements version 1 of the file format (``docs/file-format.md``) and three
extensions that never change the meaning of a version-1 file:

* ``parameters``: named numbers, each a number or an expression over the
  parameters above it; any number field may then be an expression string
  (see :mod:`mobility.expressions`);
* ``limbs``: a block of joints repeated ``copies`` times, with the copy index
  available in expressions and ``{...}`` substitutions in names, and an
  optional frame per copy;
* joint types may also be written by name (``revolute`` for ``R``...), frames
  may be given by ``axis`` and ``angle`` instead of ``rpy``, and a joint may
  carry ``actuated: true``.

Every error names the file, the line, the key and what was expected.  The
loader knows nothing of screws.

Examples
--------
>>> text = '''
... name: slider
... ground: g
... end_effector: s
... joints:
...   - {name: P1, type: P, links: [g, s], axis: [0, 0, 2]}
... '''
>>> m = loads(text)
>>> m.joints[0].axis
(0.0, 0.0, 1.0)
>>> loads(text.replace("[0, 0, 2]", "[0, 2]"), file="slider.yaml")
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: slider.yaml:6: joints[0].axis: expected a list of 3 numbers, got 2
"""

from __future__ import annotations

import difflib
import math
import re
from pathlib import Path
from typing import Any, Callable, Mapping

from .errors import MechanismError, MechanismFileError
from .expressions import evaluate
from .model import EXPECTED_KEYS, JOINT_DOF, JOINT_TYPES, WORLD, Expected, Frame, Joint, Mechanism
from .transforms import rotation_from_axis_angle, rotation_from_rpy
from .yaml_source import KeyPath, Positions, format_key, parse_yaml, read_text

__all__ = ["load", "loads", "TOP_LEVEL_KEYS", "JOINT_KEYS", "EXPECTED_VALIDATORS"]

TOP_LEVEL_KEYS = ("name", "description", "ground", "end_effector", "units", "frames", "joints", "expected", "parameters", "limbs")
JOINT_KEYS = ("name", "type", "links", "frame", "axis", "point", "pitch", "axes", "normal", "actuated")
FRAME_KEYS = ("origin", "rpy", "axis", "angle", "parent")
LIMB_KEYS = ("copies", "index", "frame", "joints")
_TYPE_NAMES = {name: letter for letter, name in JOINT_TYPES.items()}
_NAME_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_SUBST_RE = re.compile(r"\{([^{}]*)\}")


def load(path: str | Path) -> Mechanism:
    """Load a mechanism file.

    Parameters
    ----------
    path : str or Path
        A YAML file following the format.

    Returns
    -------
    Mechanism

    Raises
    ------
    MechanismFileError
        When the file cannot be read or breaks the format; the message names
        file, line, key and what was expected.
    """
    return loads(read_text(path), file=str(path))


def loads(text: str, file: str = "<string>") -> Mechanism:
    """Load a mechanism from YAML text (see :func:`load`)."""
    data, positions = parse_yaml(text, file)
    return _Reader(file, positions).mechanism(data)


def _expected_int(value: Any, key: str, *, signed: bool = False) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or (not signed and value < 0):
        raise MechanismError(key, f"expected {'an integer' if signed else 'a non-negative integer'}, got {value!r}")
    return value


def _expected_pattern(value: Any, key: str) -> str:
    if not isinstance(value, str) or not re.fullmatch(r"0|([1-6]T)?([1-6]R)?", value) or not value:
        raise MechanismError(key, f'expected a pattern such as "3T", "1T2R", "3R" or "0", got {value!r}')
    return value


EXPECTED_VALIDATORS: dict[str, Callable[[Any, str], Any]] = {
    "dof": _expected_int,
    "pattern": _expected_pattern,
    "mobility": _expected_int,
    "redundant_constraints": _expected_int,
    "idle_dof": _expected_int,
    "gruebler_kutzbach": lambda v, k: _expected_int(v, k, signed=True),
    "full_cycle_dof": _expected_int,
    "full_cycle_mobility": _expected_int,
    "finite_verdict": lambda v, k: _expected_choice(v, k, ("full-cycle", "instantaneous-only", "cannot-move", "bifurcation")),
}
"""Validators of the ``expected`` keys (other modules may register more)."""


def _expected_choice(value: Any, key: str, choices: tuple[str, ...]) -> str:
    if value not in choices:
        raise MechanismError(key, f"expected one of {', '.join(choices)}, got {value!r}")
    return value


class _Reader:
    """Turns parsed YAML into a Mechanism, translating every error to file:line: key."""

    def __init__(self, file: str, positions: Positions) -> None:
        self.file = file
        self.pos = positions
        self.names: dict[str, float] = {}
        self.angle_scale = math.pi / 180.0

    # -- errors -----------------------------------------------------------
    def fail(self, path: KeyPath, message: str) -> MechanismFileError:
        return MechanismFileError(format_key(path), message, file=self.file, line=self.pos.line(path))

    def check_keys(self, mapping: Mapping[str, Any], allowed: tuple[str, ...], path: KeyPath, what: str) -> None:
        for key in mapping:
            if key not in allowed:
                close = difflib.get_close_matches(str(key), allowed, n=1)
                hint = f" (did you mean {close[0]!r}?)" if close else ""
                raise self.fail(path + (key,), f"unknown key in {what}{hint}; expected one of: {', '.join(allowed)}")

    def mapping(self, value: Any, path: KeyPath, what: str) -> Mapping[str, Any]:
        if not isinstance(value, dict):
            raise self.fail(path, f"expected a mapping ({what}), got {_kind(value)}")
        return value

    # -- scalars ----------------------------------------------------------
    def number(self, value: Any, path: KeyPath, names: Mapping[str, float] | None = None) -> float:
        if isinstance(value, bool):
            raise self.fail(path, f"expected a number, got {value!r}")
        if isinstance(value, (int, float)):
            if not math.isfinite(value):
                raise self.fail(path, f"expected a finite number, got {value!r}")
            return float(value)
        if isinstance(value, str):
            try:
                return evaluate(value, self.names if names is None else names)
            except ValueError as exc:
                raise self.fail(path, str(exc)) from None
        raise self.fail(path, f"expected a number or an expression, got {_kind(value)}")

    def vector(self, value: Any, path: KeyPath, names: Mapping[str, float] | None = None) -> tuple[float, float, float]:
        if not isinstance(value, list):
            raise self.fail(path, f"expected a list of 3 numbers, got {_kind(value)}")
        if len(value) != 3:
            raise self.fail(path, f"expected a list of 3 numbers, got {len(value)}")
        x, y, z = (self.number(v, path + (i,), names) for i, v in enumerate(value))
        return (x, y, z)

    def string(self, value: Any, path: KeyPath) -> str:
        if not isinstance(value, str) or not value.strip():
            raise self.fail(path, f"expected a non-empty string, got {_kind(value)}")
        return value

    # -- document ---------------------------------------------------------
    def mechanism(self, data: Any) -> Mechanism:
        if data is None:
            raise self.fail((), "the file is empty; expected a mapping with name, ground, end_effector and joints")
        doc = self.mapping(data, (), "a mechanism")
        self.check_keys(doc, TOP_LEVEL_KEYS, (), "a mechanism")
        for key in ("name", "ground", "end_effector"):
            if key not in doc:
                raise self.fail((), f"missing required key {key!r}")
        if "joints" not in doc and "limbs" not in doc:
            raise self.fail((), "missing required key 'joints'")
        name = self.string(str(doc["name"]) if isinstance(doc["name"], (int, float)) else doc["name"], ("name",))
        description = doc.get("description", "")
        if not isinstance(description, str):
            raise self.fail(("description",), f"expected a string, got {_kind(description)}")
        length_unit = self.units(doc.get("units"))
        self.parameters(doc.get("parameters"))
        frames = self.frames(doc.get("frames"))
        joints, sources = self.joints(doc.get("joints", []), ("joints",), {}, None)
        limb_frames, limb_joints, limb_sources = self.limbs(doc.get("limbs"))
        frames += limb_frames
        joints += limb_joints
        sources += limb_sources
        if not joints:
            raise self.fail(("joints",), "expected at least one joint")
        expected = self.expected(doc["expected"]) if "expected" in doc else None
        try:
            return Mechanism(
                name=name,
                ground=self.string(doc["ground"], ("ground",)),
                end_effector=self.string(doc["end_effector"], ("end_effector",)),
                joints=tuple(joints),
                frames=tuple(frames),
                description=description,
                length_unit=length_unit,
                expected=expected,
                source=self.file,
            )
        except MechanismError as exc:
            raise self.fail(self.source_path(exc.key, sources), exc.message) from None

    def source_path(self, key: str, sources: list[KeyPath]) -> KeyPath:
        """Key path in the file of a model error key such as ``joints[4].name``."""
        path = _parse_key(key)
        if len(path) >= 2 and path[0] == "joints" and isinstance(path[1], int) and path[1] < len(sources):
            return sources[path[1]] + path[2:]
        return path

    def units(self, value: Any) -> str:
        if value is None:
            return ""
        units = self.mapping(value, ("units",), "units")
        self.check_keys(units, ("angle", "length"), ("units",), "units")
        angle = units.get("angle", "deg")
        if angle in ("deg", "degree", "degrees"):
            self.angle_scale = math.pi / 180.0
        elif angle in ("rad", "radian", "radians"):
            self.angle_scale = 1.0
        else:
            raise self.fail(("units", "angle"), f"expected deg or rad, got {angle!r}")
        length = units.get("length", "")
        if not isinstance(length, str):
            raise self.fail(("units", "length"), f"expected a unit label such as mm, got {_kind(length)}")
        return length

    def parameters(self, value: Any) -> None:
        if value is None:
            return
        params = self.mapping(value, ("parameters",), "parameter names to numbers or expressions")
        for key, raw in params.items():
            if not _NAME_RE.match(key) or key in ("pi", "tau", "e"):
                raise self.fail(("parameters", key), "expected a parameter name (letters, digits, _; not pi, tau or e)")
            self.names[key] = self.number(raw, ("parameters", key))

    def frames(self, value: Any) -> list[Frame]:
        if value is None:
            return []
        frames = self.mapping(value, ("frames",), "frame names to frames")
        return [self.frame(str(fname), fdata, ("frames", fname), self.names) for fname, fdata in frames.items()]

    def frame(self, name: str, data: Any, path: KeyPath, names: Mapping[str, float]) -> Frame:
        fdata = self.mapping(data if data is not None else {}, path, "a frame with origin, rpy, parent")
        self.check_keys(fdata, FRAME_KEYS + (("name",) if path[0] == "limbs" else ()), path, "a frame")
        origin = self.vector(fdata["origin"], path + ("origin",), names) if "origin" in fdata else (0.0, 0.0, 0.0)
        if "rpy" in fdata and ("axis" in fdata or "angle" in fdata):
            raise self.fail(path, "give either rpy or axis and angle, not both")
        if "rpy" in fdata:
            rpy = self.vector(fdata["rpy"], path + ("rpy",), names)
            rotation = rotation_from_rpy(tuple(a * self.angle_scale for a in rpy))
        elif "axis" in fdata or "angle" in fdata:
            if "axis" not in fdata or "angle" not in fdata:
                raise self.fail(path, "a rotation by axis and angle needs both keys")
            axis = self.vector(fdata["axis"], path + ("axis",), names)
            norm = math.sqrt(sum(a * a for a in axis))
            if norm == 0.0:
                raise self.fail(path + ("axis",), "expected a non-zero direction, got [0, 0, 0]")
            rotation = rotation_from_axis_angle([a / norm for a in axis], self.number(fdata["angle"], path + ("angle",), names) * self.angle_scale)
        else:
            rotation = rotation_from_rpy((0.0, 0.0, 0.0))
        parent = fdata.get("parent", WORLD)
        if not isinstance(parent, str):
            raise self.fail(path + ("parent",), f"expected a frame name, got {_kind(parent)}")
        try:
            return Frame(name, origin, tuple(map(tuple, rotation)), parent)
        except MechanismError as exc:
            raise self.fail(path + tuple(_parse_key(exc.key)), exc.message) from None

    def joints(self, value: Any, path: KeyPath, names: Mapping[str, float], default_frame: str | None, subst: Callable[[str, KeyPath], str] | None = None) -> tuple[list[Joint], list[KeyPath]]:
        if not isinstance(value, list):
            raise self.fail(path, f"expected a list of joints, got {_kind(value)}")
        out, sources = [], []
        for i, raw in enumerate(value):
            out.append(self.joint(raw, path + (i,), names, default_frame, subst))
            sources.append(path + (i,))
        return out, sources

    def joint(self, raw: Any, path: KeyPath, extra_names: Mapping[str, float], default_frame: str | None, subst: Callable[[str, KeyPath], str] | None) -> Joint:
        data = self.mapping(raw, path, "a joint with name, type, links and geometry")
        self.check_keys(data, JOINT_KEYS, path, "a joint")
        for key in ("name", "type", "links"):
            if key not in data:
                raise self.fail(path, f"missing required key {key!r} of a joint")
        names = {**self.names, **extra_names}
        text = subst or (lambda s, p: s)
        name = text(self.string(str(data["name"]) if isinstance(data["name"], (int, float)) else data["name"], path + ("name",)), path + ("name",))
        jtype = data["type"]
        if isinstance(jtype, str) and jtype.lower() in _TYPE_NAMES:
            jtype = _TYPE_NAMES[jtype.lower()]
        if jtype not in JOINT_DOF:
            raise self.fail(path + ("type",), f"unknown joint type {jtype!r}; expected one of {', '.join(JOINT_DOF)} (or revolute, prismatic, helical, cylindrical, universal, spherical, planar)")
        links = data["links"]
        if not isinstance(links, list) or len(links) != 2 or not all(isinstance(x, (str, int)) for x in links):
            raise self.fail(path + ("links",), f"expected two link names [a, b], got {_kind(links)}")
        links = tuple(text(str(x), path + ("links", k)) for k, x in enumerate(links))
        fields: dict[str, Any] = {}
        for key in ("axis", "point", "normal"):
            if key in data:
                fields[key] = self.vector(data[key], path + (key,), names)
        if "pitch" in data:
            fields["pitch"] = self.number(data["pitch"], path + ("pitch",), names)
        if "axes" in data:
            axes = data["axes"]
            if not isinstance(axes, list) or len(axes) != 2:
                raise self.fail(path + ("axes",), f"expected two directions [a1, a2], got {_kind(axes)}")
            fields["axes"] = tuple(self.vector(a, path + ("axes", k), names) for k, a in enumerate(axes))
        frame = data.get("frame", default_frame or WORLD)
        if not isinstance(frame, str):
            raise self.fail(path + ("frame",), f"expected a frame name, got {_kind(frame)}")
        actuated = data.get("actuated", False)
        if not isinstance(actuated, bool):
            raise self.fail(path + ("actuated",), f"expected true or false, got {actuated!r}")
        try:
            return Joint(name, jtype, links, frame=text(frame, path + ("frame",)), actuated=actuated, **fields)
        except MechanismError as exc:
            raise self.fail(path + _parse_key(exc.key), exc.message) from None

    def limbs(self, value: Any) -> tuple[list[Frame], list[Joint], list[KeyPath]]:
        frames: list[Frame] = []
        joints: list[Joint] = []
        sources: list[KeyPath] = []
        if value is None:
            return frames, joints, sources
        if not isinstance(value, list):
            raise self.fail(("limbs",), f"expected a list of limb patterns, got {_kind(value)}")
        for k, raw in enumerate(value):
            path: KeyPath = ("limbs", k)
            limb = self.mapping(raw, path, "a limb pattern with copies and joints")
            self.check_keys(limb, LIMB_KEYS, path, "a limb pattern")
            copies = limb.get("copies")
            if isinstance(copies, bool) or not isinstance(copies, int) or copies < 1:
                raise self.fail(path + ("copies",), f"expected a positive integer, got {copies!r}")
            index = limb.get("index", "i")
            if not isinstance(index, str) or not _NAME_RE.match(index):
                raise self.fail(path + ("index",), f"expected a variable name, got {index!r}")
            if "joints" not in limb:
                raise self.fail(path, "missing required key 'joints' of a limb pattern")
            for i in range(copies):
                local = {index: float(i)}

                def subst(s: str, p: KeyPath, local: dict[str, float] = local) -> str:
                    def one(m: re.Match[str]) -> str:
                        v = self.number(m.group(1), p, {**self.names, **local})
                        return str(int(v)) if v == int(v) else repr(v)

                    return _SUBST_RE.sub(one, s)

                frame_name = None
                if "frame" in limb:
                    fdata = self.mapping(limb["frame"], path + ("frame",), "a frame")
                    frame_name = subst(str(fdata.get("name", f"limb{k}_{{{index}}}")), path + ("frame", "name"))
                    parent = fdata.get("parent")
                    fdata = {**fdata, **({"parent": subst(parent, path + ("frame", "parent"))} if isinstance(parent, str) else {})}
                    fdata.pop("name", None)
                    frames.append(self.frame(frame_name, fdata, path + ("frame",), {**self.names, **local}))
                js, src = self.joints(limb["joints"], path + ("joints",), local, frame_name, subst)
                joints += js
                sources += src
        return frames, joints, sources

    def expected(self, value: Any) -> Expected:
        path: KeyPath = ("expected",)
        data = self.mapping(value, path, "expected results")
        self.check_keys(data, tuple(EXPECTED_KEYS), path, "the expected block")
        fields: dict[str, Any] = {}
        extra: dict[str, Any] = {}
        for key, raw in data.items():
            kpath = path + (key,)
            if key == "translations":
                if not isinstance(raw, list):
                    raise self.fail(kpath, f"expected a list of 3-vectors, got {_kind(raw)}")
                fields[key] = tuple(self.vector(v, kpath + (i,)) for i, v in enumerate(raw))
                continue
            validator = EXPECTED_VALIDATORS.get(key)
            try:
                parsed = validator(raw, format_key(kpath)) if validator else raw
            except MechanismError as exc:
                raise self.fail(kpath, exc.message) from None
            if key in Expected.__dataclass_fields__:
                fields[key] = parsed
            else:
                extra[key] = parsed
        return Expected(**fields, extra=extra)


def _kind(value: Any) -> str:
    """Describe a parsed YAML value for an error message."""
    if value is None:
        return "nothing"
    if isinstance(value, bool):
        return f"{value!r}".lower()
    if isinstance(value, (int, float)):
        return f"the number {value!r}"
    if isinstance(value, str):
        return f"the string {value!r}"
    if isinstance(value, list):
        return f"a list of {len(value)}"
    if isinstance(value, dict):
        return "a mapping"
    return type(value).__name__


def _parse_key(key: str) -> KeyPath:
    """Parse ``joints[3].axes[0]`` into ``("joints", 3, "axes", 0)``."""
    out: list[str | int] = []
    for part in re.finditer(r"([^.\[\]]+)|\[(\d+)\]", key):
        out.append(int(part.group(2)) if part.group(2) is not None else part.group(1))
    return tuple(out)
