"""Regression checks: analyse mechanisms and compare with their ``expected`` blocks.

A mechanism file may carry an ``expected`` block (see ``docs/file-format.md``).
:func:`check_file` loads and analyses one file and compares every key of that
block with the analysis; :func:`check_paths` does it for files and folders
(every ``*.yaml``/``*.yml`` inside, recursively, sorted) and gathers the
results in a :class:`CheckReport`, whose :attr:`~CheckReport.exit_status` is
what ``mobility check`` returns.

How each key is compared:

* ``dof``, ``pattern``, ``mobility``, ``redundant_constraints``, ``idle_dof``,
  ``gruebler_kutzbach``: equality with the :class:`~mobility.core.result.Result`;
* ``translations``: as subspaces (same dimension, and stacking the expected
  and found bases adds no dimension), with the rank policy of
  :mod:`mobility.core.tolerance`; an empty list means "no translation" (a
  zero or dependent direction is refused when the file is read: an input
  error, exit status 2, not a failed check);
* ``full_cycle_dof``, ``full_cycle_mobility``, ``finite_verdict``: equality
  with :func:`mobility.finite.finite_mobility`, computed only when one of them
  is present (it costs more than the screw analysis);
* ``actuation``: equality with the verdict of
  :func:`mobility.actuation.check_actuation` for the joints marked
  ``actuated: true`` (none marked: a mismatch that says so).

Other modules may add keys to :data:`COMPARATORS`.  A key of the block that no
comparator knows is reported as a mismatch, never silently passed.

Each checked file ends in one of four statuses: ``"pass"``, ``"fail"`` (a key
disagrees), ``"missing"`` (no ``expected`` block: not a pass) and ``"error"``
(the file cannot be read or analysed; its one-line message is kept).

A YAML document of another kind (a flexure document, see
``docs/actuation.md``) is checked by a function given in ``others``
(:data:`OtherDocument`); ``mobility check`` gives the one for flexures,
:func:`mobility.testing.flexure_check.flexure_document`.
Paths and messages are reported as text
(:func:`mobility.io.files.printable_name`): the bytes of a file name that
are not UTF-8 appear as ``\\xNN``.

Examples
--------
>>> import mobility
>>> m = mobility.loads('''
... name: slide
... ground: g
... end_effector: s
... joints: [{name: p, type: P, links: [g, s], axis: [1, 0, 0]}]
... expected: {dof: 1, pattern: 1T, translations: [[2, 0, 0]], mobility: 1}
... ''')
>>> c = check_mechanism(m)
>>> c.status, [x.key for x in c.comparisons]
('pass', ['dof', 'pattern', 'translations', 'mobility'])
>>> check_mechanism(m.replace(expected=mobility.Expected(dof=2))).mismatches[0].describe()
'dof 1 (expected 2)'
"""

from __future__ import annotations

import dataclasses
import errno
import os
import stat
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any, Callable, Iterable, Sequence

import numpy as np

from ..core.analysis import analyze
from ..errors import MobilityError, RequestError, counted
from ..io.files import file_name, os_problem, printable_name
from ..io.limits import current_limits, require_size
from ..io.loader import load, read_mechanism
from ..io.yaml_source import Positions, parse_yaml, read_text
from ..core.expected import expected_basis_problem
from ..core.model import Mechanism, require_mechanism
from ..core.result import Result
from ..core.screws import same_subspace
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, binary_scale, clean_numbers, require_tolerance

__all__ = [
    "Comparison",
    "CheckResult",
    "CheckReport",
    "COMPARATORS",
    "STATUSES",
    "OtherDocument",
    "check_mechanism",
    "check_file",
    "check_paths",
    "mechanism_files",
    "compare_translations",
    "compare_verdict",
]

STATUSES = ("pass", "fail", "missing", "error")
"""The statuses of a checked file, in the order the summary lists them."""

MECHANISM_SUFFIXES = (".yaml", ".yml")


