"""An MJCF file, and every file it includes, checked before MuJoCo reads them.

MuJoCo opens the files a model names and expands ``<replicate>``,
``<flexcomp>`` and ``<composite>`` with no bound: a named pipe makes it wait for
ever, ``count="1000000"`` costs minutes and gigabytes.  :func:`scan_mjcf` walks
the parsed file first, as MuJoCo finds and reads its files, and refuses in one
line what ``docs/robot-files.md`` lists: a bad ``<include>``, counts past the
limits of :mod:`mobility.io.limits` (every copy counted), a ``<flexcomp>``,
``nan``, ``inf`` or an underflow in a geometric attribute, and a direction
MuJoCo would silently replace (:data:`DIRECTIONS`).

Examples
--------
>>> from mobility.io.xml_source import parse_xml
>>> doc = parse_xml('<mujoco>\\n<worldbody>\\n<body pos="nan 0 0"/>\\n</worldbody>\\n</mujoco>', "m.xml")
>>> scan_mjcf(doc, ".")
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: m.xml:3: body/@pos: expected finite numbers, got 'nan 0 0'
>>> doc = parse_xml('<mujoco><worldbody><replicate count="9000"><body><joint/></body></replicate></worldbody></mujoco>', "r.xml")
>>> scan_mjcf(doc, ".")
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: r.xml:1: joint: 9000 joints (count of <replicate> 9000) are more than the limit of 5000 (set MOBILITY_MAX_JOINTS to raise it)
>>> doc = parse_xml('<mujoco><worldbody><body name="b" quat="1e200 1e200 0 0"/></worldbody></mujoco>', "q.xml")
>>> scan_mjcf(doc, ".")
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: q.xml:1: body[b]/@quat: the sum of its squares overflows in double precision: MuJoCo would silently use no rotation instead; expected smaller numbers (only the direction counts), got '1e200 1e200 0 0'
"""

from __future__ import annotations

import math
import os
import re
import stat
import sys
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Callable
from xml.etree.ElementTree import Element

from ..errors import MechanismFileError, clipped
from .files import read_capped, require_not_pipe
from .limits import Limits, current_limits
from .xml_source import XmlDocument, parse_xml, require_no_underflow

__all__ = ["scan_mjcf", "MjcfScan", "GEOMETRY_ATTRIBUTES", "DIRECTIONS", "MUJOCO_EPS"]

GEOMETRY_ATTRIBUTES = frozenset({"pos", "quat", "axisangle", "euler", "xyaxes", "zaxis", "axis", "anchor", "ref", "springref",
                                 "fromto", "size", "offset", "relpose", "polycoef", "spacing"})
"""MJCF attributes that place bodies and joints: a ``nan`` or ``inf`` in one is refused (``range="-inf inf"`` is left to MuJoCo)."""

MUJOCO_EPS = 1e-14
"""MuJoCo's ``mjEPS``: a vector whose sum of squares is below it is not normalized (``mjuu_normvec``)."""

DIRECTIONS = {"quat": "no rotation", "axisangle": "no rotation", "zaxis": "the direction +z or -z", "axis": "a zero axis",
              "fromto": "the direction +z or -z", "relpose": "a zero quaternion"}
"""Attributes whose direction MuJoCo normalizes (``mjuu_normvec``), and what it silently uses when their double-precision
sum of squares overflows (from about ``1e154``); a quaternion whose sum is below :data:`MUJOCO_EPS` stays unnormalized."""

_COUNTED = {"replicate", "flexcomp", "composite"}
_RESOLUTIONS = {"supersphere": (1, 2), "supertorus": (1, 2), "wedge": (2, 1), "plate": (2, 1), "cone": (1, 1)}
"""Builtin meshes MuJoCo makes as it reads the file: how many leading ``params`` are resolutions, and the power of their product
(``sphere`` and ``hemisphere`` are bounded by MuJoCo itself)."""
_HEX = re.compile(r"[+-]?0[xX]")


