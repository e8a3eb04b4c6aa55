"""XML documents with the line of every element, for one-line error messages.

:func:`parse_xml` parses with the standard library (``expat`` feeding an ``ElementTree.TreeBuilder``) and keeps the
line each element starts on; ``mujoco=True`` refuses what MuJoCo's own parser (tinyxml2) reads otherwise (a non-UTF-8
file, a ``<!DOCTYPE>``, a tab in a ``file``: ``docs/robot-files.md``), so that :mod:`mobility.io.mjcf_scan` checks
what MuJoCo opens.

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
from typing import Any
from xml.parsers import expat

from ..errors import MechanismFileError, RequestError, clipped, control_character_problem, name_problem
from .expressions import require_literal
from .files import file_name, is_regular_file, open_regular, read_capped
from .limits import Limits, current_limits

__all__ = ["XmlDocument", "parse_xml", "read_xml", "root_tag", "require_no_underflow"]


_BOM = b"\xef\xbb\xbf"
_UTF16_BOMS = ((b"\xff\xfe", "utf-16-le"), (b"\xfe\xff", "utf-16-be"))
_OTHER_BOMS = ((b"\xff\xfe\x00\x00", "UTF-32"), (b"\x00\x00\xfe\xff", "UTF-32"), (b"\xff\xfe", "UTF-16"), (b"\xfe\xff", "UTF-16"))
_TAG = re.compile(rb"<[^\s/>]+")
_ATTRIBUTE = re.compile(rb"\s+([^\s=/>]+)\s*=\s*(\"[^\"]*\"|'[^']*')")
_XML_SPACE = re.compile(rb"[\t\r\n]")
_NAME_ATTRIBUTES = frozenset({"name", "model"})
"""The attributes that name something (``<joint name>``, ``<mujoco model>``): held to :func:`~mobility.errors.name_problem`."""


@dataclass(frozen=True, eq=False)
class XmlDocument:
    """A parsed XML file: its root element and the line of every element.

    ``lines``: element -> 1-based line where it starts; ``file``: the name used in messages.
    """

    root: ET.Element
    file: str
    lines: dict[ET.Element, int] = field(default_factory=dict)

    def line(self, element: ET.Element | None) -> int | None:
        """The line where ``element`` starts (``None`` if unknown)."""
        return None if element is None else self.lines.get(element)

    def fail(self, element: ET.Element | None, key: str, message: str) -> MechanismFileError:
        """A one-line error about ``element``: ``file:line: key: message`` (a key built from a huge name is cut short)."""
        return MechanismFileError(clipped(key, 120), message, file=self.file, line=self.line(element))


def parse_xml(text: str | bytes, file: str = "<string>", *, mujoco: bool = False) -> XmlDocument:
    """Parse XML text, keeping the line of each element.

    Parameters
    ----------
    mujoco : bool
        Refuse what MuJoCo's parser would read differently (see the module docstring).

    Raises
    ------
    MechanismFileError
        When the text is not well-formed XML (at its line and column), or MuJoCo would read it differently.
    RequestError
        When ``text`` is neither ``str`` nor ``bytes``.

    Examples
    --------
    >>> parse_xml('<!DOCTYPE m [<!ENTITY f "a.xml">]>\\n<mujoco><include file="&f;"/></mujoco>', "m.xml", mujoco=True)
    Traceback (most recent call last):
    ...
    mobility.errors.MechanismFileError: m.xml:1: <!DOCTYPE>: a document type declaration, which MuJoCo skips (it reads '&name;' as written, not the entity); expected MJCF without <!DOCTYPE>
    """
    if not isinstance(text, (str, bytes)):
        raise RequestError(caller="parse_xml", expected="the text of an XML file (str or bytes)", got=type(text).__name__)
    builder = ET.TreeBuilder()
    lines: dict[ET.Element, int] = {}
    parser = expat.ParserCreate()
    parser.buffer_text = True
    source = b""
    if mujoco:
        text, source = _as_utf8(text, file)

    def start(tag: str, attrs: dict[str, str]) -> None:
        for key, value in attrs.items():
            problem = control_character_problem(value, "an attribute")
            if problem is None and key in _NAME_ATTRIBUTES and value.strip():  # a name (of a body, link, joint, the robot): the rule of every name (&#13; is a line break); a blank one is the robot readers' to refuse
                problem = name_problem(value, "a name")
            if problem is not None:  # a character reference (&#x9b;) can make what a terminal obeys
                raise MechanismFileError(f"{clipped(tag)}.{clipped(key)}", problem, file=file, line=parser.CurrentLineNumber)
        if mujoco and "file" in attrs:
            raw = _raw_value(source, parser.CurrentByteIndex, b"file")
            if raw is not None and _XML_SPACE.search(raw):
                raise MechanismFileError(f"{clipped(tag)}/@file", f"{clipped(raw.decode('utf-8', 'replace'))!r}: a tab or a line break, which MuJoCo keeps in the name "
                                         "it opens while XML reads a space; expected a file name without tabs or line breaks",
                                         file=file, line=parser.CurrentLineNumber)
        lines[builder.start(tag, attrs)] = parser.CurrentLineNumber

    def doctype(*_: Any) -> None:
        raise MechanismFileError("<!DOCTYPE>", "a document type declaration, which MuJoCo skips (it reads '&name;' as written, not the entity); "
                                 "expected MJCF without <!DOCTYPE>", file=file, line=parser.CurrentLineNumber)

    parser.StartElementHandler = start
    parser.EndElementHandler = builder.end
    parser.CharacterDataHandler = builder.data
    if mujoco:
        parser.StartDoctypeDeclHandler = doctype
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


def _as_utf8(text: str | bytes, file: str) -> tuple[str, bytes]:
    """The text as MuJoCo reads it (UTF-8, whatever the XML declaration says) and its bytes; text that is not UTF-8 refused.

    Examples
    --------
    >>> _as_utf8("<m/>".encode("utf-16"), "m.xml")
    Traceback (most recent call last):
    ...
    mobility.errors.MechanismFileError: m.xml:1: not UTF-8 text (it starts with a UTF-16 byte order mark); expected a UTF-8 file, the only encoding MuJoCo reads
    """
    if isinstance(text, str):
        return text, text.encode("utf-8", "surrogatepass")
    for bom, name in _OTHER_BOMS:
        if text.startswith(bom):
            raise MechanismFileError("", f"not UTF-8 text (it starts with a {name} byte order mark); expected a UTF-8 file, the only encoding MuJoCo reads",
                                     file=file, line=1)
    try:
        return text.decode("utf-8"), text
    except UnicodeDecodeError as exc:
        line = text.count(b"\n", 0, exc.start) + 1
        raise MechanismFileError("", f"not UTF-8 text (byte 0x{text[exc.start]:02x} is not valid UTF-8 there); "
                                 "expected a UTF-8 file, the only encoding MuJoCo reads", file=file, line=line) from None


def _raw_value(source: bytes, start: int, name: bytes) -> bytes | None:
    """The value of attribute ``name`` as written in the start tag at byte ``start`` of ``source`` (``None`` if not found).

    Examples
    --------
    >>> _raw_value(b'<include  file="a\\tb.xml"/>', 0, b"file")
    b'a\\tb.xml'
    """
    found = _TAG.match(source, start)
    at = found.end() if found else len(source)
    while (attribute := _ATTRIBUTE.match(source, at)) is not None:
        if attribute.group(1) == name:
            return attribute.group(2)[1:-1]
        at = attribute.end()
    return None


def require_no_underflow(words: list[str], values: list[float]) -> list[float]:
    """``values`` (what ``words`` read as) unless a number written non-zero reads as 0 (``1e-400``; ``float`` and MuJoCo's
    ``strtod`` say nothing); else a ``ValueError`` saying which (:func:`~mobility.io.expressions.require_literal`).

    Examples
    --------
    >>> require_no_underflow(["0", "0.0e9", "-0x0p3", "1e-310"], [0.0, 0.0, -0.0, 1e-310])
    [0.0, 0.0, -0.0, 1e-310]
    >>> require_no_underflow(["1", "-1e-400"], [1.0, -0.0])
    Traceback (most recent call last):
    ValueError: the number '-1e-400' underflows: it is below the smallest float (4.94e-324) and would read as -0.0; expected 0 or a larger number
    """
    for word, value in zip(words, values):
        if value == 0.0:
            try:
                require_literal(word, value)
            except ValueError as exc:
                raise ValueError(f"{exc}; expected 0 or a larger number") from None
    return values


def read_xml(path: str | Path) -> XmlDocument:
    """Read and parse an XML file (:func:`~mobility.io.files.read_capped`, then :func:`parse_xml`)."""
    return parse_xml(read_capped(file_name(path, "read_xml")), str(path))


def root_tag(path: str | Path, limits: Limits | None = None) -> str | None:
    """The tag of the first element of an XML file, or ``None`` if it is not XML (or a directory or a device, not opened);
    read in chunks until the first start tag, never beyond the size limit.

    Raises
    ------
    MechanismFileError
        When ``path`` is a named pipe or a socket.
    RequestError
        When ``path`` is not a file name (an ``int`` would be taken for a file descriptor).

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.NamedTemporaryFile("w", suffix=".xml", delete=False) as f:
    ...     _ = f.write('<?xml version="1.0"?>\\n<!-- a comment -->\\n<mujoco model="m"/>')
    >>> root_tag(f.name)
    'mujoco'
    >>> os.unlink(f.name)
    """
    if not is_regular_file(file_name(path, "root_tag")):
        return None
    found: list[str] = []
    parser = expat.ParserCreate()

    def start(tag: str, attrs: dict[str, str]) -> None:
        found.append(tag)
        raise StopIteration  # stop at the first element

    parser.StartElementHandler = start
    cap, size = current_limits(limits).max_file_bytes, 0
    try:
        with open_regular(path) as handle:  # without waiting: /proc/kmsg is a regular file whose reading waits
            while size <= cap:
                chunk = handle.read(min(1 << 16, cap + 1 - size))
                if not chunk or (size == 0 and not _starts_like_xml(chunk)):  # the end, nothing to read without waiting, or not XML
                    break
                size += len(chunk)
                parser.Parse(chunk, False)
    except (OSError, StopIteration, expat.ExpatError, LookupError, ValueError):
        pass
    return found[0] if found else None


def _starts_like_xml(chunk: bytes) -> bool:
    """Whether the first bytes of a file start with ``<`` after a byte order mark (UTF-8 or UTF-16) and white space.

    Examples
    --------
    >>> _starts_like_xml("<mujoco/>".encode("utf-16")), _starts_like_xml(b"name: m")
    (True, False)
    """
    for bom, codec in _UTF16_BOMS:
        if chunk.startswith(bom):
            head = chunk[len(bom):len(bom) + 512]
            return head[: len(head) // 2 * 2].decode(codec, "replace").lstrip().startswith("<")
    return chunk.removeprefix(_BOM).lstrip().startswith(b"<")