@dataclass(frozen=True)
class Comparison:
    """One key of an ``expected`` block compared with what the analysis found.

    Attributes
    ----------
    key : str
    expected : Any
        The value in the file (translations as a list of 3-lists).
    actual : Any
        What was found, in the same form (``None`` when nothing could be found).
    ok : bool
    note : str
        Why a comparison failed when the values alone do not say it.
    """

    key: str
    expected: Any
    actual: Any
    ok: bool
    note: str = ""

    def describe(self) -> str:
        """``key actual (expected value)``, e.g. ``'dof 4 (expected 3)'``."""
        if self.note:
            return f"{self.key}: {self.note}"
        return f"{self.key} {_short(self.actual)} (expected {_short(self.expected)})"

    def to_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {"key": self.key, "expected": clean_numbers(self.expected), "actual": clean_numbers(self.actual), "ok": self.ok, "note": self.note}


@dataclass(frozen=True, eq=False)
class CheckResult:
    """The check of one mechanism (usually one file).

    Attributes
    ----------
    path : str
        The file as given (empty for a mechanism built in code).
    name : str
        The mechanism's name (empty when the file could not be read).
    status : str
        ``"pass"``, ``"fail"``, ``"missing"`` or ``"error"``.
    comparisons : tuple of Comparison
        One per key of the ``expected`` block, in the block's order.
    result : Result or None
        The analysis (``None`` on error).
    error : str
        The one-line error message, when ``status == "error"``.
    internal : bool
        True when the error is a defect of :mod:`mobility` rather than bad
        input (exit status 3 instead of 2).
    kind : str
        What the file holds: ``"mechanism"``, or the kind of another
        document (``"flexure"``), whose analysis is not a
        :class:`~mobility.core.result.Result` (``result`` is then ``None``).
    found : dict or None
        What the check of another kind of document found (a flexure's
        ``dof``, ``pattern``, ``translations``...); for a mechanism
        :meth:`found_values` reads it from ``result``.
    """

    path: str
    name: str
    status: str
    comparisons: tuple[Comparison, ...] = ()
    result: Result | None = None
    error: str = ""
    internal: bool = False
    kind: str = "mechanism"
    found: dict[str, Any] | None = None

    def found_values(self) -> dict[str, Any] | None:
        """``found``, or for a mechanism the numbers of its ``result`` (``None`` on error)."""
        r = self.result
        if self.found is not None or r is None:
            return self.found
        return {
            "dof": r.dof,
            "pattern": r.pattern,
            "mobility": r.mobility,
            "gruebler_kutzbach": r.gruebler_kutzbach,
            "redundant_constraints": r.redundant_constraints,
            "idle_dof": r.idle_dof,
            "translations": clean_numbers(r.translations),
        }

    @property
    def ok(self) -> bool:
        """True when the file passed."""
        return self.status == "pass"

    @property
    def mismatches(self) -> tuple[Comparison, ...]:
        """The comparisons that failed."""
        return tuple(c for c in self.comparisons if not c.ok)

    @property
    def message(self) -> str:
        """One line saying why the file did not pass (empty when it passed)."""
        if self.status == "fail":
            return "; ".join(c.describe() for c in self.mismatches)
        if self.status == "missing":
            return "no expected block"
        if self.status == "error":
            return self.error
        return ""

    def to_dict(self) -> dict[str, Any]:
        """JSON form (one entry of ``mobility check --json``)."""
        return {
            "path": self.path,
            "name": self.name,
            "kind": self.kind,
            "status": self.status,
            "message": self.message,
            "found": self.found_values(),
            "comparisons": [c.to_dict() for c in self.comparisons],
        }