@dataclass(frozen=True)
class MjcfScan:
    """What the scan found: every ``<include>`` (including file, line), the files read and the counts, copies included
    (the compiled model must keep at least ``equalities``, ``world_joints`` and ``world_bodies``)."""

    includes: tuple[tuple[str, int | None], ...] = ()
    files: tuple[str, ...] = ()
    elements: int = 0
    joints: int = 0
    copies: int = 0
    equalities: int = 0
    asset_values: int = 0
    world_joints: int = 0
    world_bodies: int = 0


@dataclass
class _Context:
    """Where an element sits: its document, the product of the counts around it, whether it is in the world."""

    doc: XmlDocument
    multiplier: int = 1
    factors: tuple[int, ...] = ()
    in_world: bool = False
    chain: tuple[str, ...] = ()
    source: tuple[XmlDocument, Element] | None = None  # the innermost <replicate>, where its copies are refused
    in_equality: bool = False  # the children of <equality>: each a constraint MuJoCo makes rows for
    model_dir: str = ""  # where MuJoCo finds the files named here: the model's folder, a sub-model's own inside a <model> file


@dataclass
class _Scanner:
    model_dir: str
    limits: Limits
    used_bytes: int
    seen: dict[str, str] = field(default_factory=dict)
    includes: list[tuple[str, int | None]] = field(default_factory=list)
    files: list[str] = field(default_factory=list)
    counts: dict[str, int] = field(default_factory=lambda: dict.fromkeys(("elements", "joints", "copies", "equalities", "asset_values",
                                                                         "world_joints", "world_bodies"), 0))  # MjcfScan's fields
    over: dict[str, tuple[XmlDocument, Element, tuple[int, ...]]] = field(default_factory=dict)  # where each count first passed its limit
    models: dict[str, tuple[int, int]] = field(default_factory=dict)  # a <model>'s elements and joints, by name: what each <attach> copies
    waiting: dict[str, list[tuple[Element, _Context]]] = field(default_factory=dict)  # <attach>es met before their <model>

    def walk(self, root: Element, context: _Context) -> None:
        """Every element under ``root`` (iteratively: a deep file must not exhaust Python's stack)."""
        stack = [(child, context) for child in reversed(list(root))]
        while stack:
            stack.extend(reversed(self.visit(*stack.pop())))

    def visit(self, element: Element, where: _Context) -> list[tuple[Element, _Context]]:
        """Check one element; the elements to visit under it, each with its context."""
        tag = element.tag
        _check_numbers(where.doc, element)
        self.count("elements", where.multiplier, element, where)
        if where.multiplier > 1:
            doc, at = where.source or (where.doc, element)
            self.count("copies", where.multiplier, at, where, doc)
        if tag in ("joint", "freejoint") and where.in_world:
            self.count("joints", where.multiplier, element, where)
            self.counts["world_joints"] += where.multiplier
        if tag == "body" and where.in_world:
            self.counts["world_bodies"] += where.multiplier
        if tag == "attach":
            self.attached(element, where)
        if where.in_equality and tag != "include":  # a connect is a joint, a weld six constraint rows: counted as joints
            self.counts["equalities"] += where.multiplier
            self.count("joints", where.multiplier, element, where)
        if tag == "include":
            return self.included(element, where, "include")
        if tag == "model" and element.get("file"):
            return self.included(element, where, "model")
        if tag == "flexcomp":  # refused before MuJoCo reads its file or makes its points
            name = element.get("name")
            raise where.doc.fail(element, f"flexcomp[{clipped(name)}]" if name else "flexcomp", "a deformable body, not supported (not even "
                                 "left out: MuJoCo would make bodies and joints of its points, reading its mesh file whatever its size); "
                                 "expected rigid bodies and joints (remove the <flexcomp>)")
        if tag in ("hfield", "mesh"):
            self.asset_values(element, where)
        inner = where
        if tag in _COUNTED:
            inner = self.counted(element, where)
        elif tag in ("worldbody", "default", "equality"):
            inner = replace(where, in_world=tag == "worldbody", in_equality=tag == "equality")
        return [(child, inner) for child in element]

    def asset_values(self, element: Element, where: _Context) -> None:
        """Count the points MuJoCo makes for a height field or a builtin mesh as it reads it; refuse them past the asset limit."""
        made = _asset_points(element)
        if made is None:
            return
        amount, how = made
        self.counts["asset_values"] += amount * where.multiplier
        limit = self.limits.max_asset_values
        if self.counts["asset_values"] > limit:
            total = self.counts["asset_values"]
            others = f"; {total} with the height fields and builtin meshes before it" if total != amount else ""
            name = element.get("name")
            key = f"{clipped(element.tag)}[{clipped(name)}]" if name else clipped(element.tag)
            raise where.doc.fail(element, key, f"{how}: {amount} points{others}, which MuJoCo allocates as it reads the file; expected "
                                 f"at most the limit of {limit} ({self.limits.hint('max_asset_values')})")

    def count(self, what: str, amount: int, element: Element, where: _Context, doc: XmlDocument | None = None) -> None:
        """Add ``amount`` to the count ``what``; remember the element where it first passes its limit."""
        self.counts[what] += amount
        limit = self.limits.max_elements if what == "elements" else self.limits.max_joints
        if self.counts[what] > limit and what not in self.over:
            self.over[what] = (doc or where.doc, element, where.factors)

    def counted(self, element: Element, where: _Context) -> _Context:
        """The context inside a ``<replicate>`` (its copies multiply), or the points of a ``<flexcomp>``/``<composite>``."""
        text = element.get("count", "")
        if any(_negative(token) for token in text.split()):  # MuJoCo makes no copy of a <replicate count="-1">, and says nothing
            raise where.doc.fail(element, f"{clipped(element.tag)}/@count", f"expected a count of 0 or more, got {clipped(text)!r}")
        factors = _counts(text)
        total = math.prod(factors) if factors else 1
        if element.tag != "replicate" or not len(element):  # an empty <replicate> (or one of comments) costs MuJoCo a copy each too
            self.count("copies", total * where.multiplier, element, where)
        if element.tag != "replicate":
            self.count("elements", total * where.multiplier, element, where)
            return where
        return replace(where, multiplier=where.multiplier * total, factors=where.factors + tuple(factors), source=(where.doc, element))

    def attached(self, element: Element, where: _Context) -> None:
        """Count the copy of a ``<model>`` that an ``<attach>`` makes (its elements and joints), before MuJoCo makes it."""
        name = element.get("model", "")
        made = self.models.get(name)
        if made is None:  # its <model> comes later in the file (an <asset> after the <worldbody>): counted when it is read
            self.waiting.setdefault(name, []).append((element, where))
            return
        elements, joints = made
        self.count("copies", elements * where.multiplier, element, where)
        self.count("elements", elements * where.multiplier, element, where)
        if where.in_world:
            self.count("joints", joints * where.multiplier, element, where)

    def included(self, element: Element, where: _Context, kind: str) -> list[tuple[Element, _Context]]:
        """Check the file of an ``<include>`` or ``<model>``; its elements, to visit in place of the element."""
        doc = where.doc
        name = element.get("file", "")
        folders = dict.fromkeys([where.model_dir or self.model_dir, os.path.dirname(doc.file) or "."])  # where MuJoCo looks, in turn
        candidates = [os.path.join(folder, name) for folder in folders] if name else []
        path = next((candidate for candidate in candidates if os.path.lexists(candidate)), None)

        def fail(message: str) -> MechanismFileError:  # at the element's line in the including file
            return doc.fail(element, kind, f"{clipped(name)!r}: {message}" if name else message)

        if path is None:
            if kind == "model":
                return []  # MuJoCo says the asset is missing
            looked = " and ".join(repr(clipped(f, 60)) for f in folders)
            raise fail(f"no such file (looked in {looked}); expected a file to include")
        self.require_includable(path, fail)
        real = os.path.realpath(path)
        if real in where.chain or (kind == "include" and real in self.seen):
            first = self.seen.get(real) or "the model file itself"
            raise fail(f"included already ({first}); expected each file included once, as MuJoCo requires")
        if len(where.chain) >= self.limits.max_depth:
            raise fail(f"included at a depth of more than the limit of {self.limits.max_depth} ({self.limits.hint('max_depth')})")
        if kind == "include":
            self.seen[real] = f"{doc.file}:{doc.line(element)}"
            self.includes.append((doc.file, doc.line(element)))
        self.files.append(path)
        inner = parse_xml(read_capped(path, self.limits), os.path.normpath(path), mujoco=True)
        model_dir = where.model_dir
        if kind == "model":  # MuJoCo reads a sub-model's own includes from the sub-model's folder
            model_dir = os.path.dirname(path) or "."
            elements, joints = _made_by(inner.root)
            model_name = element.get("name") or Path(name).stem
            self.models[model_name] = (elements, joints)
            for attach, at in self.waiting.pop(model_name, []):
                self.attached(attach, at)
        context = replace(where, doc=inner, in_world=where.in_world and kind == "include", chain=where.chain + (real,),
                          in_equality=where.in_equality and kind == "include", model_dir=model_dir)
        return [(child, context) for child in inner.root]

    def require_includable(self, path: str, fail: Callable[[str], MechanismFileError]) -> None:
        """A regular file, within what remains of the size limit."""
        try:
            mode = require_not_pipe(path)
        except MechanismFileError:
            raise fail("a pipe or socket; expected a file to include") from None
        if not stat.S_ISREG(mode):
            what = "a directory" if stat.S_ISDIR(mode) else "not a regular file (a device, or unreadable)"
            raise fail(f"{what}; expected a file to include")
        size = os.stat(path).st_size
        cap = self.limits.max_file_bytes
        if self.used_bytes + size > cap:
            raise fail(f"has {size} bytes: with the {self.used_bytes} bytes read before it, more than the limit of {cap} bytes "
                       f"for a document and the files it includes ({self.limits.hint('max_file_bytes')})")
        self.used_bytes += size

    def raise_first_over(self) -> None:
        """Refuse the count that passed its limit first, at the element where it did."""
        if not self.over:
            return
        what = next(w for w in ("joints", "copies", "elements") if w in self.over)  # the joint limit says most
        doc, element, factors = self.over[what]
        limit_name = "max_elements" if what == "elements" else "max_joints"
        limit = getattr(self.limits, limit_name)
        noun = {"elements": "elements", "joints": "joints", "copies": "elements made by the count of <replicate>, <flexcomp> and <composite>"}[what]
        details = ["included files and copies counted"] if what == "elements" else []
        equalities = self.counts["equalities"]
        if what == "joints" and equalities:
            noun = "joints and equalities"
            details += [f"{equalities} of them <connect>, <weld> or other equalities, each counted as a joint"]
        details += [f"count of <replicate> {' x '.join(map(str, factors))}"] if factors else []
        detail = f" ({'; '.join(details)})" if details else ""
        raise doc.fail(element, clipped(element.tag),
                       f"{self.counts[what]} {noun}{detail} are more than the limit of {limit} ({self.limits.hint(limit_name)})")


