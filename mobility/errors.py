"""The error hierarchy.

Every error the package raises on purpose derives from :class:`MobilityError`.
Errors about a mechanism description are also :class:`ValueError`, and carry
where the problem is (file, line, key path) and what was expected, so the
command line can print one line and exit with status 2.

Examples
--------
>>> err = MechanismFileError("joints[2].axis", "expected 3 numbers, got 2",
...                          file="arm.yaml", line=7)
>>> str(err)
'arm.yaml:7: joints[2].axis: expected 3 numbers, got 2'
>>> isinstance(err, ValueError)
True
"""

from __future__ import annotations

__all__ = [
    "MobilityError",
    "MechanismError",
    "MechanismFileError",
    "AnalysisError",
]


class MobilityError(Exception):
    """Base class of every error raised on purpose by :mod:`mobility`."""


class MechanismError(MobilityError, ValueError):
    """A mechanism description is invalid.

    Parameters
    ----------
    key : str
        Path of the offending entry, e.g. ``"joints[3].axis"``; empty for the
        whole document.
    message : str
        What is wrong and what was expected.
    """

    def __init__(self, key: str, message: str) -> None:
        self.key = key
        self.message = message
        super().__init__(self._format())

    def _format(self) -> str:
        return f"{self.key}: {self.message}" if self.key else self.message

    def with_key_prefix(self, prefix: str) -> "MechanismError":
        """Return the same error with ``prefix`` put in front of its key."""
        if not prefix:
            return self
        key = f"{prefix}.{self.key}" if self.key and not self.key.startswith("[") else f"{prefix}{self.key}"
        return type(self)(key, self.message)


class MechanismFileError(MechanismError):
    """A mechanism file is invalid; the message names file, line and key.

    Parameters
    ----------
    key : str
        Key path inside the document (``"joints[3].axis"``).
    message : str
        What is wrong and what was expected.
    file : str
        Path of the file as the user gave it.
    line : int or None
        1-based line number, when known.
    """

    def __init__(self, key: str, message: str, *, file: str = "<string>", line: int | None = None) -> None:
        self.file = file
        self.line = line
        super().__init__(key, message)

    def _format(self) -> str:
        where = f"{self.file}:{self.line}" if self.line is not None else self.file
        return f"{where}: {super()._format()}"


class AnalysisError(MobilityError):
    """An analysis could not be carried out (e.g. a Newton re-closure failed)."""
