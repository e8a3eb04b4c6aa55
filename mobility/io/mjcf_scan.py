"""An MJCF file, and every file it includes, checked before MuJoCo reads them.

MuJoCo opens the files an MJCF model names (``<include file>``, ``<model
file>``) and expands ``<replicate>``, ``<flexcomp>`` and ``<composite>``
itself, with no bound: a named pipe makes it wait for ever, a huge file or
``count="1000000"`` costs minutes and gigabytes before any joint can be
counted.  :func:`scan_mjcf` walks the parsed file first (our own XML pass,
:mod:`mobility.io.xml_source`) and refuses, in one line naming the file and
the line of the element:

* an ``<include>`` whose file is missing, not a regular file (a pipe, a
  directory, a device), included already, nested deeper than the depth
  limit, or larger than what remains of the size limit (the model and the
  files it includes are one document); a ``<model>`` asset file likewise
  when it exists;
* more joints than the joint limit, more elements than the element limit,
  or more elements made by the ``count`` of ``<replicate>``, ``<flexcomp>``
  and ``<composite>`` than the joint limit, every copy counted (nested
  replicates multiply), included files counted (see
  :mod:`mobility.io.limits`);
* a geometric attribute (``pos``, ``quat``, ``axis``, ``euler``, ...) that
  holds ``nan`` or ``inf``.

Files are found as MuJoCo finds them: relative to the directory of the model
file first, then to the directory of the file that includes them.

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
"""

from __future__ import annotations

import math
import os
import stat
from dataclasses import dataclass, field
from pathlib import Path
from xml.etree.ElementTree import Element

from ..errors import MechanismFileError, clipped
from .files import read_capped, refuse_pipe
from .limits import Limits, current_limits
from .xml_source import XmlDocument, parse_xml

__all__ = ["scan_mjcf", "MjcfScan", "GEOMETRY_ATTRIBUTES"]

GEOMETRY_ATTRIBUTES = frozenset({
    "pos", "quat", "axisangle", "euler", "xyaxes", "zaxis", "axis", "anchor", "ref", "springref",
    "fromto", "size", "offset", "relpose", "polycoef", "spacing",
})
"""MJCF attributes that place bodies and joints: a ``nan`` or ``inf`` in one is refused at its line.

Others (``range="-inf inf"`` is common) are left to MuJoCo."""

_COUNTED = {"replicate", "flexcomp", "composite"}


@dataclass(frozen=True)
class MjcfScan:
    """What the scan found: every ``<include>`` (the including file and the line) and the counts, copies included."""

    includes: tuple[tuple[str, int | None], ...] = ()
    elements: int = 0
    joints: int = 0
    copies: int = 0


@dataclass
class _Over:
    """The first element where a count passed its limit."""

    doc: XmlDocument
    element: Element
    factors: tuple[int, ...]


@dataclass
class _Context:
    """Where an element sits: its document, the product of the counts around it, whether it is in the world."""

    doc: XmlDocument
    multiplier: int = 1
    factors: tuple[int, ...] = ()
    in_world: bool = False
    chain: tuple[str, ...] = ()
    source: tuple[XmlDocument, Element] | None = None  # the innermost <replicate>, where its copies are refused


