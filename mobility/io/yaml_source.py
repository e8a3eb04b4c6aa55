"""YAML documents with the line of every key, for error messages.

:func:`parse_yaml` returns plain Python data (dicts, lists, scalars) and a
:class:`Positions` table from key paths to 1-based line numbers, so that any
later error about ``joints[3].axis`` can name its line.  Duplicate keys in a
mapping are an error (PyYAML would silently keep the last one).

Examples
--------
>>> data, pos = parse_yaml("name: x\\njoints:\\n  - {name: A}\\n", "m.yaml")
>>> data["joints"][0]["name"], pos.line(("joints", 0, "name"))
('A', 3)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from ..errors import MechanismFileError

__all__ = ["KeyPath", "Positions", "format_key", "parse_yaml", "read_text"]

KeyPath = tuple[str | int, ...]


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
    """Line numbers of the nodes of a YAML document, by key path."""

    lines: dict[KeyPath, int] = field(default_factory=dict)

    def line(self, path: KeyPath) -> int | None:
        """Line of ``path``, or of its nearest ancestor that has one."""
        path = tuple(path)
        while True:
            if path in self.lines:
                return self.lines[path]
            if not path:
                return None
            path = path[:-1]


def _construct(node: yaml.Node, path: KeyPath, pos: Positions, file: str, loader: yaml.SafeLoader) -> Any:
    pos.lines.setdefault(path, node.start_mark.line + 1)
    if isinstance(node, yaml.MappingNode):
        out: dict[Any, Any] = {}
        for key_node, value_node in node.value:
            key = loader.construct_object(key_node, deep=True)
            if not isinstance(key, (str, int, float, bool)):
                raise MechanismFileError(format_key(path), "mapping keys must be plain names", file=file, line=key_node.start_mark.line + 1)
            key = str(key) if not isinstance(key, str) else key
            if key in out:
                raise MechanismFileError(format_key(path + (key,)), "duplicate key", file=file, line=key_node.start_mark.line + 1)
            pos.lines[path + (key,)] = key_node.start_mark.line + 1
            out[key] = _construct(value_node, path + (key,), pos, file, loader)
        return out
    if isinstance(node, yaml.SequenceNode):
        return [_construct(item, path + (i,), pos, file, loader) for i, item in enumerate(node.value)]
    return loader.construct_object(node, deep=True)


def read_text(path: str | Path) -> str:
    """The text of a document file.

    Raises
    ------
    MechanismFileError
        One line naming the file: missing, a directory, or unreadable.
    """
    name = str(path)
    try:
        return Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise MechanismFileError("", "no such file", file=name) from None
    except IsADirectoryError:
        raise MechanismFileError("", "is a directory, expected a mechanism file", file=name) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise MechanismFileError("", f"cannot read: {exc}", file=name) from None


def parse_yaml(text: str, file: str = "<string>") -> tuple[Any, Positions]:
    """Parse one YAML document, keeping the line of every key.

    Raises
    ------
    MechanismFileError
        On a YAML syntax error (with its line), or a duplicate key.
    """
    loader = yaml.SafeLoader(text)
    try:
        node = loader.get_single_node()
        pos = Positions()
        if node is None:
            return None, pos
        return _construct(node, (), pos, file, loader), pos
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark is not None else None
        what = exc.problem or exc.context or "syntax error"
        raise MechanismFileError("", f"YAML syntax error: {what}", file=file, line=line) from None
    except yaml.YAMLError as exc:
        raise MechanismFileError("", f"YAML error: {exc}", file=file) from None
    finally:
        loader.dispose()
