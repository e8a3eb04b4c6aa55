"""YAML documents with the line of every key, read within bounded time and memory.

:func:`parse_yaml` returns plain data and a :class:`Positions` table from key
paths to 1-based lines.  The document is built from the parser's events (libyaml's, or PyYAML's own), in one loop
with an explicit stack, every bound of :class:`~mobility.io.limits.Limits` checked as the nodes arrive (an alias bomb
stops, although values are shared as PyYAML shares them).  What is refused: ``docs/file-format.md`` (Strictness);
keys are kept as written (``on:`` is ``"on"``, not ``True``).

Examples
--------
>>> data, pos = parse_yaml("name: x\\njoints:\\n  - {name: A}\\n", "m.yaml")
>>> data["joints"][0]["name"], pos.line(("joints", 0, "name"))
('A', 3)
>>> parse_yaml("a: &x [1, 2]\\nb: [*x, *x]\\n", "m.yaml")[0]
{'a': [1, 2], 'b': [[1, 2], [1, 2]]}
>>> parse_yaml("a: !vec [0, 0, 1]\\n", "m.yaml")
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: m.yaml:1: a: unsupported YAML tag '!vec'; mechanism files use plain YAML (no tags)
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

import yaml

from ..errors import TERMINAL_CONTROL, MechanismFileError, RequestError, clipped, control_character_problem
from .expressions import require_literal
from .files import read_capped
from .limits import Limits, current_limits

try:  # libyaml's parser, in C, about 14 times faster than the pure-Python one
    from yaml import CSafeLoader as _EventSource
except ImportError:  # pragma: no cover - PyPI's wheels of pyyaml ship libyaml
    from yaml import SafeLoader as _EventSource  # type: ignore[assignment]

_RESOLVER = yaml.resolver.Resolver()
"""The implicit tags of YAML 1.1 plain scalars, as PyYAML's safe loader resolves them."""

__all__ = ["KeyPath", "Positions", "format_key", "parse_yaml", "read_text"]

KeyPath = tuple[str | int, ...]

_TAG = "tag:yaml.org,2002:"
_STR, _MAP, _SEQ, _INT = _TAG + "str", _TAG + "map", _TAG + "seq", _TAG + "int"
_SCALAR_TAGS = {_STR, _TAG + "int", _TAG + "float", _TAG + "bool", _TAG + "null"}
"""Tags a scalar may carry explicitly (``!!int 3``); any other tag is an error."""
_KIND = {_TAG + "int": "an integer", _TAG + "float": "a number", _TAG + "bool": "true or false", _TAG + "timestamp": "a date", _TAG + "null": "null"}