@dataclass
class _Scanner:
    model_dir: str
    limits: Limits
    used_bytes: int
    seen: dict[str, str] = field(default_factory=dict)
    includes: list[tuple[str, int | None]] = field(default_factory=list)
    counts: dict[str, int] = field(default_factory=lambda: {"elements": 0, "joints": 0, "copies": 0})
    over: dict[str, _Over] = field(default_factory=dict)

    def walk(self, root: Element, context: _Context) -> None:
        """Every element under ``root`` (iteratively: a deep file must not exhaust Python's stack)."""
        stack = [(child, context) for child in reversed(list(root))]
        while stack:
            element, where = stack.pop()
            children = self.visit(element, where)
            stack.extend(reversed(children))

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
        if tag == "include":
            return self.included(element, where, "include")
        if tag == "model" and element.get("file"):
            return self.included(element, where, "model")
        inner = where
        if tag in _COUNTED:
            inner = self.counted(element, where)
        elif tag in ("worldbody", "default"):
            inner = _Context(where.doc, where.multiplier, where.factors, tag == "worldbody", where.chain, where.source)
        return [(child, inner) for child in element]

    def count(self, what: str, amount: int, element: Element, where: _Context, doc: XmlDocument | None = None) -> None:
        """Add ``amount`` to the count ``what``; remember the element where it first passes its limit."""
        self.counts[what] += amount
        limit = self.limits.max_elements if what == "elements" else self.limits.max_joints
        if self.counts[what] > limit and what not in self.over:
            self.over[what] = _Over(doc or where.doc, element, where.factors)

    def counted(self, element: Element, where: _Context) -> _Context:
        """The context inside a ``<replicate>`` (its copies multiply), or the points of a ``<flexcomp>``/``<composite>``."""
        factors = _counts(element.get("count", ""))
        total = math.prod(factors) if factors else 1
        if element.tag != "replicate":
            self.count("copies", total * where.multiplier, element, where)
            self.count("elements", total * where.multiplier, element, where)
            return where
        return _Context(where.doc, where.multiplier * total, where.factors + tuple(factors), where.in_world, where.chain, (where.doc, element))

    def included(self, element: Element, where: _Context, kind: str) -> list[tuple[Element, _Context]]:
        """Check the file of an ``<include>`` or ``<model>``; its elements, to visit in place of the element."""
        doc = where.doc
        name = element.get("file", "")
        path = self.resolve(name, doc.file)
        fail = _failing(doc, element, kind, name)
        if path is None:
            if kind == "model":
                return []  # MuJoCo says the asset is missing
            raise fail(f"no such file (looked in {_dirs(self.model_dir, doc.file)}); expected a file to include")
        self.check_file(path, fail, kind)
        real = os.path.realpath(path)
        if real in where.chain or (kind == "include" and real in self.seen):
            first = self.seen.get(real) or "the model file itself"
            raise fail(f"included already ({first}); expected each file included once, as MuJoCo requires")
        if len(where.chain) >= self.limits.max_depth:
            raise fail(f"included at a depth of more than the limit of {self.limits.max_depth} ({self.limits.hint('max_depth')})")
        if kind == "include":
            self.seen[real] = f"{doc.file}:{doc.line(element)}"
            self.includes.append((doc.file, doc.line(element)))
        inner = parse_xml(read_capped(path, self.limits), os.path.normpath(path))
        context = _Context(inner, where.multiplier, where.factors, where.in_world and kind == "include", where.chain + (real,), where.source)
        return [(child, context) for child in inner.root]

    def resolve(self, name: str, including: str) -> str | None:
        """The path MuJoCo opens for ``name``: in the model's directory, else in the including file's; ``None`` if neither exists."""
        if not name:
            return None
        for folder in (self.model_dir, os.path.dirname(including) or "."):
            candidate = os.path.join(folder, name)
            if os.path.lexists(candidate):
                return candidate
        return None

    def check_file(self, path: str, fail, kind: str) -> None:
        """A regular file, within what remains of the size limit."""
        try:
            mode = refuse_pipe(path)
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
        over = self.over[what]
        limit_name = "max_elements" if what == "elements" else "max_joints"
        limit = getattr(self.limits, limit_name)
        noun = {"elements": "elements", "joints": "joints", "copies": "elements made by the count of <replicate>, <flexcomp> and <composite>"}[what]
        details = ["included files and copies counted"] if what == "elements" else []
        details += [f"count of <replicate> {' x '.join(map(str, over.factors))}"] if over.factors else []
        detail = f" ({'; '.join(details)})" if details else ""
        raise over.doc.fail(over.element, clipped(over.element.tag),
                            f"{self.counts[what]} {noun}{detail} are more than the limit of {limit} ({self.limits.hint(limit_name)})")


def scan_mjcf(doc: XmlDocument, model_dir: str | Path, limits: Limits | None = None, *, size: int = 0) -> MjcfScan:
    """Check an MJCF document and the files it includes (see the module docstring).

    Parameters
    ----------
    doc : XmlDocument
        The parsed model file.
    model_dir : str or Path
        The directory MuJoCo finds included files in (the model file's; the
        working directory when MuJoCo is given the text).
    limits : Limits, optional
    size : int
        Bytes of the model file, counted against the size limit with the
        files it includes.

    Returns
    -------
    MjcfScan

    Raises
    ------
    MechanismFileError
        One line naming the file (the including one for a bad include), the
        line of the element and the limit or the value.
    """
    scanner = _Scanner(str(model_dir) or ".", current_limits(limits), size)
    scanner.seen[os.path.realpath(doc.file)] = "the model file itself"
    scanner.walk(doc.root, _Context(doc, chain=(os.path.realpath(doc.file),)))
    scanner.raise_first_over()
    return MjcfScan(tuple(scanner.includes), scanner.counts["elements"], scanner.counts["joints"], scanner.counts["copies"])


def _check_numbers(doc: XmlDocument, element: Element) -> None:
    """Refuse a geometric attribute holding ``nan`` or ``inf`` (``1e400`` reads as ``inf``)."""
    for attribute, value in element.attrib.items():
        if attribute not in GEOMETRY_ATTRIBUTES:
            continue
        try:
            numbers = [float(token) for token in value.split()]
        except ValueError:
            continue  # not numbers: MuJoCo says what it expected
        if not all(math.isfinite(x) for x in numbers):
            name = element.get("name")
            key = f"{clipped(element.tag)}[{clipped(name)}]/@{attribute}" if name else f"{clipped(element.tag)}/@{attribute}"
            raise doc.fail(element, key, f"expected finite numbers, got {clipped(value)!r}")


def _counts(text: str) -> list[int]:
    """The integers of a ``count`` attribute (none if it is not integers: MuJoCo then refuses it)."""
    try:
        values = [int(token) for token in text.split()]
    except ValueError:
        return []
    return [v for v in values if v > 0] if all(v >= 0 for v in values) else []


def _failing(doc: XmlDocument, element: Element, kind: str, name: str):
    """An error about the file of an ``<include>``/``<model>``, at its line in the including file."""

    def fail(message: str) -> MechanismFileError:
        return doc.fail(element, kind, f"{clipped(name)!r}: {message}" if name else message)

    return fail


def _dirs(model_dir: str, including: str) -> str:
    folders = dict.fromkeys([model_dir, os.path.dirname(including) or "."])
    return " and ".join(repr(clipped(f, 60)) for f in folders)