def scan_mjcf(doc: XmlDocument, model_dir: str | Path, limits: Limits | None = None, *, size: int = 0) -> MjcfScan:
    """Check an MJCF document and the files it includes (see the module docstring), each refusal one line at the element's.

    Parameters
    ----------
    model_dir : str or Path
        The directory MuJoCo finds included files in.
    size : int
        Bytes of the model file, counted against the size limit with its includes.
    """
    scanner = _Scanner(str(model_dir) or ".", current_limits(limits), size)
    scanner.seen[os.path.realpath(doc.file)] = "the model file itself"
    scanner.walk(doc.root, _Context(doc, chain=(os.path.realpath(doc.file),)))
    scanner.raise_first_over()
    return MjcfScan(tuple(scanner.includes), tuple(scanner.files), **scanner.counts)


def _check_numbers(doc: XmlDocument, element: Element) -> None:
    """Refuse a geometric attribute (or an actuator's ``gear``) holding ``nan`` or ``inf`` (``1e400`` reads as ``inf``), a number written
    non-zero that reads as 0 (``1e-400``), or a direction MuJoCo would replace (:data:`DIRECTIONS`)."""
    for attribute, value in element.attrib.items():
        if attribute not in GEOMETRY_ATTRIBUTES and attribute != "gear":
            continue
        numbers = _numbers(value)
        if numbers is None:
            continue  # not numbers: MuJoCo says what it expected
        try:
            if not all(math.isfinite(x) for x in numbers):
                raise ValueError("expected finite numbers")
            _require_direction(attribute, require_no_underflow(value.split(), numbers))
        except ValueError as exc:
            name = element.get("name")
            key = f"{clipped(element.tag)}[{clipped(name)}]/@{attribute}" if name else f"{clipped(element.tag)}/@{attribute}"
            raise doc.fail(element, key, f"{exc}, got {clipped(value)!r}") from None