# Characters YAML does not allow in a stream (the complement of its printable set).
_NOT_PRINTABLE = re.compile("[^\t\n\r\x20-\x7e\x85\xa0-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def format_key(path: KeyPath) -> str:
    """Write a key path as ``joints[3].axis``.

    Examples
    --------
    >>> format_key(("joints", 3, "axis"))
    'joints[3].axis'
    """
    out = ""
    for part in path:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += f".{part}" if out else str(part)
    return out


@dataclass
class Positions:
    """Line numbers of the nodes of a YAML document, by key path (the content reached through an alias: the alias's line)."""

    lines: dict[KeyPath, int] = field(default_factory=dict)

    def line(self, path: KeyPath) -> int | None:
        """Line of ``path``, or of its nearest ancestor that has one."""
        path = tuple(path)
        while path and path not in self.lines:
            path = path[:-1]
        return self.lines.get(path)


def read_text(path: str | Path, limits: Limits | None = None) -> str:
    """The text of a document file, read with the size cap of ``limits`` (:func:`read_capped`), refused if not UTF-8."""
    raw = read_capped(path, limits)
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw.count(b"\n", 0, exc.start) + 1
        raise MechanismFileError("", f"not UTF-8 text (byte 0x{raw[exc.start]:02x})", file=str(path), line=line) from None


def parse_yaml(text: str, file: str = "<string>", limits: Limits | None = None) -> tuple[Any, Positions]:
    """Parse one YAML document into ``(data, positions)``, keeping the line of every key (``data`` is ``None`` for an empty document).

    Raises
    ------
    MechanismFileError
        On a YAML syntax error (with its line), a limit passed, or any
        construct the format refuses (see the module docstring).
    """
    if not isinstance(text, str):
        raise RequestError(caller="parse_yaml", expected="the text of a document (str)", got=type(text).__name__)
    lim = current_limits(limits)
    if len(text) > lim.max_file_bytes:
        raise MechanismFileError("", f"a document of {len(text)} characters is larger than the limit of {lim.max_file_bytes} (set MOBILITY_MAX_FILE_BYTES to raise it)", file=file)
    bad = _NOT_PRINTABLE.search(text) or TERMINAL_CONTROL.search(text)
    if bad is not None:
        line = text.count("\n", 0, bad.start()) + 1
        raise MechanismFileError("", control_character_problem(bad.group(), "YAML", also=_NOT_PRINTABLE) or "", file=file, line=line)
    try:
        return _events_built(_EventSource, text, file, lim)
    except yaml.MarkedYAMLError as exc:
        if exc.problem != _LIBYAML_NESTING or _EventSource is yaml.SafeLoader:
            raise _syntax_error(exc, file) from None
    # libyaml (from PyYAML 6.0.4) refuses 1,000 open brackets while it reads ahead, before the first of them
    # reaches the builder: the pure-Python parser reads the same events without that bound, so that the
    # builder's own depth limit (MOBILITY_MAX_DEPTH) decides, naming the key and the line as for any limit.
    try:
        return _events_built(yaml.SafeLoader, text, file, lim)
    except yaml.MarkedYAMLError as exc:
        raise _syntax_error(exc, file) from None


YAML_DEPTH_BOUND = 1000
"""The most levels a YAML document may nest, whatever :attr:`Limits.max_depth` says: PyYAML's pure-Python reader spends
time growing with the square of the depth (50,000 deep: past 90 s at 3 GB); at this bound, about a second."""

_LIBYAML_NESTING = "exceeded maximum nesting depth"
"""libyaml's problem when more than its 1,000 flow collections are open at once."""


def _events_built(source: Any, text: str, file: str, limits: Limits) -> tuple[Any, Positions]:
    """The document of ``text`` read from the events of the parser class ``source`` (libyaml's, or PyYAML's in Python)."""
    loader = source(text)
    try:
        return _Builder(loader, file, limits).document()
    except yaml.MarkedYAMLError:
        raise
    except yaml.YAMLError as exc:
        raise MechanismFileError("", f"YAML error: {' '.join(str(exc).split())}", file=file) from None
    finally:
        loader.dispose()


def _syntax_error(exc: yaml.MarkedYAMLError, file: str) -> MechanismFileError:
    """The one-line error of a YAML syntax error, at its line."""
    mark = exc.problem_mark or exc.context_mark
    mark_line = mark.line + 1 if mark is not None else None
    what = exc.problem or exc.context or "syntax error"
    return MechanismFileError("", f"YAML syntax error: {what}", file=file, line=mark_line)


def _add_to(frame: list[Any], value: Any, size: int) -> None:
    """Put a finished node into the collection of ``frame`` (a stack frame of :meth:`_Builder.node_tree`), counting its nodes."""
    frame[2] += size
    if frame[5]:  # a mapping: the value of the pending key
        frame[0][frame[4]] = value
        frame[4] = None
    else:
        frame[0].append(value)


class _Builder:
    """Builds the values and the positions of one document from its events (one loop, an explicit stack)."""

    def __init__(self, loader: Any, file: str, limits: Limits) -> None:
        self.loader = loader
        self.file = file
        self.limits = limits
        self.lines: dict[KeyPath, int] = {}
        self.anchors: dict[str, tuple[Any, int]] = {}  # anchor -> (value, nodes once expanded)

    def fail(self, path: KeyPath, line: int, message: str) -> MechanismFileError:
        return MechanismFileError(format_key(path), message, file=self.file, line=line)

    def document(self) -> tuple[Any, Positions]:
        get_event = self.loader.get_event
        get_event()  # StreamStartEvent
        event = get_event()
        if isinstance(event, yaml.StreamEndEvent):
            return None, Positions(self.lines)
        value = self.node_tree(get_event)
        get_event()  # DocumentEndEvent
        event = get_event()
        if not isinstance(event, yaml.StreamEndEvent):
            raise self.fail((), event.start_mark.line + 1, "expected one YAML document, found a second one (a line '---')")
        return value, Positions(self.lines)

    def node_tree(self, get_event: Any) -> Any:
        """The value of the document's root node; events are read up to its end."""
        lines = self.lines
        max_depth, max_nodes = min(self.limits.max_depth, YAML_DEPTH_BOUND), self.limits.max_nodes
        anchors = self.anchors
        # One frame per open collection: [container, path, nodes so far, anchor, pending key (None: expecting a key), is mapping]
        stack: list[list[Any]] = []
        nodes = 0
        while True:
            event = get_event()
            cls = type(event)
            if cls is yaml.MappingEndEvent or cls is yaml.SequenceEndEvent:
                container, path, size, anchor, _, _ = stack.pop()
                if anchor is not None:
                    anchors[anchor] = (container, size)
                if not stack:
                    return container
                _add_to(stack[-1], container, size)
                continue
            line = event.start_mark.line + 1
            if stack:
                parent = stack[-1]
                if parent[5]:
                    if parent[4] is None:  # this node is a key
                        parent[4] = self.key(event, parent, line)
                        parent[2] += 1
                        nodes += 1
                        continue
                    path = parent[1] + (parent[4],)
                else:
                    path = parent[1] + (len(parent[0]),)
                    lines[path] = line
            else:
                parent = None
                path = ()
                lines[path] = line
            if cls is yaml.ScalarEvent:
                value, size = self.scalar(event, path, line), 1
            elif cls is yaml.AliasEvent:
                if event.anchor not in anchors:
                    open_anchor = any(frame[3] == event.anchor for frame in stack)
                    raise self.fail(path, line, f"recursive alias *{event.anchor} (it refers to a node that contains it)" if open_anchor else f"undefined alias *{event.anchor}")
                value, size = anchors[event.anchor]
            else:  # a mapping or a sequence starts
                is_mapping = cls is yaml.MappingStartEvent
                if event.tag not in (None, "!", _MAP if is_mapping else _SEQ):
                    raise self.fail(path, line, _unsupported_tag(event.tag))
                if len(stack) >= max_depth:
                    how = ("set MOBILITY_MAX_DEPTH to raise it" if max_depth == self.limits.max_depth else
                           "the most a YAML document may nest whatever MOBILITY_MAX_DEPTH says: the reader's time grows with the square of the depth")
                    raise MechanismFileError(format_key(path[:3]) + "...", f"nested deeper than the limit of {max_depth} levels ({how})", file=self.file, line=line)
                nodes += 1
                stack.append([{} if is_mapping else [], path, 1, event.anchor, None, is_mapping])
                continue
            nodes += size
            if nodes > max_nodes:
                raise self.fail(path, line, f"the document has more than the limit of {max_nodes} YAML nodes, aliases expanded (set MOBILITY_MAX_NODES to raise it)")
            if event.anchor is not None:
                anchors[event.anchor] = (value, size)
            if parent is None:
                return value
            _add_to(parent, value, size)

    def key(self, event: Any, frame: list[Any], line: int) -> str:
        """The text of a mapping key, checked: a plain scalar, not ``<<``, not already in the mapping."""
        path = frame[1]
        if type(event) is not yaml.ScalarEvent:
            what = "an alias" if type(event) is yaml.AliasEvent else "a collection"
            raise self.fail(path, line, f"mapping keys must be plain names, got {what}")
        if event.tag not in (None, "!") and event.tag not in _SCALAR_TAGS:
            raise self.fail(path, line, _unsupported_tag(event.tag))
        key = event.value
        if event.style == '"':
            self.require_printable(key, path, line)
        if key == "<<" and event.implicit[0]:
            raise self.fail(path + (key,), line, "YAML merge keys (<<) are not supported; write the keys out")
        if key in frame[0]:
            raise self.fail(path + (key,), line, "duplicate key")
        self.lines[path + (key,)] = line
        if event.anchor is not None:
            self.anchors[event.anchor] = (key, 1)
        return key

    def scalar(self, event: Any, path: KeyPath, line: int) -> Any:
        """The value of a scalar: resolved as PyYAML's safe loader does, with every failure an error at its key."""
        value, tag = event.value, event.tag
        if event.style == '"':  # an escape (backslash-e, backslash-x1b) makes what the stream did not hold
            self.require_printable(value, path, line)
        if tag is None or tag == "!":
            if not event.implicit[0]:  # quoted, or tagged '!': a string
                return value
            tag = _resolve_plain(value)
            if tag == _STR:
                return value
            if tag == _INT and value.isdigit() and (value[0] != "0" or value == "0"):  # the common case, decimal
                return int(value) if len(value) < 1000 else self.scalar_by_constructor(tag, event, path, line)
        elif tag not in _SCALAR_TAGS:
            raise self.fail(path, line, _unsupported_tag(tag))
        if tag == _STR:
            return value
        ambiguous = _yaml11_only_number(tag, value)
        if ambiguous:
            raise self.fail(path, line, ambiguous)
        return self.scalar_by_constructor(tag, event, path, line)

    def require_printable(self, text: str, path: KeyPath, line: int) -> None:
        """A string written with escapes must still hold no control character (an ESC would reach the terminal)."""
        problem = control_character_problem(text, "a value", also=_NOT_PRINTABLE)
        if problem is not None:
            raise self.fail(path, line, problem)

    def scalar_by_constructor(self, tag: str, event: Any, path: KeyPath, line: int) -> Any:
        value = event.value
        construct = self.loader.yaml_constructors.get(tag)
        if construct is None:  # tags of the resolver with no value of their own ('=' and '<<' as values)
            return value
        try:
            result = construct(self.loader, yaml.ScalarNode(tag, value, event.start_mark, event.end_mark))
        except (ValueError, TypeError, AttributeError, OverflowError, KeyError):
            raise self.fail(path, line, f"cannot read {clipped(value)!r} as {_KIND.get(tag, tag)}") from None
        if type(result) is float and (result == 0.0 or math.isinf(result)):
            try:  # 1e-400 would read as 0.0, 1e400 as inf: as the expressions refuse it
                require_literal(value, result)
            except ValueError as exc:
                raise self.fail(path, line, str(exc)) from None
        return result


@lru_cache(maxsize=4096)
def _resolve_plain(value: str) -> str:
    """The tag PyYAML's safe loader gives a plain scalar (``'3'`` -> int, ``'yes'`` -> bool, else str)."""
    return _RESOLVER.resolve(yaml.ScalarNode, value, (True, False))


_OCTAL = re.compile(r"[-+]?0[0-7_]+")
_SEXAGESIMAL = re.compile(r"[-+]?[0-9][0-9_]*(?::[0-5]?[0-9])+(?:\.[0-9_]*)?")


def _yaml11_only_number(tag: str, value: str) -> str | None:
    """Why ``value`` is refused as a number, when YAML 1.1 (PyYAML: ``010`` is 8, ``1:30`` is 90) and YAML 1.2 read it differently.

    Examples
    --------
    >>> _yaml11_only_number(_INT, "010")
    "'010' reads as octal 8 in YAML 1.1 but as 10 in YAML 1.2; write 10 or 8, without the leading zero"
    >>> _yaml11_only_number(_INT, "10") is None
    True
    """
    body = value.strip()
    if tag == _INT and _OCTAL.fullmatch(body):
        digits = body.lstrip("+-").replace("_", "")
        if int(digits, 8) == int(digits):  # 07, 00: the same number either way
            return None
        sign = "-" if body.startswith("-") else ""
        octal, decimal = f"{sign}{int(digits, 8)}", f"{sign}{int(digits)}"
        return f"{body!r} reads as octal {octal} in YAML 1.1 but as {decimal} in YAML 1.2; write {decimal} or {octal}, without the leading zero"
    if tag in (_INT, _TAG + "float") and _SEXAGESIMAL.fullmatch(body):
        return f"{body!r} reads as a base-60 number in YAML 1.1 but as text in YAML 1.2; write a plain decimal number"
    return None


def _unsupported_tag(tag: str) -> str:
    shown = "!!" + tag[len(_TAG):] if tag.startswith(_TAG) else tag
    return f"unsupported YAML tag {shown!r}; mechanism files use plain YAML (no tags)"