@dataclass(frozen=True, eq=False)
class CheckReport:
    """The checks of several files, with the exit status of ``mobility check``.

    Attributes
    ----------
    results : tuple of CheckResult
        In the order the files were given (folders expanded, sorted).
    """

    results: tuple[CheckResult, ...]

    def count(self, status: str) -> int:
        """Number of files with ``status``."""
        return sum(r.status == status for r in self.results)

    @property
    def ok(self) -> bool:
        """True when every file passed (and there was at least one)."""
        return bool(self.results) and all(r.ok for r in self.results)

    @property
    def exit_status(self) -> int:
        """3 if a check met an internal error, else 2 if any input was bad, else 1
        if any file failed or had no ``expected`` block, else 0."""
        if any(r.status == "error" and r.internal for r in self.results):
            return 3
        if any(r.status == "error" for r in self.results):
            return 2
        return 0 if self.ok else 1

    def summary(self) -> str:
        """``'40 passed, 1 failed, 0 without expected block, 0 errors'``."""
        errors = self.count("error")
        return (
            f"{self.count('pass')} passed, {self.count('fail')} failed, "
            f"{self.count('missing')} without expected block, {counted(errors, 'error')}"
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON form of ``mobility check --json``."""
        return {
            "results": [r.to_dict() for r in self.results],
            "summary": {s: self.count(s) for s in STATUSES} | {"total": len(self.results)},
            "exit_status": self.exit_status,
        }


class _Subject:
    """A mechanism with its analyses computed on demand (the finite one is costly)."""

    def __init__(self, mechanism: Mechanism, tol: Tolerance) -> None:
        self.mechanism = mechanism
        self.tol = tol

    @cached_property
    def result(self) -> Result:
        return analyze(self.mechanism, tol=self.tol)

    @cached_property
    def finite(self) -> dict[str, Any]:
        from ..finite.full_cycle import finite_mobility  # imported on demand: it pulls in scipy.optimize

        require_size(self.mechanism, "max_finite_joints", "the full-cycle expectations", self.mechanism.source or "<mechanism>")
        return finite_mobility(self.mechanism, tol=self.tol).expected_values()


Comparator = Callable[[_Subject, Any], Comparison]
"""``comparator(subject, expected_value) -> Comparison``."""


def _equal(key: str, attribute: str | None = None) -> Comparator:
    def compare(subject: _Subject, expected: Any) -> Comparison:
        actual = getattr(subject.result, attribute or key)
        return Comparison(key, expected, actual, actual == expected)

    return compare


def _finite(key: str) -> Comparator:
    def compare(subject: _Subject, expected: Any) -> Comparison:
        actual = subject.finite[key]
        return Comparison(key, expected, actual, actual == expected)

    return compare


def compare_translations(found: np.ndarray, expected: Any, tol: Tolerance) -> Comparison:
    """An expected translation basis (rows) compared with the ``found`` one as subspaces.

    Raises
    ------
    RequestError
        When ``expected`` is not a basis (a zero row, or one dependent on
        those before it): an input error, not a failed check.  A file's
        ``expected`` block is refused for it when read.

    Examples
    --------
    >>> compare_translations(np.array([[0.0, 0.0, 1.0]]), [[0, 0, 5]], DEFAULT_TOLERANCE).ok
    True
    >>> compare_translations(np.zeros((0, 3)), [[1, 0, 0]], DEFAULT_TOLERANCE).describe()
    'translations: found the span of [], expected the span of [[1, 0, 0]]'
    >>> compare_translations(np.zeros((0, 3)), [[0, 0, 0]], DEFAULT_TOLERANCE)
    Traceback (most recent call last):
    mobility.errors.RequestError: compare_translations: expected[0]: expected a non-zero direction, got [0, 0, 0]
    """
    rows = np.asarray(expected, dtype=float).reshape(-1, 3)
    problem = expected_basis_problem([(float(x), float(y), float(z)) for x, y, z in rows.tolist()])
    if problem is not None:
        raise RequestError(problem[1], caller="compare_translations", argument=f"expected[{problem[0]}]")
    actual = clean_numbers(found)
    scaled = rows * np.array([binary_scale(row) for row in rows]).reshape(-1, 1)  # before squaring: any finite vector has a direction
    unit = scaled / np.linalg.norm(scaled, axis=1)[:, None]
    if len(unit) == 0 or len(found) == 0:
        ok = len(found) == 0 and len(unit) == 0
    else:
        ok = same_subspace(unit.T, found.T, tol)
    note = "" if ok else f"found the span of {_short(actual)}, expected the span of {_short(rows.tolist())}"
    return Comparison("translations", rows.tolist(), actual, ok, note)


def compare_verdict(key: str, found: Any, expected: Any, inputs: Sequence[str]) -> Comparison:
    """An expected actuation verdict compared with the one ``found`` for ``inputs`` (none marked: a mismatch that says so).

    Examples
    --------
    >>> compare_verdict("actuation", "valid", "valid", ["P1", "P2"]).ok
    True
    >>> compare_verdict("actuation", "actuation-singular", "valid", []).describe()
    'actuation: no input is marked actuated (actuated: true), so there is no verdict to compare'
    """
    if not inputs:
        return Comparison(key, expected, None, False, "no input is marked actuated (actuated: true), so there is no verdict to compare")
    return Comparison(key, expected, found, found == expected)


def _translations(subject: _Subject, expected: Any) -> Comparison:
    return compare_translations(subject.result.translations, expected, subject.tol)


def _actuation(subject: _Subject, expected: Any) -> Comparison:
    from ..actuation import check_actuation  # imported on demand: most files expect no actuation verdict

    check = check_actuation(subject.mechanism, tol=subject.tol)
    return compare_verdict("actuation", check.verdict, expected, [i.name for i in check.inputs])


COMPARATORS: dict[str, Comparator] = {
    "dof": _equal("dof"),
    "pattern": _equal("pattern"),
    "translations": _translations,
    "mobility": _equal("mobility"),
    "redundant_constraints": _equal("redundant_constraints"),
    "idle_dof": _equal("idle_dof"),
    "gruebler_kutzbach": _equal("gruebler_kutzbach"),
    "full_cycle_dof": _finite("full_cycle_dof"),
    "full_cycle_mobility": _finite("full_cycle_mobility"),
    "finite_verdict": _finite("finite_verdict"),
    "actuation": _actuation,
}
"""How each ``expected`` key is compared (other modules may register more)."""


def check_mechanism(mechanism: Mechanism, *, tol: Tolerance = DEFAULT_TOLERANCE, path: str = "") -> CheckResult:
    """Analyse ``mechanism`` and compare it with its ``expected`` block.

    Parameters
    ----------
    mechanism : Mechanism
    tol : Tolerance
        Rank policy of the analysis and of the subspace comparisons.
    path : str
        Where the mechanism came from, for the report.

    Returns
    -------
    CheckResult
        Status ``"missing"`` when the mechanism has no ``expected`` block
        (it is still analysed).

    Raises
    ------
    RequestError
        When ``mechanism`` is not a :class:`~mobility.core.model.Mechanism`
        or ``tol`` not a :class:`~mobility.core.tolerance.Tolerance`.
    MobilityError
        When the analysis itself fails (:func:`check_file` turns it into an
        ``"error"`` result).
    """
    mechanism = require_mechanism(mechanism, "check_mechanism")
    tol = require_tolerance(tol, "check_mechanism")
    subject = _Subject(mechanism, tol)
    expected = mechanism.expected
    items = expected.items() if expected is not None else []
    if not items:
        return CheckResult(path, mechanism.name, "missing", (), subject.result)
    comparisons = []
    for key, value in items:
        comparator = COMPARATORS.get(key)
        if comparator is None:
            comparisons.append(Comparison(key, value, None, False, "no comparator knows this key"))
        else:
            comparisons.append(comparator(subject, value))
    status = "pass" if all(c.ok for c in comparisons) else "fail"
    return CheckResult(path, mechanism.name, status, tuple(comparisons), subject.result)


OtherDocument = Callable[[str, Any, Positions, Tolerance], "CheckResult | None"]
"""``check(path, data, positions, tol)``: the check of a YAML document that is not a mechanism file
(``data`` and ``positions``, the parsed document from :func:`~mobility.io.yaml_source.parse_yaml`, say
which kind it is and where each key stands), or ``None`` when ``data`` is not of its kind.  It may raise
:class:`~mobility.errors.MobilityError` for a bad document (reported as the file's error).
:func:`mobility.testing.flexure_check.flexure_document` is the one for flexure documents."""


def check_file(path: str | Path, *, tol: Tolerance = DEFAULT_TOLERANCE, others: Sequence[OtherDocument] = ()) -> CheckResult:
    """Load, analyse and check one mechanism file; never raises on a bad file.

    A YAML file is read and parsed once; each of ``others`` is then offered
    the parsed document before it is read as a mechanism.  Any other file
    (a robot description) is loaded by :func:`mobility.io.loader.load`.

    Parameters
    ----------
    path : str or Path
    tol : Tolerance
    others : sequence of OtherDocument
        Checks of other kinds of YAML documents, tried in turn; the first
        that takes the document checks it.

    Returns
    -------
    CheckResult
        Status ``"error"`` with the one-line message (file, line, key) when
        the file cannot be read or analysed.

    Raises
    ------
    RequestError
        When ``path`` is not a file name (a ``str`` or ``os.PathLike``
        without a NUL character): no file is named, so no result can be.

    Examples
    --------
    >>> check_file("no/such/file.yaml").message
    'no/such/file.yaml: no such file'
    """
    file_name(path, "check_file")
    name = printable_name(path)
    try:
        if Path(path).suffix.lower() not in MECHANISM_SUFFIXES:
            return check_mechanism(load(path), tol=tol, path=name)
        limits = current_limits()
        data, positions = parse_yaml(read_text(path, limits), str(path), limits)
        for other in others:
            found = other(str(path), data, positions, tol)
            if found is not None:
                return dataclasses.replace(found, path=name, name=printable_name(found.name))
        return check_mechanism(read_mechanism(data, positions, str(path), limits=limits), tol=tol, path=name)
    except MobilityError as exc:
        return CheckResult(name, "", "error", error=printable_name(str(exc)))
    except Exception as exc:  # a defect of the package: report it, keep checking the other files
        return CheckResult(name, "", "error", error=printable_name(f"internal error ({type(exc).__name__}: {exc})"), internal=True)


def _path_problem(raw: str | Path) -> tuple[int, str]:
    """The file type bits of ``raw`` and, when it cannot be looked up, why (else ``""``)."""
    try:
        return os.stat(raw).st_mode, ""
    except FileNotFoundError:
        return 0, "no such file or folder"
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            return 0, f"is {os_problem(exc)}, expected a mechanism file or folder"
        return 0, f"cannot look it up: {os_problem(exc)}"
    except ValueError as exc:  # a NUL in a name given from Python
        return 0, f"cannot look it up: {exc}"


def mechanism_files(paths: Iterable[str | Path]) -> list[tuple[str, Path | None, str]]:
    """Expand ``paths`` into mechanism files.

    Returns
    -------
    list of (shown, path, problem)
        ``shown`` is the name to report, as text
        (:func:`~mobility.io.files.printable_name`); ``path`` is ``None`` when
        ``problem`` says why nothing can be checked there (no such path, a
        symbolic link loop, an empty folder).  Folders give every
        ``*.yaml``/``*.yml`` file inside, recursively, sorted by path.
    """
    out: list[tuple[str, Path | None, str]] = []
    for raw in paths:
        p = Path(raw)
        shown = printable_name(raw)
        mode, problem = _path_problem(raw)
        if problem:
            out.append((shown, None, f"{shown}: {problem}"))
        elif stat.S_ISDIR(mode):
            found = sorted(f for f in p.rglob("*") if f.suffix.lower() in MECHANISM_SUFFIXES and not f.is_dir())  # a pipe among them is reported on its row, not skipped
            if not found:
                out.append((shown, None, f"{shown}: no *.yaml mechanism file in this folder"))
            out.extend((printable_name(f), f, "") for f in found)
        else:
            out.append((shown, p, ""))
    return out


def check_paths(paths: Sequence[str | Path], *, tol: Tolerance = DEFAULT_TOLERANCE, others: Sequence[OtherDocument] = ()) -> CheckReport:
    """Check every mechanism file given or found in the folders given (``others``: as for :func:`check_file`).

    Raises
    ------
    RequestError
        When ``paths`` is not a list (or tuple) of file names; a bare name
        is refused, not read as a list of its characters.

    Examples
    --------
    >>> report = check_paths(["no/such/folder"])
    >>> report.exit_status, report.results[0].message
    (2, 'no/such/folder: no such file or folder')
    >>> check_paths("mechanisms")
    Traceback (most recent call last):
    ...
    mobility.errors.RequestError: check_paths: expected a list of file or folder names, got str (one name is written [name])
    """
    if not isinstance(paths, (list, tuple)):
        one = " (one name is written [name])" if isinstance(paths, (str, os.PathLike)) else ""
        raise RequestError(caller="check_paths", expected="a list of file or folder names", got=f"{type(paths).__name__}{one}")
    for k, path in enumerate(paths):
        file_name(path, f"check_paths: paths[{k}]")
    results = []
    for shown, path, problem in mechanism_files(paths):
        if path is None:
            results.append(CheckResult(shown, "", "error", error=problem))
        else:
            results.append(check_file(path, tol=tol, others=others))
    return CheckReport(tuple(results))


def _short(value: Any) -> str:
    """A compact text form: vectors with 6 significant digits, round-off shown as 0 (:func:`~mobility.core.tolerance.clean_numbers`)."""
    value = clean_numbers(value)
    if isinstance(value, list):
        return "[" + ", ".join(_short(v) for v in value) + "]"
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)