def _numbers(value: str) -> list[float] | None:
    """The numbers of an attribute as MuJoCo reads them (decimal or hexadecimal; too large is ``inf``), ``None`` if it is not numbers.

    Examples
    --------
    >>> _numbers("1 0x1p3 -2e500"), _numbers("a b")
    ([1.0, 8.0, -inf], None)
    """
    out = []
    for token in value.split():
        try:
            out.append(float(token))
            continue
        except ValueError:
            if not _HEX.match(token):
                return None
        try:
            out.append(float.fromhex(token))
        except OverflowError:
            out.append(-math.inf if token.startswith("-") else math.inf)
        except ValueError:
            return None
    return out


def _require_direction(attribute: str, numbers: list[float]) -> list[float]:
    """``numbers`` when MuJoCo uses the direction they write as written (or refuses it itself); else a ``ValueError`` saying what MuJoCo would silently use instead.

    Examples
    --------
    >>> _require_direction("quat", [1e153, 1e153, 0, 0])
    [1e+153, 1e+153, 0, 0]
    >>> _require_direction("axis", [1e154, 1e154, 0])
    Traceback (most recent call last):
    ValueError: the sum of its squares overflows in double precision: MuJoCo would silently use a zero axis instead; expected smaller numbers (only the direction counts)
    >>> _require_direction("quat", [1e-8, 1e-8, 0, 0])
    Traceback (most recent call last):
    ValueError: the sum of its squares, 2e-16, is below MuJoCo's 1e-14: MuJoCo would leave it unnormalized and silently use another rotation; expected larger numbers (only the direction counts)
    >>> _require_direction("quat", [1e200, 0, 0, 0])  # MuJoCo's zero quaternion is no rotation, as written
    [1e+200, 0, 0, 0]
    """
    sizes = {"quat": 4, "axisangle": 4, "zaxis": 3, "axis": 3, "fromto": 6, "relpose": 7}
    if attribute not in DIRECTIONS or len(numbers) != sizes[attribute]:
        return numbers  # MuJoCo says how many numbers it expected
    quaternion = attribute in ("quat", "relpose")
    vector = {"axisangle": numbers[:3], "relpose": numbers[3:],
              "fromto": [a - b for a, b in zip(numbers[:3], numbers[3:])]}.get(attribute, numbers)  # fromto: from - to, as MuJoCo
    squares = 0.0
    for x in vector:  # summed in MuJoCo's order, so that it overflows or underflows where MuJoCo's does
        squares += x * x
    if squares == math.inf and not _overflow_harmless(attribute, numbers, vector):
        raise ValueError(f"the sum of its squares overflows in double precision: MuJoCo would silently use {DIRECTIONS[attribute]} instead; "
                         "expected smaller numbers (only the direction counts)")
    if quaternion and squares < MUJOCO_EPS and any(vector) and not _no_rotation(vector):  # all zero: MuJoCo's own error, or (relpose) the pose at qpos0
        size = f"{squares:.3g}" if squares else "0 (the squares underflow)"
        raise ValueError(f"the sum of its squares, {size}, is below MuJoCo's {MUJOCO_EPS:g}: MuJoCo would leave it unnormalized and "
                         "silently use another rotation; expected larger numbers (only the direction counts)")
    return numbers


