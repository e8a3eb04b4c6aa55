"""The error hierarchy: every error class of the package is defined here.

Every error the package raises on purpose derives from :class:`MobilityError`
(the command line prints it on one line and exits with status 2) and from the
builtin it refines (``ValueError``, ``ImportError``, ``ArithmeticError``), so
code written against the builtins keeps working.

Examples
--------
>>> err = MechanismFileError("joints[2].axis", "expected 3 numbers, got 2",
...                          file="arm.yaml", line=7)
>>> str(err)
'arm.yaml:7: joints[2].axis: expected 3 numbers, got 2'
>>> isinstance(err, ValueError)
True
>>> str(MissingExtraError("plotting", "matplotlib", "plot"))
"plotting needs matplotlib, which is not installed: pip install 'mechanism-mobility[plot]'"
"""

from __future__ import annotations

import re
import sys
import unicodedata
from typing import Iterable

_BIDI = "\u202a-\u202e\u2066-\u2069"
"""Characters that reorder the text around them on a terminal (bidirectional overrides, "Trojan source")."""
_UNSHOWN = {"Cc": "a control character", "Cf": "a format character (invisible, or reordering the text)", "Cs": "a lone surrogate",
             "Zl": "a line separator", "Zp": "a paragraph separator"}
"""The Unicode categories of the characters a message never shows raw and a name never holds, and what each is called."""
TERMINAL_CONTROL = re.compile(f"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x84\x86-\x9f{_BIDI}]")
"""Characters a terminal obeys rather than shows: C0 and C1 controls but tab and line breaks (LF, CR, NEL), DEL, bidirectional overrides."""

__all__ = ["MobilityError", "MechanismError", "MechanismFileError", "MechanismCheckFailed", "RequestError", "SynthesisError",
           "PlotFormatError", "AnalysisError", "HalfTurnError", "MissingExtraError", "PlottingUnavailableError", "name_list",
           "counted", "did_you_mean", "one_line", "clipped", "shown_argument", "control_character_problem", "name_problem",
           "TERMINAL_CONTROL", "DISTRIBUTION"]

DISTRIBUTION = "mechanism-mobility"
"""The name the package is installed by (``mobility`` on the package index is another project); it is imported and run as ``mobility``."""


def counted(n: int, word: str, plural: str = "s", *, grouped: bool = False) -> str:
    """``n`` and ``word``, in the plural unless ``n`` is 1: the count of a message or a report (``grouped``: thousands separated by commas).

    Examples
    --------
    >>> counted(1, "pose"), counted(8, "combination"), counted(5, "constraint wrench", "es"), counted(0, "direction")
    ('1 pose', '8 combinations', '5 constraint wrenches', '0 directions')
    >>> counted(12000, "pose", grouped=True), counted(1, "pose", grouped=True)
    ('12,000 poses', '1 pose')
    """
    return f"{n:,} {word}{'' if n == 1 else plural}" if grouped else f"{n} {word}{'' if n == 1 else plural}"


def name_list(names: Iterable[object], *, most: int = 12, empty: str = "(none)") -> str:
    """Names for a one-line message: the first ``most``, then how many there are in all.

    Examples
    --------
    >>> name_list(["A", "B", "C"])
    'A, B, C'
    >>> name_list([f"J{i}" for i in range(100)], most=3)
    'J0, J1, J2, ... (100 in all)'
    >>> name_list([])
    '(none)'
    """
    items = [str(n) for n in names]
    if not items:
        return empty
    shown = ", ".join(items[:most])
    return shown if len(items) <= most else f"{shown}, ... ({len(items)} in all)"


def did_you_mean(name: object, names: Iterable[object]) -> str:
    """`` (did you mean 'x'?)`` naming the closest of ``names`` to ``name`` (``difflib``), or ``""`` when none is close.

    Examples
    --------
    >>> did_you_mean("crnk", ["crank", "rocker"]), did_you_mean("zz", ["crank"])
    (" (did you mean 'crank'?)", '')
    """
    import difflib  # only when a name is wrong: not at start-up

    close = difflib.get_close_matches(str(name), [str(n) for n in names], n=1)
    return f" (did you mean {clipped(close[0])!r}?)" if close else ""


