"""XML documents with the line of every element, for one-line error messages.

Robot description files (URDF, MJCF) are XML.  :func:`parse_xml` parses one
with the standard library (``xml.parsers.expat`` feeding an
``xml.etree.ElementTree.TreeBuilder``) and keeps the line on which each
element starts, so that a later error about ``<joint name="knee">`` can name
its line.  Malformed XML is a :class:`~mobility.errors.MechanismFileError`
naming the line and column.

Examples
--------
>>> doc = parse_xml('<robot name="r">\\n  <link name="base"/>\\n</robot>\\n', "r.urdf")
>>> doc.root.tag, doc.line(doc.root.find("link"))
('robot', 2)
>>> parse_xml("<robot>\\n<link>\\n</robot>", "r.urdf")
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: r.urdf:3: malformed XML: mismatched tag (column 3); expected well-formed XML
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from xml.parsers import expat

from ..errors import MechanismFileError
from .files import read_capped

__all__ = ["XmlDocument", "parse_xml", "read_xml", "root_tag"]

_CONTROL = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")
"""Control characters (C0 but tab and line breaks, DEL, C1) and bidirectional overrides."""


@dataclass(frozen=True, eq=False)
class XmlDocument:
    """A parsed XML file: its root element and the line of every element.

    Attributes
    ----------
    root : xml.etree.ElementTree.Element
    file : str
        The file name used in messages.
    lines : dict
        Element -> 1-based line where it starts.
    """

    root: ET.Element
    file: str
    lines: dict[ET.Element, int] = field(default_factory=dict)

    def line(self, element: ET.Element | None) -> int | None:
        """The line where ``element`` starts (``None`` if unknown)."""
        return None if element is None else self.lines.get(element)

    def fail(self, element: ET.Element | None, key: str, message: str) -> MechanismFileError:
        """A one-line error about ``element``: ``file:line: key: message``."""
        return MechanismFileError(key, message, file=self.file, line=self.line(element))


def parse_xml(text: str | bytes, file: str = "<string>") -> XmlDocument:
    """Parse XML text, keeping the line of each element.

    Parameters
    ----------
    text : str or bytes
    file : str
        Name used in error messages.

    Raises
    ------
    MechanismFileError
        When the text is not well-formed XML (the message names line and column).
    """
    builder = ET.TreeBuilder()
    lines: dict[ET.Element, int] = {}
    parser = expat.ParserCreate()
    parser.buffer_text = True

    def start(tag: str, attrs: dict[str, str]) -> None:
        for key, value in attrs.items():
            bad = _CONTROL.search(value)
            if bad is not None:  # a character reference (&#x9b;) can make what a terminal obeys
                raise MechanismFileError(f"{tag}.{key}", f"control character {bad.group()!r} (code {ord(bad.group())}) is not allowed in an attribute", file=file, line=parser.CurrentLineNumber)
        lines[builder.start(tag, attrs)] = parser.CurrentLineNumber

    parser.StartElementHandler = start
    parser.EndElementHandler = builder.end
    parser.CharacterDataHandler = builder.data
    try:
        parser.Parse(text, True)
    except MechanismFileError:
        raise
    except expat.ExpatError as exc:
        reason = expat.ErrorString(exc.code)
        raise MechanismFileError("", f"malformed XML: {reason} (column {exc.offset + 1}); expected well-formed XML", file=file, line=exc.lineno) from None
    except (LookupError, ValueError) as exc:  # an encoding the XML declaration names and Python does not know
        raise MechanismFileError("", f"unreadable XML ({exc}); expected UTF-8 or another known encoding", file=file, line=1) from None
    return XmlDocument(builder.close(), file, lines)


def read_xml(path: str | Path) -> XmlDocument:
    """Read and parse an XML file (see :func:`parse_xml`).

    Raises
    ------
    MechanismFileError
        When the file cannot be read, is larger than the size limit
        (:mod:`mobility.io.limits`) or is not well-formed XML.
    """
    return parse_xml(read_capped(path), str(path))


def root_tag(path: str | Path) -> str | None:
    """The tag of the first element of an XML file, or ``None`` if it is not XML.

    Reads only the start of the file: enough to tell a URDF (``<robot>``) from
    an MJCF (``<mujoco>``) file.

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.NamedTemporaryFile("w", suffix=".xml", delete=False) as f:
    ...     _ = f.write('<?xml version="1.0"?>\\n<!-- a comment -->\\n<mujoco model="m"/>')
    >>> root_tag(f.name)
    'mujoco'
    >>> os.unlink(f.name)
    """
    try:
        with open(path, "rb") as handle:
            head = handle.read(65536)
    except OSError:
        return None
    if not head.lstrip().startswith(b"<"):
        return None
    found: list[str] = []
    parser = expat.ParserCreate()

    def start(tag: str, attrs: dict[str, str]) -> None:
        found.append(tag)
        raise StopIteration  # stop at the first element

    parser.StartElementHandler = start
    try:
        parser.Parse(head, False)
    except (StopIteration, expat.ExpatError, LookupError, ValueError):
        pass
    return found[0] if found else None