def _overflow_harmless(attribute: str, numbers: list[float], vector: list[float]) -> bool:
    """Whether what MuJoCo uses for a direction whose sum of squares overflows is what was written.

    Dividing by the infinite norm leaves signed zeros: a zero quaternion is no
    rotation, an ``axisangle`` turns by nothing, a zero ``zaxis`` (``fromto``)
    becomes +z or -z.  A zero joint axis or weld quaternion never is.
    """
    if attribute == "quat":
        return _no_rotation(vector)
    if attribute == "axisangle":
        return numbers[3] == 0.0
    if attribute in ("zaxis", "fromto") and all(math.isfinite(x) for x in vector):
        used = (0.0, 0.0, math.copysign(1.0, vector[2]))
        return math.dist(_unit(vector), used) <= sys.float_info.epsilon
    return False


def _no_rotation(quaternion: list[float]) -> bool:
    """Whether a (finite, non-zero) quaternion is no rotation to double precision, whatever its size."""
    unit = _unit(quaternion)
    return math.hypot(*unit[1:]) <= sys.float_info.epsilon


def _unit(vector: list[float]) -> list[float]:
    """A finite, non-zero vector made of length 1, without overflow or underflow (scaled by its largest number first)."""
    largest = max(abs(x) for x in vector)
    scaled = [x / largest for x in vector]
    length = math.hypot(*scaled)
    return [x / length for x in scaled]