def one_line(text: str) -> str:
    """``text`` safe to print as one terminal line: line breaks, control and format characters shown escaped.

    An escape sequence a user typed must reach the terminal as text, not as a
    command, and U+2028, U+202E or U+200E must show as what they are.

    Examples
    --------
    >>> one_line("bad.yaml: two\\nlines and \\x1b[31mred")
    'bad.yaml: two\\\\nlines and \\\\x1b[31mred'
    >>> one_line("wrote bad\\udcff.csv")   # a file name's undecodable byte: printable in any encoding
    'wrote bad\\\\xff.csv'
    >>> one_line("a\\u2028b\\u200e.yaml")
    'a\\\\u2028b\\\\u200e.yaml'
    """
    if text.isprintable():  # the common case: no character of _UNSHOWN (nor any other Python would not print)
        return text
    return "".join(_escaped(char) if unicodedata.category(char) in _UNSHOWN else char for char in text)


def _escaped(char: str) -> str:
    """A character of :func:`one_line` shown escaped: a byte no encoding decoded (``surrogateescape``) as ``\\xNN``, the rest as Python writes it."""
    if "\udc80" <= char <= "\udcff":
        return f"\\x{ord(char) - 0xDC00:02x}"
    return repr(char)[1:-1]


def name_problem(text: str, what: str = "a name") -> str | None:
    """What is wrong with the name ``text`` if it holds a character no name may hold, else None.

    The one rule for every name a user chooses, in every format: no control
    or format character, no line or paragraph separator, no lone surrogate
    (it would break a table's line, hide itself or reorder the text).

    Examples
    --------
    >>> name_problem("left knee") is None, name_problem("连杆") is None
    (True, True)
    >>> print(name_problem("knee\\r", "a joint name"))
    a line break '\\r' (U+000D) is not allowed in a joint name
    >>> print(name_problem("a\\u202eb"))
    a format character (invisible, or reordering the text) '\\u202e' (U+202E) is not allowed in a name
    """
    if text.isprintable():
        return None
    for char in text:
        kind = _UNSHOWN.get(unicodedata.category(char))
        if kind is not None:
            if char == "\t":
                kind = "a tab"
            elif char in "\n\r\x85":
                kind = "a line break"
            return f"{kind} {char!r} (U+{ord(char):04X}) is not allowed in {what}"
    return None


def control_character_problem(text: str, where: str, *, also: re.Pattern[str] | None = None) -> str | None:
    """What is wrong with ``text`` if it holds a character a terminal obeys rather than shows, else None.

    Tab and line breaks are allowed, the rest of ``TERMINAL_CONTROL`` not; the
    file readers check every value a message may quote, ``also`` adding a
    format's own forbidden characters (YAML's non-printable set).

    Examples
    --------
    >>> control_character_problem("link one", "a value") is None
    True
    >>> print(control_character_problem("a\\x1b[2J", "a value"))
    control character '\\x1b' (code 27) is not allowed in a value
    """
    bad = TERMINAL_CONTROL.search(text) or (also.search(text) if also is not None else None)
    if bad is None:
        return None
    return f"control character {bad.group()!r} (code {ord(bad.group())}) is not allowed in {where}"


def shown_argument(value: object) -> str:
    """An argument as a message quotes it: its ``repr``, clipped, on one line (the ``repr`` of an array spans lines).

    Examples
    --------
    >>> print(shown_argument("a" * 100), shown_argument([[1.0, 0.0], [0.0, 1.0]]))
    'aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa... [[1.0, 0.0], [0.0, 1.0]]
    >>> shown_argument(10**5000)
    'an integer of more than 4,300 digits'
    """
    try:
        text = repr(value)
    except ValueError:  # an int of more digits than Python writes (sys.get_int_max_str_digits)
        text = f"an integer of more than {sys.get_int_max_str_digits():,} digits"
    return one_line(clipped(text))


def clipped(text: object, most: int = 40) -> str:
    """``text`` shortened for a message: at most ``most`` characters, the cut marked by ``...``.

    Examples
    --------
    >>> clipped("shoulder")
    'shoulder'
    >>> clipped("A" * 1000)
    'AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA...'
    """
    text = str(text)
    return text if len(text) <= most else text[: max(most - 3, 0)] + "..."


class MobilityError(Exception):
    """Base class of every error raised on purpose by :mod:`mobility`.

    Every error pickles and copies with its message and attributes, so one
    raised in a worker process reaches the caller as it was raised.

    Examples
    --------
    >>> import copy, pickle
    >>> err = pickle.loads(pickle.dumps(MechanismFileError("joints[0].axis", "expected 3 numbers", file="a.yaml", line=3)))
    >>> str(err), err.key, err.line, str(copy.copy(err)) == str(err)
    ('a.yaml:3: joints[0].axis: expected 3 numbers', 'joints[0].axis', 3, True)
    """

    def __reduce__(self) -> tuple:
        # Exception's own reduction calls the class with ``self.args`` (the message), which a class whose
        # __init__ takes other arguments (MechanismError(key, message)) cannot take: rebuild without __init__.
        return (_rebuilt, (type(self), self.args, dict(self.__dict__)))