def _negative(token: str) -> bool:
    """Whether a token of a ``count`` is a negative integer (as MuJoCo reads it: ``-1``, ``-01``)."""
    try:
        return int(token) < 0
    except ValueError:
        return False


def _asset_points(element: Element) -> tuple[int, str] | None:
    """How many points MuJoCo makes for a height field (``nrow`` x ``ncol``) or a builtin mesh as it reads it, and how it was counted.

    ``None`` for anything else (a height field from a file, which MuJoCo reads
    only when compiling; numbers MuJoCo refuses itself).

    Examples
    --------
    >>> from xml.etree.ElementTree import Element
    >>> _asset_points(Element("hfield", nrow="20000", ncol="20000"))
    (400000000, 'nrow x ncol = 20000 x 20000')
    >>> _asset_points(Element("mesh", builtin="wedge", params="300 200 90 45 0.5"))
    (60000, 'builtin wedge, resolutions 300 x 200 (params)')
    >>> _asset_points(Element("mesh", file="arm.stl")) is None
    True
    """
    if element.tag == "hfield":
        try:
            rows, columns = int(element.get("nrow", "0")), int(element.get("ncol", "0"))
        except ValueError:
            return None
        if rows <= 0 or columns <= 0:
            return None
        return rows * columns, f"nrow x ncol = {rows} x {columns}"
    builtin = (element.get("builtin") or "").strip()
    if builtin not in _RESOLUTIONS:
        return None
    numbers = _numbers(element.get("params", ""))
    count, power = _RESOLUTIONS[builtin]
    if not numbers:
        return None
    resolutions = [max(0, int(x)) if math.isfinite(x) else 0 for x in numbers[:count]]  # MuJoCo casts them to int
    points = math.prod(resolutions) ** power
    shown = " x ".join(str(r) for r in resolutions) + (" squared" if power == 2 else "")
    return points, f"builtin {builtin}, resolution{'s' if len(resolutions) > 1 else ''} {shown} (params)"


def _made_by(root: Element) -> tuple[int, int]:
    """The elements and the joints of a ``<model>`` file, each ``<replicate>``'s copies multiplied: what one ``<attach>`` of it makes.

    Examples
    --------
    >>> from xml.etree.ElementTree import fromstring
    >>> _made_by(fromstring('<mujoco><worldbody><replicate count="40 10"><body><joint/></body></replicate></worldbody></mujoco>'))
    (803, 400)
    """
    elements = joints = 0
    stack = [(root, 1)]
    while stack:
        element, multiplier = stack.pop()
        elements += multiplier
        joints += multiplier if element.tag in ("joint", "freejoint") else 0
        if element.tag == "replicate":
            factors = _counts(element.get("count", ""))
            multiplier *= max(1, math.prod(factors)) if factors else 1
        stack.extend((child, multiplier) for child in element)
    return elements, joints


def _counts(text: str) -> list[int]:
    """The integers of a ``count`` attribute (none if it is not integers: MuJoCo then refuses it)."""
    try:
        values = [int(token) for token in text.split()]
    except ValueError:
        return []
    return [v for v in values if v > 0] if all(v >= 0 for v in values) else []