def _rebuilt(cls: type, args: tuple, state: dict) -> MobilityError:
    """An error of class ``cls`` with ``args`` and attributes ``state``, without calling its ``__init__`` (the pickle of :class:`MobilityError`)."""
    error = cls.__new__(cls, *args)
    error.args = args
    error.__dict__.update(state)
    return error


class MechanismError(MobilityError, ValueError):
    """A mechanism description is invalid.

    ``key`` is the path of the offending entry (``"joints[3].axis"``; empty for
    the whole document), ``message`` what is wrong and what was expected.

    Examples
    --------
    >>> str(MechanismError("joints[3].axis", "expected 3 numbers"))
    'joints[3].axis: expected 3 numbers'
    """

    def __init__(self, key: str, message: str) -> None:
        self.key = key
        self.message = message
        super().__init__(one_line(self._format()))  # a key may quote a name as written ("pi\n")

    def _format(self) -> str:
        return f"{self.key}: {self.message}" if self.key else self.message


class MechanismFileError(MechanismError):
    """A mechanism file is invalid; the message names file, line and key.

    ``file`` is the path as the user gave it, ``line`` 1-based (``None`` when
    unknown); see the module's example.
    """

    def __init__(self, key: str, message: str, *, file: str = "<string>", line: int | None = None) -> None:
        self.file = file
        self.line = line
        super().__init__(key, message)

    def _format(self) -> str:
        where = f"{self.file}:{self.line}" if self.line is not None else self.file
        return f"{where}: {super()._format()}"


class MechanismCheckFailed(MobilityError, AssertionError):
    """A mechanism file did not pass its regression check (the message says why)."""


class RequestError(MobilityError, ValueError):
    """An argument of a function, or an option of the command line, is out of its range.

    The message is built from the fields: ``caller: argument: expected
    EXPECTED, got GOT``, empty parts left out, and ``problem`` (in words) where
    the trouble is not a value out of range, or after a semicolon as advice.
    ``got`` is shown as given (:func:`shown_argument`, or a type name).

    Examples
    --------
    >>> err = RequestError(caller="plot_mechanism", argument="title", expected="a str or None", got="int")
    >>> str(err), err.argument, err.got
    ('plot_mechanism: title: expected a str or None, got int', 'title', 'int')
    >>> str(RequestError("choose one output format", argument="--json and --format csv"))
    '--json and --format csv: choose one output format'
    """

    def __init__(self, problem: str = "", *, caller: str = "", argument: str = "", expected: str = "", got: object = "") -> None:
        got = str(got)  # a count, say
        self.problem, self.caller, self.argument, self.expected, self.got = problem, caller, argument, expected, got
        said = f"expected {expected}" + (f", got {got}" if got else "") if expected else ""
        super().__init__(": ".join(part for part in (caller, argument, "; ".join(p for p in (said, problem) if p)) if part))


class SynthesisError(RequestError):
    """A motion pattern or a synthesis request is invalid."""


class PlotFormatError(RequestError):
    """An output file name whose type cannot be written."""


class AnalysisError(MobilityError):
    """An analysis could not be carried out (e.g. a decomposition did not converge)."""


class HalfTurnError(MobilityError, ArithmeticError):
    """A half-turn (``θ = π``) has no finite quasi-vector: ``2 tan(θ/2)`` is infinite.

    Use :class:`~mobility.core.finite_screws.FiniteScrew` (homogeneous form),
    which represents half-turns exactly.
    """


class MissingExtraError(MobilityError, ImportError):
    """A feature needs an optional extra that is not installed.

    ``feature`` was asked for (``"plotting"``), ``package`` is missing, the
    ``extra`` of :data:`DISTRIBUTION` installs it; ``detail`` says more about
    the import failure, left out when it only says ``package`` is missing.
    """

    def __init__(self, feature: str, package: str, extra: str, detail: str = "") -> None:
        self.feature = feature
        self.package = package
        self.extra = extra
        if detail.startswith(f"No module named '{package.split('[')[0]}"):
            detail = ""
        more = f" ({detail})" if detail else ""
        super().__init__(f"{feature} needs {package}, which is not installed{more}: pip install '{DISTRIBUTION}[{extra}]'")


class PlottingUnavailableError(MissingExtraError):
    """matplotlib is not installed; the message says how to install it."""

    def __init__(self, detail: str = "") -> None:
        super().__init__("plotting", "matplotlib", "plot", detail)
